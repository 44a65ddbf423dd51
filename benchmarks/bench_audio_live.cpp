// The live audio client beside hapticd (issue 14; docs/audio.md "Live audio"): in one benchmark
// run, on one machine, phases of --seconds each in this order, repeated --rounds times:
//   alone     hapticd with its simulated device (the scene's hand script), no client
//   audio     hapticd + audio-client live (timer-driven callback: this machine has no sound device),
//             the default playout delay (a batch period plus a block)
//   audio-p0  the same with --playout-ms 0 (an impulse sounds in the first block after it arrives)
// Per phase: the servo's wake latency p50/p99/p999/max and tick compute p99 (hapticd --stats-json);
// with audio: the contact-to-callback latency (the CONTACT sample's server time, and its receipt
// by the client, to the start of the callback block that carries its impulse), events played,
// late, the callback's largest cost, the budget's fewest modes (audio-client --stats-json). And the
// device latency RtAudio reports when a device exists (none here: reported as absent).
// Measures, never asserts. Writes JSON (--json), one CSV row per phase (--csv), a table (--md).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"
#include "benchmarks/proc_tools.hpp"

namespace {

using namespace thx;

struct Options {
  std::string hapticd, audio, scene, workdir = ".", json, csv, md;
  double seconds = 20;
  int rounds = 1;
  int port = 7980;
};

[[noreturn]] void usage(const std::string& why) {
  std::fprintf(stderr, "bench_audio_live: %s (--help)\n", why.c_str());
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage(a + ": missing value");
      return argv[++i];
    };
    if (a == "--hapticd") o.hapticd = value();
    else if (a == "--audio-client") o.audio = value();
    else if (a == "--scene") o.scene = value();
    else if (a == "--seconds") o.seconds = std::atof(value().c_str());
    else if (a == "--rounds") o.rounds = std::atoi(value().c_str());
    else if (a == "--port") o.port = std::atoi(value().c_str());
    else if (a == "--workdir") o.workdir = value();
    else if (a == "--json") o.json = value();
    else if (a == "--csv") o.csv = value();
    else if (a == "--md") o.md = value();
    else usage("unknown argument '" + a + "'");
  }
  if (o.hapticd.empty() || o.audio.empty() || o.scene.empty()) usage("--hapticd, --audio-client and --scene are required");
  if (!(o.seconds > 2) || o.rounds < 1) usage("--seconds must be > 2 and --rounds >= 1");
  return o;
}

struct Phase {
  std::string name;
  int round = 0;
  int hapticd_status = -1, audio_status = -1;
  bool fifo = false;
  double ticks = NAN, missed = NAN, wake_p50 = NAN, wake_p99 = NAN, wake_p999 = NAN, wake_max = NAN, compute_p99 = NAN;
  // audio
  std::string output;
  double playout_ms = NAN, src_p50 = NAN, src_p99 = NAN, src_max = NAN, rcv_p50 = NAN, rcv_p99 = NAN, rcv_max = NAN;
  double events = NAN, late = NAN, expired = NAN, max_cost_us = NAN, min_modes = NAN, modes = NAN, device_latency_s = NAN;
  double timer_late_max_us = NAN, ticks_received = NAN, server_dropped = NAN;
};

double num(const std::string& text, const std::string& object, const std::string& key) {
  return test::jsonNumber(text, object, key).value_or(NAN);
}

