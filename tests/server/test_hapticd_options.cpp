// hapticd's command line (server/hapticd_options.hpp): every option's happy path, the defaults,
// the errors (option, value, what was expected) and the conversions into the parts' options.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "base/error.hpp"
#include "device/device_specs.hpp"
#include "server/hapticd_options.hpp"

namespace test_hapticd_options {

namespace {

using thx::srv::HapticdOptions;
using thx::srv::parseHapticdOptions;

HapticdOptions parse(std::vector<std::string> args) {
  args.insert(args.begin(), {"--scene", "scenes/default.yaml"});
  return parseHapticdOptions(args);
}

// The UsageError's message for `args` (given as they are, no --scene added).
std::string usageError(const std::vector<std::string>& args) {
  try {
    parseHapticdOptions(args);
  } catch (const thx::UsageError& e) {
    EXPECT_EQ(e.kind(), thx::Error::Kind::Usage);
    return e.what();
  }
  ADD_FAILURE() << "no UsageError";
  return "";
}

}  // namespace

TEST(HapticdOptions, DefaultsAreTheDocumentedOnes) {
  const HapticdOptions o = parse({});
  EXPECT_FALSE(o.help);
  EXPECT_EQ(o.scene, "scenes/default.yaml");
  EXPECT_EQ(o.scenes_dir, "");
  EXPECT_EQ(o.device, "");
  EXPECT_FALSE(o.duration_s);
  EXPECT_FALSE(o.lockstep);
  EXPECT_EQ(o.spin_ns, 0);
  EXPECT_EQ(o.stats_json, "");
  EXPECT_EQ(o.record, "");
  EXPECT_EQ(o.lcm_url, thx_msgs::kDefaultLcmUrl);
  EXPECT_FALSE(o.no_lcm);
  EXPECT_EQ(o.io_priority, 40);
  EXPECT_EQ(o.limits.max_clients, 32);
  EXPECT_DOUBLE_EQ(o.limits.max_bandwidth_bytes_per_s, 8e6);
  EXPECT_EQ(o.limits.heartbeat_timeout_ns, 2'000'000'000);
  EXPECT_EQ(o.limits.client_grace_ns, 10'000'000'000);
  EXPECT_FALSE(o.max_rate_given);
  EXPECT_TRUE(o.crease);
  EXPECT_TRUE(o.passivity);
  EXPECT_FALSE(o.stiffness_fraction);
  EXPECT_FALSE(o.strict_stability);
  EXPECT_FALSE(o.paper_loop);
  EXPECT_EQ(o.missed_mode, thx::srv::MissedTickMode::RideThrough);
  EXPECT_FALSE(o.plane_rate_hz);
  EXPECT_FALSE(o.rt.require);
  EXPECT_EQ(o.rt.cpu, -1);
  EXPECT_TRUE(o.rt.lock_memory);
  EXPECT_TRUE(o.rt.lock_on_fault);
  EXPECT_EQ(o.flight_dir, ".");
  EXPECT_EQ(o.flight_limits.max_files, 20u);
  EXPECT_DOUBLE_EQ(o.flight_limits.min_interval_s, 10.0);
  EXPECT_FALSE(o.quiet);
  EXPECT_FALSE(o.verbose);
  EXPECT_EQ(o.vrpn_listen, "");
  EXPECT_EQ(o.vrpn_name, "Phantom0");
  EXPECT_FALSE(o.vrpn_report_hz);
  EXPECT_EQ(o.vrpn_max_clients, 16);
  EXPECT_FALSE(o.vrpn_plane2);
  // The default bus is udpm on port 7667: control on the next port, data ports after it.
  EXPECT_EQ(o.ports.control_port, 7668);
  EXPECT_EQ(o.ports.data_first, 7669);
  EXPECT_EQ(o.ports.data_last, 7669 + 32 - 1);
}

TEST(HapticdOptions, HelpStopsParsingAndNeedsNoScene) {
  for (const char* h : {"-h", "--help"}) {
    const HapticdOptions o = parseHapticdOptions({h, "--bogus"});
    EXPECT_TRUE(o.help) << h;
  }
  // What comes before --help is still checked, as before.
  EXPECT_EQ(usageError({"--bogus", "--help"}), "unknown argument '--bogus'");
  EXPECT_NE(std::string(thx::srv::hapticdHelp()).find("usage: hapticd --scene FILE [options]"), std::string::npos);
}

TEST(HapticdOptions, FilesDeviceAndRunOptions) {
  const HapticdOptions o =
      parse({"--scenes-dir", "more/scenes", "--device", "replay:s.lcm", "--duration", "2.5", "--lockstep",
             "--record", "r.lcm", "--stats-json", "s.json", "--quiet", "--verbose"});
  EXPECT_EQ(o.scenes_dir, "more/scenes");
  EXPECT_EQ(o.device, "replay:s.lcm");
  EXPECT_EQ(o.duration_s, 2.5);
  EXPECT_TRUE(o.lockstep);
  EXPECT_EQ(o.record, "r.lcm");
  EXPECT_EQ(o.stats_json, "s.json");
  EXPECT_TRUE(o.quiet);
  EXPECT_TRUE(o.verbose);
  EXPECT_EQ(parse({"--device", "sim"}).device, "sim");
  EXPECT_EQ(parse({"--device", "vrpn:Phantom0@localhost"}).device, "vrpn:Phantom0@localhost");
  EXPECT_EQ(parse({"--duration", "0"}).duration_s, 0.0);
}

TEST(HapticdOptions, TransportAndClientOptions) {
  const HapticdOptions o = parse({"--lcm-url", "udpm://239.255.76.67:7000?ttl=0", "--control-port", "7100",
                                  "--data-ports", "7200-7203", "--io-priority", "30", "--max-clients", "4",
                                  "--max-rate", "250", "--max-bandwidth", "2.5", "--heartbeat-timeout", "0.5",
                                  "--client-grace", "0"});
  EXPECT_EQ(o.lcm_url, "udpm://239.255.76.67:7000?ttl=0");
  EXPECT_EQ(o.control_port, "7100");
  EXPECT_EQ(o.data_ports, "7200-7203");
  EXPECT_EQ(o.ports.control_port, 7100);
  EXPECT_EQ(o.ports.data_first, 7200);
  EXPECT_EQ(o.ports.data_last, 7203);
  EXPECT_EQ(o.io_priority, 30);
  EXPECT_EQ(o.limits.max_clients, 4);
  EXPECT_DOUBLE_EQ(o.limits.max_rate_hz, 250.0);
  EXPECT_TRUE(o.max_rate_given);
  EXPECT_DOUBLE_EQ(o.limits.max_bandwidth_bytes_per_s, 2.5e6);
  EXPECT_EQ(o.limits.heartbeat_timeout_ns, 500'000'000);
  EXPECT_EQ(o.limits.client_grace_ns, 0);
  const HapticdOptions off = parse({"--no-lcm", "--control-port", "off", "--data-ports", "off"});
  EXPECT_TRUE(off.no_lcm);
  EXPECT_EQ(off.ports.control_port, 0);
  EXPECT_EQ(off.ports.data_first, 0);
}

TEST(HapticdOptions, RenderingAndRealTimeOptions) {
  const HapticdOptions o =
      parse({"--no-crease", "--no-passivity", "--missed-policy", "disengage", "--stiffness-fraction", "0.5",
             "--strict-stability", "--paper-loop", "--plane-rate", "50", "--require-rt", "--cpu", "1", "--no-mlock",
             "--mlock-eager", "--flight-dir", "flights", "--flight-max", "3", "--flight-interval", "0"});
  EXPECT_FALSE(o.crease);
  EXPECT_FALSE(o.passivity);
  EXPECT_EQ(o.missed_mode, thx::srv::MissedTickMode::DisengageOnGap);
  EXPECT_EQ(o.stiffness_fraction, 0.5);
  EXPECT_TRUE(o.strict_stability);
  EXPECT_TRUE(o.paper_loop);
  EXPECT_EQ(o.plane_rate_hz, 50.0);
  EXPECT_TRUE(o.rt.require);
  EXPECT_EQ(o.rt.cpu, 1);
  EXPECT_FALSE(o.rt.lock_memory);
  EXPECT_FALSE(o.rt.lock_on_fault);
  EXPECT_EQ(o.flight_dir, "flights");
  EXPECT_EQ(o.flight_limits.max_files, 3u);
  EXPECT_DOUBLE_EQ(o.flight_limits.min_interval_s, 0.0);
  EXPECT_EQ(parse({"--missed-policy", "ride-through"}).missed_mode, thx::srv::MissedTickMode::RideThrough);
  EXPECT_EQ(parse({"--spin-us", "150"}).spin_ns, 150'000);
}

TEST(HapticdOptions, VrpnServerOptions) {
  const HapticdOptions o = parse({"--vrpn-listen", "0.0.0.0:3884", "--vrpn-name", "Pen1", "--vrpn-report-hz", "500",
                                  "--vrpn-max-clients", "2", "--vrpn-plane2"});
  EXPECT_EQ(o.vrpn_listen, "0.0.0.0:3884");
  EXPECT_EQ(o.vrpn_address.ip, "0.0.0.0");
  EXPECT_EQ(o.vrpn_address.port, 3884);
  EXPECT_EQ(o.vrpn_name, "Pen1");
  EXPECT_EQ(o.vrpn_report_hz, 500.0);
  EXPECT_EQ(o.vrpn_max_clients, 2);
  EXPECT_TRUE(o.vrpn_plane2);
  const HapticdOptions loopback = parse({"--vrpn-listen", "3883"});
  EXPECT_EQ(loopback.vrpn_address.ip, "127.0.0.1");
  EXPECT_EQ(loopback.vrpn_address.port, 3883);
}

TEST(HapticdOptions, ErrorsNameTheOptionTheValueAndWhatWasExpected) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--scene", "x", "--bogus"}, "unknown argument '--bogus'"},
      {{"--lockstep"}, "--scene FILE is required"},
      {{"--scene"}, "--scene needs a value"},
      {{"--scene", "x", "--duration", "-1"}, "--duration must be >= 0"},
      {{"--scene", "x", "--duration", "abc"}, "--duration: expected a number, got 'abc'"},
      {{"--scene", "x", "--io-priority", "80"}, "--io-priority: expected a whole number 0..79 (below the servo's 80), got 80"},
      {{"--scene", "x", "--max-clients", "0"}, "--max-clients must be a whole number >= 1"},
      {{"--scene", "x", "--spin-us", "-3"}, "--spin-us: expected microseconds in [0, 10000], got -3"},
      {{"--scene", "x", "--max-rate", "0"}, "--max-rate must be > 0"},
      {{"--scene", "x", "--max-bandwidth", "0"}, "--max-bandwidth must be > 0"},
      {{"--scene", "x", "--heartbeat-timeout", "0.01"}, "--heartbeat-timeout must be in [0.05, 3600] s"},
      {{"--scene", "x", "--client-grace", "-1"}, "--client-grace must be in [0, 3600] s"},
      {{"--scene", "x", "--missed-policy", "foo"}, "--missed-policy: expected 'ride-through' or 'disengage', got 'foo'"},
      {{"--scene", "x", "--plane-rate", "0"}, "--plane-rate: expected a rate > 0 Hz"},
      {{"--scene", "x", "--stiffness-fraction", "2"}, "--stiffness-fraction must be in (0, 1]"},
      {{"--scene", "x", "--flight-dir", ""}, "--flight-dir: expected a folder, got ''"},
      {{"--scene", "x", "--flight-max", "1.5"}, "--flight-max: expected an integer 0..1000000"},
      {{"--scene", "x", "--flight-interval", "90000"}, "--flight-interval: expected seconds in [0, 86400]"},
      {{"--scene", "x", "--vrpn-name", "a@b"}, "--vrpn-name: expected 1..95 characters without '@', got 'a@b'"},
      {{"--scene", "x", "--vrpn-report-hz", "0"}, "--vrpn-report-hz must be > 0"},
      {{"--scene", "x", "--vrpn-max-clients", "300"}, "--vrpn-max-clients: expected an integer 1..256"},
      {{"--scene", "x", "--device", "foo"},
       "--device: expected 'sim', 'vrpn:NAME@HOST[:PORT]', 'vrpn:NAME@tcp://HOST:PORT' or 'replay:FILE', got 'foo'"},
      {{"--scene", "x", "--device", "replay:"}, "--device replay:FILE needs a file"},
      {{"--scene", "x", "--device", "vrpn:a@b", "--lockstep"}, "--lockstep needs the simulated or a replayed device"},
      {{"--scene", "x", "--plane-rate", "10"}, "--plane-rate applies to --paper-loop only"},
      {{"--scene", "x", "--vrpn-listen", "1.2.3:99"},
       "--vrpn-listen: expected [ADDR:]PORT with an IPv4 ADDR and PORT 1..65535, got '1.2.3:99'"},
      {{"--scene", "x", "--control-port", "99999"}, "--control-port 99999: expected a port 1..65535 or 'off'"},
      {{"--scene", "x", "--cpu", "abc"}, "--cpu: expected a number, got 'abc'"},
  };
  for (const auto& [args, message] : cases) EXPECT_EQ(usageError(args), message);
}

TEST(HapticdOptions, ListenAddresses) {
  EXPECT_FALSE(thx::srv::parseListenAddress(""));
  EXPECT_FALSE(thx::srv::parseListenAddress("0"));
  EXPECT_FALSE(thx::srv::parseListenAddress("65536"));
  EXPECT_FALSE(thx::srv::parseListenAddress("localhost:3883"));
  EXPECT_FALSE(thx::srv::parseListenAddress("127.0.0.1:"));
  EXPECT_EQ(thx::srv::parseListenAddress("65535")->port, 65535);
}

TEST(HapticdOptions, ConvertsIntoThePartsOptions) {
  HapticdOptions o = parse({"--no-crease", "--stiffness-fraction", "0.25", "--paper-loop", "--quiet", "--verbose",
                            "--flight-dir", "f", "--flight-max", "2", "--io-priority", "20"});
  const thx::srv::ScenePolicy policy = thx::srv::scenePolicy(o);
  EXPECT_FALSE(policy.crease);
  EXPECT_TRUE(policy.passivity);
  EXPECT_EQ(policy.stiffness_fraction, 0.25);
  EXPECT_EQ(policy.paper_loop_plane_hz, thx::srv::kPaperPlaneRateHz);
  EXPECT_FALSE(thx::srv::scenePolicy(parse({})).paper_loop_plane_hz);

  const thx::srv::SceneSwitcherOptions sso = thx::srv::sceneSwitcherOptions(o);
  EXPECT_EQ(sso.scenes_dir, "scenes");  // the folder of --scene
  EXPECT_TRUE(sso.quiet);
  EXPECT_TRUE(sso.verbose);
  EXPECT_FALSE(sso.policy.crease);
  EXPECT_EQ(thx::srv::sceneSwitcherOptions(parseHapticdOptions({"--scene", "a.yaml"})).scenes_dir, ".");
  EXPECT_EQ(thx::srv::sceneSwitcherOptions(parse({"--scenes-dir", "d"})).scenes_dir, "d");

  thx::srv::PublisherOptions po = thx::srv::publisherOptions(o, 500.0);
  EXPECT_DOUBLE_EQ(po.servo_rate_hz, 500.0);
  EXPECT_DOUBLE_EQ(po.limits.max_rate_hz, 500.0);  // no --max-rate: the servo rate
  EXPECT_FALSE(po.log_subscriptions);
  EXPECT_EQ(po.flight_dir, "f");
  EXPECT_EQ(po.flight_limits.max_files, 2u);
  EXPECT_EQ(po.fifo_priority, 20);
  EXPECT_EQ(po.data_port_first, 7669);
  EXPECT_DOUBLE_EQ(thx::srv::publisherOptions(parse({"--max-rate", "100"}), 500.0).limits.max_rate_hz, 100.0);
  EXPECT_EQ(thx::srv::publisherOptions(parse({"--data-ports", "off"}), 1000.0).data_port_first, 0);
  // Lock-step: ordinary I/O threads (a SCHED_FIFO publisher would starve behind the waiting servo).
  EXPECT_EQ(thx::srv::ioThreadPriority(parse({"--lockstep", "--io-priority", "20"})), 0);

  EXPECT_EQ(thx::srv::vrpnAddress(parse({"--device", "vrpn:P@h"}), "Q@g"), "P@h");
  EXPECT_EQ(thx::srv::vrpnAddress(parse({}), "Q@g"), "Q@g");  // the scene's
  EXPECT_EQ(thx::srv::vrpnAddress(parse({"--device", "sim"}), "Q@g"), "");

  o = parse({"--vrpn-listen", "3900", "--vrpn-name", "P", "--vrpn-max-clients", "3", "--vrpn-plane2"});
  const thx::dev::DeviceSpec spec = thx::dev::phantomDesktopSpec();
  const thx::srv::VrpnServerOptions vso = thx::srv::vrpnServerOptions(o, spec, 1000.0);
  EXPECT_EQ(vso.listen_ip, "127.0.0.1");
  EXPECT_EQ(vso.port, 3900);
  EXPECT_EQ(vso.device_name, "P");
  EXPECT_DOUBLE_EQ(vso.report_hz, 1000.0);
  EXPECT_DOUBLE_EQ(vso.max_report_hz, 1000.0);
  EXPECT_EQ(vso.max_clients, 3);
  EXPECT_TRUE(vso.render_plane2);
  EXPECT_DOUBLE_EQ(vso.workspace_max[0], spec.workspace_radius_m);
  EXPECT_DOUBLE_EQ(vso.workspace_min[2], -spec.workspace_radius_m);
  EXPECT_DOUBLE_EQ(vso.limits.peak_force_n, spec.peak_force_n);
  EXPECT_DOUBLE_EQ(vso.limits.max_stiffness_n_per_m, spec.max_stiffness_n_per_m);
}

}  // namespace test_hapticd_options
