// The machine's own tail for a fixed piece of work of about a microsecond, timed as
// bench_mesh_force times the servo's render(): steady_clock around each repetition, 100,000
// repetitions, p50 and p99. The work never changes, so whatever spread it shows is the machine's
// (the VM's neighbours, its scheduler), not the code's: a control for the render cost's p99
// (docs/meshes.md, "The tail at 500,000 triangles").
// Two kinds of work, in alternating rounds: a chain of dependent multiply-adds (no memory), and
// a chain of dependent loads through the same few hundred cache lines spread over 200 KB (a
// working set that stays in the core's caches, as the renderer's mostly does).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"

namespace {

using namespace thx;
using Clock = std::chrono::steady_clock;

constexpr const char* kHelp = R"(usage: bench_timing_noise [--rounds N] [--reps N] [--csv FILE] [--json FILE]

The machine's tail for fixed work of about a microsecond: each repetition timed with
steady_clock as bench_mesh_force times render(), p50, p99 and their ratio. The work is the same
in every repetition, so its spread is the machine's. Two kinds, in alternating rounds:
  alu    600 dependent multiply-adds (no memory)
  loads  300 dependent loads through the same cache lines, spread over 200 KB
Also: the median time of the repetition right after a p99 one (above the p50 when slow
repetitions come in bursts).

  --rounds N   rounds of each kind (default 5)
  --reps N     repetitions per round (default 100000)
  --csv FILE   one row per round
  --json FILE  the same as JSON
)";

// Where each repetition's result goes, so that the compiler keeps the work.
volatile double alu_sink = 0;
volatile std::size_t load_sink = 0;

constexpr int kAluSteps = 600;
constexpr int kHops = 300;
constexpr std::size_t kLoadBytes = 200 * 1000;

struct Round {
  std::string kind;
  int round = 0;
  double p50_us = 0, p90_us = 0, p99_us = 0, after_tail_us = 0;
};

Round summarise(const std::string& kind, int round, const std::vector<double>& us) {
  std::vector<double> s = us;
  std::sort(s.begin(), s.end());
  auto at = [&](double q) { return s[std::min(s.size() - 1, std::size_t(q * double(s.size())))]; };
  Round r{kind, round, at(0.5), at(0.9), at(0.99), 0};
  std::vector<double> after;
  for (std::size_t i = 0; i + 1 < us.size(); ++i) {
    if (us[i] >= r.p99_us) after.push_back(us[i + 1]);
  }
  std::sort(after.begin(), after.end());
  r.after_tail_us = after.empty() ? 0 : after[after.size() / 2];
  return r;
}

// A cycle through every cache line of the buffer in a shuffled order; each repetition follows the
// same kHops of it from the same start.
std::vector<std::size_t> shuffledCycle(std::size_t bytes) {
  const std::size_t lines = bytes / 64, stride = 64 / sizeof(std::size_t);
  std::vector<std::size_t> order(lines), next(lines * stride);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::mt19937 rng(1);
  std::shuffle(order.begin(), order.end(), rng);
  for (std::size_t i = 0; i < lines; ++i) next[order[i] * stride] = order[(i + 1) % lines] * stride;
  next.push_back(order[0] * stride);  // the start, kept at the end
  return next;
}

int run(int argc, char** argv) {
  int rounds = 5, reps = 100000;
  std::string csv_path, json_path;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--rounds") rounds = int(cli::parseInteger(a, v, 1, 1000));
    else if (a == "--reps") reps = int(cli::parseInteger(a, v, 1000, 10'000'000));
    else if (a == "--csv") csv_path = v;
    else if (a == "--json") json_path = v;
    else throw UsageError("unknown option " + a + " (see --help)");
  }
  const std::vector<std::size_t> next = shuffledCycle(kLoadBytes);
  const std::size_t start = next.back();
  std::vector<double> us(static_cast<std::size_t>(reps));
  std::vector<Round> out;
  for (int round = 0; round < rounds; ++round) {
    for (int k = 0; k < reps; ++k) {
      const auto t0 = Clock::now();
      double a = 1.0001;
      for (int i = 0; i < kAluSteps; ++i) a = a * 1.0000001 + 1e-9;
      alu_sink = a;
      const auto t1 = Clock::now();
      us[std::size_t(k)] = std::chrono::duration<double, std::micro>(t1 - t0).count();
    }
    out.push_back(summarise("alu", round, us));
    for (int k = 0; k < reps; ++k) {
      const auto t0 = Clock::now();
      std::size_t p = start;
      for (int i = 0; i < kHops; ++i) p = next[p];
      load_sink = p;
      const auto t1 = Clock::now();
      us[std::size_t(k)] = std::chrono::duration<double, std::micro>(t1 - t0).count();
    }
    out.push_back(summarise("loads", round, us));
  }
  std::printf("%s\n%-6s %5s %8s %8s %8s %8s %18s\n", bench::machineDescription().c_str(), "kind", "round", "p50 us",
              "p90 us", "p99 us", "p99/p50", "after a p99, us");
  std::string csv = "kind,round,p50_us,p90_us,p99_us,p99_over_p50,after_tail_us\n";
  std::string json = "{\n  \"benchmark\": \"timing noise of fixed work\",\n  \"machine\": \"" +
                     bench::machineDescription() + "\",\n  \"date\": \"" + bench::isoTimeNow() + "\",\n  \"rounds\": [\n";
  for (std::size_t i = 0; i < out.size(); ++i) {
    const Round& r = out[i];
    std::printf("%-6s %5d %8.3f %8.3f %8.3f %8.2f %18.3f\n", r.kind.c_str(), r.round, r.p50_us, r.p90_us, r.p99_us,
                r.p99_us / r.p50_us, r.after_tail_us);
    csv += bench::fmt("%s,%d,%.3f,%.3f,%.3f,%.3f,%.3f\n", r.kind.c_str(), r.round, r.p50_us, r.p90_us, r.p99_us,
                      r.p99_us / r.p50_us, r.after_tail_us);
    json += bench::fmt("    {\"kind\": \"%s\", \"round\": %d, \"p50_us\": %.3f, \"p90_us\": %.3f, \"p99_us\": %.3f, "
                       "\"p99_over_p50\": %.3f, \"after_tail_us\": %.3f}%s\n",
                       r.kind.c_str(), r.round, r.p50_us, r.p90_us, r.p99_us, r.p99_us / r.p50_us, r.after_tail_us,
                       i + 1 < out.size() ? "," : "");
  }
  json += "  ]\n}\n";
  if (!csv_path.empty()) bench::writeTextFile(csv_path, csv);
  if (!json_path.empty()) bench::writeTextFile(json_path, json);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_timing_noise", run); }