Phase runPhase(const Options& o, const std::string& url, const std::string& name, int round) {
  Phase p;
  p.name = name;
  p.round = round;
  const std::string tag = o.workdir + "/bench_audio_live_" + name + "_" + std::to_string(round);
  char hd[32], ad[32];
  std::snprintf(hd, sizeof hd, "%g", o.seconds + 3);
  std::snprintf(ad, sizeof ad, "%g", o.seconds);
  const std::vector<std::string> hargv = {o.hapticd, "--scene", o.scene, "--duration", hd, "--quiet", "--lcm-url", url,
                                          "--stats-json", tag + "_hapticd.json", "--flight-dir", o.workdir};
  std::fprintf(stderr, "bench_audio_live: round %d, %s: %g s\n", round, name.c_str(), o.seconds);
  const pid_t server = bench::spawn(hargv, tag + "_hapticd.log");
  pid_t audio = -1;
  if (name != "alone") {
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    std::vector<std::string> a = {o.audio,   "--scene", o.scene, "--lcm-url", url, "--duration", ad, "--quiet",
                                  "--output", "auto", "--wav", tag + ".wav", "--stats-json", tag + "_audio.json"};
    if (name == "audio-p0") a.insert(a.end(), {"--playout-ms", "0"});
    audio = bench::spawn(a, tag + "_audio.log");
  }
  if (audio > 0) p.audio_status = test::waitExit(audio);
  p.hapticd_status = test::waitExit(server);
  const std::string s = test::slurp(tag + "_hapticd.json");
  p.ticks = num(s, "", "ticks");
  p.missed = num(s, "", "missed_ticks");
  p.wake_p50 = num(s, "wake_latency_us", "p50");
  p.wake_p99 = num(s, "wake_latency_us", "p99");
  p.wake_p999 = num(s, "wake_latency_us", "p999");
  p.wake_max = num(s, "wake_latency_us", "max");
  p.compute_p99 = num(s, "tick_compute_us", "p99");
  p.fifo = test::jsonBool(s, "realtime", "sched_fifo").value_or(false);
  if (audio > 0) {
    const std::string j = test::slurp(tag + "_audio.json");
    p.output = test::jsonField(j, "output");
    p.device_latency_s = num(j, "", "device_latency_s");
    p.playout_ms = num(j, "", "playout_delay_ms");
    p.src_p50 = num(j, "latency_from_source_us", "p50");
    p.src_p99 = num(j, "latency_from_source_us", "p99");
    p.src_max = num(j, "latency_from_source_us", "max");
    p.rcv_p50 = num(j, "latency_from_receipt_us", "p50");
    p.rcv_p99 = num(j, "latency_from_receipt_us", "p99");
    p.rcv_max = num(j, "latency_from_receipt_us", "max");
    p.events = num(j, "", "events");
    p.late = num(j, "", "late_events");
    p.expired = num(j, "", "expired_events");
    p.max_cost_us = num(j, "", "max_cost_us");
    p.min_modes = num(j, "", "min_rendered_modes");
    p.modes = num(j, "", "modes");
    p.timer_late_max_us = num(j, "", "timer_max_wake_late_us");
    p.ticks_received = num(j, "", "ticks");
    p.server_dropped = num(j, "", "server_dropped");
  }
  return p;
}

