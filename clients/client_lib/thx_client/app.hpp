#pragma once
// ClientApp: the scaffolding every hapticd client repeats, once. It installs the stop signals,
// opens LCM (an unusable URL is an error that names it and the usual fix), makes the Client,
// waits for the server's hello, and runs a paced loop on the same rt::Pacer as the servo
// (grid deadlines, realign after an overrun, no catch-up burst). A complete client:
//
//   thx::client::ClientApp app("visual");  // or ClientApp(AppOptions{...}), ClientApp(id, url, timeout)
//   app.client().subscribe("DEVICE_STATE", 60.0);
//   app.waitForServer();
//   app.runPaced(60.0, [&](const thx::rt::TickTiming&) {
//     if (auto s = app.client().latestDeviceState()) draw(*s);
//     return true;  // false ends the loop
//   });
//
// Errors a user can fix (no LCM, no server) are thx::Error; main catches them once. The loop and
// the waits end early when SIGINT/SIGTERM arrives (stopRequested()).
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "base/error.hpp"
#include "rt/pacer.hpp"
#include "thx_client/client.hpp"
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
  ClientOptions client;                  // resend, silence, heartbeat (client_id set from above)
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
  // server runs another scene than options().scene; returns nullopt when a stop signal came first.
  std::optional<thx_msgs::hello_t> waitForServer();
  // Polls until done() holds (true), the timeout passes or a stop signal arrives (false).
  bool pollUntil(const std::function<bool()>& done, double timeout_s);
  // Calls step() at rate_hz on the monotonic clock, handling LCM traffic before each step, until
  // step returns false, max_steps steps ran (< 0: no limit) or a stop signal arrives.
  LoopStats runPaced(double rate_hz, const std::function<bool(const rt::TickTiming&)>& step,
                     std::int64_t max_steps = -1);

 private:
  AppOptions options_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::unique_ptr<Client> client_;
};

}  // namespace thx::client
