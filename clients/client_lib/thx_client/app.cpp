#include "thx_client/app.hpp"

#include <cmath>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>

#include "thx_client/stop_signal.hpp"
#include "thx_msgs/lcm_open.hpp"

namespace thx::client {


ClientApp::ClientApp(AppOptions options) : options_(std::move(options)) {
  installStopSignals();
  lcm_ = thx_msgs::openLcm(options_.lcm_url);
  ClientOptions co = options_.client;
  co.client_id = options_.client_id;
  client_ = std::make_unique<Client>(*lcm_, std::move(co));
}

namespace {
AppOptions appOptions(std::string client_id, std::string lcm_url, double connect_timeout_s) {
  AppOptions o;
  o.client_id = std::move(client_id);
  o.lcm_url = std::move(lcm_url);
  o.connect_timeout_s = connect_timeout_s;
  return o;
}
}  // namespace

ClientApp::ClientApp(std::string client_id, std::string lcm_url, double connect_timeout_s)
    : ClientApp(appOptions(std::move(client_id), std::move(lcm_url), connect_timeout_s)) {}

// The Client goes first: it unsubscribes through the LCM instance.
ClientApp::~ClientApp() { client_.reset(); }

bool ClientApp::stopRequested() const { return thx::client::stopRequested(); }

bool ClientApp::pollUntil(const std::function<bool()>& done, double timeout_s) {
  const std::int64_t give_up = rt::monotonicNowNs() + std::int64_t(timeout_s * 1e9);
  while (!done()) {
    if (stopRequested() || rt::monotonicNowNs() > give_up) return false;
    // A stop signal interrupts LCM's wait (no SA_RESTART) and makes poll() fail: that is a stop.
    if (client_->poll(20) < 0 && !stopRequested())
      throw thx::Error(thx::Error::Kind::Io, "LCM receive failed on " + options_.lcm_url);
  }
  return true;
}

std::optional<thx_msgs::hello_t> ClientApp::waitForServer() {
  if (pollUntil([&] { return client_->latestHello().has_value(); }, options_.connect_timeout_s)) {
    const auto hello = client_->latestHello();
    if (options_.scene) {
      const SceneCheck check = checkScene(*hello, *options_.scene, options_.allow_different_scene);
      if (!check.ok()) throw thx::Error(thx::Error::Kind::Config, check.message);
      if (!check.message.empty()) std::fprintf(stderr, "warning: %s\n", check.message.c_str());
    }
    // A device the server does not have would deliver nothing: say so now, not after a timeout.
    if (std::string problem = deviceProblem(*hello, client_->device()); !problem.empty())
      throw thx::Error(thx::Error::Kind::Config, problem);
    return hello;
  }
  if (stopRequested()) return std::nullopt;
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%g", options_.connect_timeout_s);
  throw thx::Error(thx::Error::Kind::Io, "no hello from hapticd within " + std::string(seconds) + " s on " +
                                             options_.lcm_url + " (is hapticd running with LCM on this URL?)");
}

LoopStats ClientApp::runPaced(double rate_hz, const std::function<bool(const rt::TickTiming&)>& step,
                              std::int64_t max_steps) {
  rt::MonotonicClock clock;
  rt::Pacer pacer(clock, std::int64_t(std::llround(1e9 / rate_hz)));
  pacer.start();
  LoopStats stats;
  while (!stopRequested() && (max_steps < 0 || stats.steps < max_steps)) {
    const rt::TickTiming t = pacer.wait();
    client_->poll(0);
    ++stats.steps;
    if (!step(t)) break;
  }
  stats.missed = pacer.totalMissed();
  return stats;
}

std::optional<thx_msgs::server_command_reply_t> ClientApp::command(std::int32_t action, const std::string& argument,
                                                                 double timeout_s) {
  requireSendable(action, argument);
  const std::string what = describeCommand(action, argument);
  const auto hello = client_->latestHello();
  const std::string server = hello && !hello->server_name.empty() ? hello->server_name : std::string("hapticd");
  // An older server ignores what it does not know: say so now instead of after the timeout.
  if (hello && hello->protocol_version < protocolVersionFor(action))
    throw thx::Error(thx::Error::Kind::Config, "cannot send '" + what + "': " + server + " speaks protocol version " +
                                                   std::to_string(hello->protocol_version) + ", this command needs " +
                                                   std::to_string(protocolVersionFor(action)) + " (a newer hapticd)");
  const std::int64_t seq = client_->sendCommand(action, argument);
  std::optional<thx_msgs::server_command_reply_t> reply;
  if (!pollUntil([&] { return (reply = client_->takeCommandReply(seq)).has_value(); }, timeout_s)) {
    if (stopRequested()) return std::nullopt;
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%g", timeout_s);
    throw thx::Error(thx::Error::Kind::Io, "no reply from " + server + " to '" + what + "' within " + seconds +
                                               " s on " + options_.lcm_url +
                                               " (is hapticd running? the command may still take effect)");
  }
  if (!reply->accepted)
    throw CommandRefused(*reply, server + " refused to " + what + ": " +
                                     (reply->reason.empty() ? std::string("no reason given") : reply->reason));
  return reply;
}

std::optional<thx_msgs::server_command_reply_t> ClientApp::resetFaults(double timeout_s) {
  return command(thx_msgs::server_command_t::ACTION_RESET_FAULTS, "", timeout_s);
}

std::optional<thx_msgs::server_command_reply_t> ClientApp::loadScene(const std::string& name, double timeout_s) {
  requireValidSceneName(name);  // SceneLookupError, as a --scene NAME would be
  return command(thx_msgs::server_command_t::ACTION_LOAD_SCENE, name, timeout_s);
}

}  // namespace thx::client