std::string jnum(double v) {
  if (!std::isfinite(v)) return "null";
  char b[48];
  std::snprintf(b, sizeof b, "%.3f", v);
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  thx::bench::exitOnHelp(argc, argv, R"(usage: bench_audio_live --hapticd PATH --audio-client PATH --scene FILE [--seconds S] [--rounds N]
                        [--port N] [--workdir DIR] [--json F] [--csv F] [--md F]

The live audio client beside hapticd (docs/audio.md, "Live audio"): per round, hapticd alone,
with audio-client live (default playout delay), and with --playout-ms 0, --seconds (20) each, over
LCM udpm with ttl=0 on --port (7980). The servo's wake latency against the run without the audio
client; the contact-to-callback latency of the timer-driven callback (no sound device here); the
device latency RtAudio reports when a device exists. Measures, never asserts.
benchmarks/run.sh BUILD_DIR audio-live runs it as the docs show.
)");
  const Options o = parse(argc, argv);
  const std::string url = "udpm://239.255.76.67:" + std::to_string(o.port) + "?ttl=0";
  std::vector<Phase> phases;
  for (int r = 1; r <= o.rounds; ++r)
    for (const char* name : {"alone", "audio", "audio-p0"}) phases.push_back(runPhase(o, url, name, r));
  phases.push_back(runPhase(o, url, "alone", o.rounds + 1));  // alone after, too

  if (!o.csv.empty()) {
    std::FILE* f = std::fopen(o.csv.c_str(), "w");
    if (!f) return std::fprintf(stderr, "bench_audio_live: cannot write %s\n", o.csv.c_str()), 1;
    std::fprintf(f, "phase,round,hapticd_status,audio_status,sched_fifo,ticks,missed_ticks,wake_p50_us,wake_p99_us,"
                    "wake_p999_us,wake_max_us,compute_p99_us,output,playout_ms,contact_to_block_p50_us,"
                    "contact_to_block_p99_us,contact_to_block_max_us,receipt_to_block_p50_us,receipt_to_block_p99_us,"
                    "receipt_to_block_max_us,events,late_events,expired_events,callback_max_cost_us,fewest_modes,modes,"
                    "device_latency_s\n");
    for (const Phase& p : phases)
      std::fprintf(f, "%s,%d,%d,%d,%d,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", p.name.c_str(),
                   p.round, p.hapticd_status, p.audio_status, p.fifo ? 1 : 0, jnum(p.ticks).c_str(), jnum(p.missed).c_str(),
                   jnum(p.wake_p50).c_str(), jnum(p.wake_p99).c_str(), jnum(p.wake_p999).c_str(), jnum(p.wake_max).c_str(),
                   jnum(p.compute_p99).c_str(), p.output.c_str(), jnum(p.playout_ms).c_str(), jnum(p.src_p50).c_str(),
                   jnum(p.src_p99).c_str(), jnum(p.src_max).c_str(), jnum(p.rcv_p50).c_str(), jnum(p.rcv_p99).c_str(),
                   jnum(p.rcv_max).c_str(), jnum(p.events).c_str(), jnum(p.late).c_str(), jnum(p.expired).c_str(),
                   jnum(p.max_cost_us).c_str(), jnum(p.min_modes).c_str(), jnum(p.modes).c_str(),
                   p.output == "device" ? jnum(p.device_latency_s).c_str() : "");
    std::fclose(f);
  }
  if (!o.json.empty()) {
    std::FILE* f = std::fopen(o.json.c_str(), "w");
    if (!f) return std::fprintf(stderr, "bench_audio_live: cannot write %s\n", o.json.c_str()), 1;
    std::fprintf(f, "{\n  \"benchmark\": \"audio_live\",\n  \"machine\": \"%s\",\n  \"date\": \"%s\",\n  \"scene\": \"%s\",\n"
                    "  \"seconds\": %g,\n  \"rounds\": %d,\n  \"url\": \"%s\",\n  \"phases\": [\n",
                 bench::machineDescription().c_str(), bench::isoTimeNow().c_str(), o.scene.c_str(), o.seconds, o.rounds,
                 url.c_str());
    for (std::size_t k = 0; k < phases.size(); ++k) {
      const Phase& p = phases[k];
      std::fprintf(f,
                   "    {\"phase\": \"%s\", \"round\": %d, \"hapticd_status\": %d, \"audio_status\": %d, \"sched_fifo\": %s,\n"
                   "     \"servo\": {\"ticks\": %s, \"missed_ticks\": %s, \"wake_p50_us\": %s, \"wake_p99_us\": %s, "
                   "\"wake_p999_us\": %s, \"wake_max_us\": %s, \"compute_p99_us\": %s},\n"
                   "     \"audio\": {\"output\": \"%s\", \"playout_ms\": %s, \"contact_to_block_us\": {\"p50\": %s, \"p99\": %s, "
                   "\"max\": %s}, \"receipt_to_block_us\": {\"p50\": %s, \"p99\": %s, \"max\": %s}, \"events\": %s, "
                   "\"late_events\": %s, \"expired_events\": %s, \"callback_max_cost_us\": %s, \"fewest_modes\": %s, "
                   "\"modes\": %s, \"timer_max_wake_late_us\": %s, \"ticks_received\": %s, \"server_dropped\": %s, "
                   "\"device_latency_s\": %s}}%s\n",
                   p.name.c_str(), p.round, p.hapticd_status, p.audio_status, p.fifo ? "true" : "false", jnum(p.ticks).c_str(),
                   jnum(p.missed).c_str(), jnum(p.wake_p50).c_str(), jnum(p.wake_p99).c_str(), jnum(p.wake_p999).c_str(),
                   jnum(p.wake_max).c_str(), jnum(p.compute_p99).c_str(), p.output.c_str(), jnum(p.playout_ms).c_str(),
                   jnum(p.src_p50).c_str(), jnum(p.src_p99).c_str(), jnum(p.src_max).c_str(), jnum(p.rcv_p50).c_str(),
                   jnum(p.rcv_p99).c_str(), jnum(p.rcv_max).c_str(), jnum(p.events).c_str(), jnum(p.late).c_str(),
                   jnum(p.expired).c_str(), jnum(p.max_cost_us).c_str(), jnum(p.min_modes).c_str(), jnum(p.modes).c_str(),
                   jnum(p.timer_late_max_us).c_str(), jnum(p.ticks_received).c_str(), jnum(p.server_dropped).c_str(),
                   p.output == "device" ? jnum(p.device_latency_s).c_str() : "null", k + 1 < phases.size() ? "," : "");
    }
    std::fprintf(f, "  ]\n}\n");
    std::fclose(f);
  }
  // The table: one row per phase.
  std::string md =
      "| phase | round | servo wake p50 / p99 / p99.9 / max µs | missed ticks | output | playout ms | contact → block p50 / p99 / "
      "max ms | receipt → block p50 / p99 / max ms | events (late, expired) | callback max cost µs | fewest modes |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n";
  char line[768];
  for (const Phase& p : phases) {
    if (p.name == "alone") {
      std::snprintf(line, sizeof line, "| %s | %d | %.1f / %.1f / %.1f / %.0f | %.0f | — | — | — | — | — | — | — |\n",
                    p.name.c_str(), p.round, p.wake_p50, p.wake_p99, p.wake_p999, p.wake_max, p.missed);
    } else {
      std::snprintf(line, sizeof line,
                    "| %s | %d | %.1f / %.1f / %.1f / %.0f | %.0f | %s | %.1f | %.2f / %.2f / %.2f | %.2f / %.2f / %.2f | "
                    "%.0f (%.0f, %.0f) | %.0f | %.0f of %.0f |\n",
                    p.name.c_str(), p.round, p.wake_p50, p.wake_p99, p.wake_p999, p.wake_max, p.missed, p.output.c_str(),
                    p.playout_ms, p.src_p50 / 1e3, p.src_p99 / 1e3, p.src_max / 1e3, p.rcv_p50 / 1e3, p.rcv_p99 / 1e3,
                    p.rcv_max / 1e3, p.events, p.late, p.expired, p.max_cost_us, p.min_modes, p.modes);
    }
    md += line;
  }
  std::snprintf(line, sizeof line,
                "\n%s; scene %s, %g s per phase, SCHED_FIFO %s. Sound device: %s.\n", bench::machineDescription().c_str(),
                std::filesystem::path(o.scene).filename().c_str(), o.seconds, phases.front().fifo ? "yes" : "no",
                std::any_of(phases.begin(), phases.end(), [](const Phase& p) { return p.output == "device"; })
                    ? "yes (its latency in the JSON)"
                    : "none (the timer-driven callback stood in; RtAudio reports no device latency)");
  md += line;
  std::fputs(md.c_str(), stdout);
  if (!o.md.empty()) {
    std::FILE* f = std::fopen(o.md.c_str(), "w");
    if (!f) return std::fprintf(stderr, "bench_audio_live: cannot write %s\n", o.md.c_str()), 1;
    std::fputs(md.c_str(), f);
    std::fclose(f);
  }
  return 0;
}
