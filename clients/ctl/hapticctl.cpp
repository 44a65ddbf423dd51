// hapticctl: tells a running hapticd what to do, from a shell or a script (docs/hapticd.md):
// which scene it runs, switch it to another, clear its latched fault. A short program on the
// client kit (thx_client/app.hpp). `hapticctl --help`.
#include <unistd.h>

#include <cstdio>
#include <string>
#include <vector>

#include "base/cli_number.hpp"
#include "base/program_main.hpp"
#include "textures/texture_fingerprint.hpp"
#include "thx_client/app.hpp"
#include "thx_client/commands.hpp"
#include "thx_client/stop_signal.hpp"

namespace {

const char* kHelp = R"(usage: hapticctl [options] COMMAND

Tells a running hapticd what to do and prints its answer.

Commands:
  status                  the server, its device and the scene it runs (from its hello)
  load-scene NAME         switch to scene NAME (hapticd finds NAME.yaml in its --scenes-dir); the
                          force ramps down and up (0.2 s each way); a scene hapticd refuses is
                          printed with its reason and the old scene keeps running
  reset-faults            clear the latched device_state_t.fault_code

Options:
  --lcm-url URL           LCM transport (default )" THX_DEFAULT_LCM_URL R"()
  --client-id ID          1-32 of [A-Za-z0-9_-] (default hapticctl-<pid>)
  --timeout S             how long to wait for hapticd and for its answer (default 10)
  -h, --help              this text

Exit status: 0 done, 1 refused / no server / no answer, 2 bad command line.
)";

struct Options {
  std::string command, argument;
  std::string lcm_url = thx_msgs::kDefaultLcmUrl;
  std::string client_id = "hapticctl-" + std::to_string(::getpid());
  double timeout_s = 10.0;
};

Options parse(const std::vector<std::string>& args) {
  Options o;
  std::vector<std::string> words;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw thx::UsageError(a + " needs a value");
      return args[++i];
    };
    if (a == "--lcm-url") {
      o.lcm_url = value();
    } else if (a == "--client-id") {
      o.client_id = value();
    } else if (a == "--timeout") {
      o.timeout_s = thx::cli::parseNumber(a, value(), thx::cli::Range{0.1, 3600.0, false, "s"});
    } else if (!a.empty() && a[0] == '-') {
      throw thx::UsageError("unknown option '" + a + "'");
    } else {
      words.push_back(a);
    }
  }
  if (words.empty()) throw thx::UsageError("a command is required: status, load-scene NAME or reset-faults");
  o.command = words[0];
  const std::size_t want = o.command == "load-scene" ? 2 : 1;
  if (o.command != "status" && o.command != "load-scene" && o.command != "reset-faults")
    throw thx::UsageError("unknown command '" + o.command + "': expected status, load-scene NAME or reset-faults");
  if (words.size() != want)
    throw thx::UsageError(o.command + (want == 2 ? " takes one scene name" : " takes no argument"));
  if (want == 2) o.argument = words[1];
  return o;
}

void printScene(const thx_msgs::hello_t& h) {
  std::printf("%s (protocol %d), device %s [%s], servo %g Hz, scene '%s' (texture %s)\n", h.server_name.c_str(),
              h.protocol_version, h.device.c_str(), h.device_names.c_str(), h.servo_rate_hz, h.scene_name.c_str(),
              thx::tex::formatFingerprint(static_cast<std::uint64_t>(h.texture_fingerprint)).c_str());
}

int run(const Options& o) {
  thx::client::ClientApp app(o.client_id, o.lcm_url, o.timeout_s);
  const std::optional<thx_msgs::hello_t> hello = app.waitForServer();
  if (!hello) return 1;  // stopped by a signal
  if (o.command == "status") {
    printScene(*hello);
    return 0;
  }
  const auto reply = o.command == "load-scene" ? app.loadScene(o.argument, o.timeout_s) : app.resetFaults(o.timeout_s);
  if (!reply) return 1;
  if (o.command == "reset-faults") {
    std::printf("fault latch cleared from tick %lld\n", static_cast<long long>(reply->tick));
    return 0;
  }
  std::printf("scene '%s' rendered from tick %lld\n", o.argument.c_str(), static_cast<long long>(reply->tick));
  return 0;
}

}  // namespace

// Usage errors, no server, a refusal with hapticd's reason and a timeout are thx::Errors.
int main(int argc, char** argv) {
  thx::client::installStopSignals();
  return thx::runProgram("hapticctl", kHelp, argc, argv,
                         [](const std::vector<std::string>& args) { return run(parse(args)); });
}
