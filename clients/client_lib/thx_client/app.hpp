#pragma once
// ClientApp: the scaffolding every hapticd client repeats, once. It installs the stop signals,
// opens LCM (an unusable URL is an error that names it and the usual fix), makes the Client,
// waits for the server's hello, and runs a paced loop on the same rt::Pacer as the servo
// (grid deadlines, realign after an overrun, no catch-up burst). A complete client:
//
//   thx::client::ClientApp app("visual");  // or ClientApp(AppOptions{...}), ClientApp(id, url, timeout)
//   app.client().subscribe(thx_msgs::Stream::DeviceState, 60.0);
//   app.waitForServer();
//   app.runPaced(60.0, [&](const thx::rt::TickTiming&) {
//     if (auto s = app.client().latestDeviceState()) draw(*s);
//     return true;  // false ends the loop
//   });
//
// Errors a user can fix (no LCM, no server) are thx::Error; main catches them once. The loop and
// the waits end early when SIGINT/SIGTERM arrives (stopRequested()).
//
// Server commands wait for their reply: app.loadScene("vvalley") returns the accepted reply (its
// tick: the first servo tick on the new scene) or throws CommandRefused with hapticd's reason.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "base/error.hpp"
#include "rt/pacer.hpp"
#include "thx_client/client.hpp"
#include "thx_client/commands.hpp"
#include "thx_client/scene_check.hpp"
#include "thx_msgs/lcm_open.hpp"
#include "thx_msgs/protocol.hpp"

namespace lcm {
class LCM;
}

namespace thx::client {

using thx_msgs::openLcm;  // thx_msgs/lcm_open.hpp: an unusable URL is a thx::Error naming it and the fix

struct AppOptions {
  std::string client_id;                 // protocol rules: 1-32 of [A-Za-z0-9_-]
  std::string lcm_url = thx_msgs::kDefaultLcmUrl;
  double connect_timeout_s = 10.0;       // waitForServer() gives up after this
  ClientOptions client;                  // resend, silence, heartbeat, the device followed (client_id
                                         // set from above)
  // The scene this client loaded: waitForServer() compares it with the server's hello and throws
  // when they differ (unless allow_different_scene: then a warning on stderr). Unset: no check.
  std::optional<SceneIdentity> scene;
  bool allow_different_scene = false;
};

struct LoopStats {
  std::int64_t steps = 0;
  std::int64_t missed = 0;  // grid points skipped after overruns (the pacer's realignment)
};

class ClientApp {
 public:
  explicit ClientApp(AppOptions options);
  explicit ClientApp(std::string client_id, std::string lcm_url = thx_msgs::kDefaultLcmUrl, double connect_timeout_s = 10.0);
  ~ClientApp();
  ClientApp(const ClientApp&) = delete;
  ClientApp& operator=(const ClientApp&) = delete;

  lcm::LCM& lcm() { return *lcm_; }
  Client& client() { return *client_; }
  const AppOptions& options() const { return options_; }
  bool stopRequested() const;

  // Polls until hapticd's hello arrives and returns it. Throws thx::Error (Io) naming the URL
  // after connect_timeout_s, or (Config) naming both scenes and both fingerprints when the
  // server runs another scene than options().scene, or (Config) naming the index and the
  // hello's device names when it has no device options().client.device (deviceProblem);
  // returns nullopt when a stop signal came first.
  std::optional<thx_msgs::hello_t> waitForServer();
  // Polls until done() holds (true), the timeout passes or a stop signal arrives (false).
  bool pollUntil(const std::function<bool()>& done, double timeout_s);
  // Calls step() at rate_hz on the monotonic clock, handling LCM traffic before each step, until
  // step returns false, max_steps steps ran (< 0: no limit) or a stop signal arrives.
  LoopStats runPaced(double rate_hz, const std::function<bool(const rt::TickTiming&)>& step,
                     std::int64_t max_steps = -1);

  // Sends a server command (Client::sendCommand) and polls until its reply. Returns the accepted
  // reply (reply.tick: the first servo tick it took effect on); nullopt when a stop signal came
  // first. Throws, each a thx::Error naming the command:
  //  - CommandRefused with the server's reason (nothing changed on the server);
  //  - Io when no reply came within timeout_s (the command may still take effect: it is not resent);
  //  - Config when the argument cannot go out (commandArgumentProblem), or the server's last hello
  //    shows a protocol_version older than the command's (protocolVersionFor), before sending.
  std::optional<thx_msgs::server_command_reply_t> command(std::int32_t action, const std::string& argument,
                                                          double timeout_s);
  // Clears the servo's latched fault (ACTION_RESET_FAULTS).
  std::optional<thx_msgs::server_command_reply_t> resetFaults(double timeout_s = 2.0);
  // Switches hapticd to scene NAME (ACTION_LOAD_SCENE; hapticd finds NAME.yaml in its scenes folder,
  // loads it, ramps its force down, swaps, ramps it up). A name that is not one (isValidSceneName) throws
  // SceneLookupError before anything is sent. Every client, this one too, then sees the change in
  // the hellos (Client::sceneChanges()). The timeout covers loading the scene's texture.
  std::optional<thx_msgs::server_command_reply_t> loadScene(const std::string& name, double timeout_s = 10.0);

 private:
  AppOptions options_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::unique_ptr<Client> client_;
};

}  // namespace thx::client
