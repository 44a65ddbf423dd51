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

}  // namespace thx::client
