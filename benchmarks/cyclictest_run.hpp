#pragma once
// cyclictest (Debian rt-tests) as the latency benchmarks run it (bench_latency, bench_load): started
// at SCHED_FIFO 80 with a 1 ms interval (bench_load: the servo's period) and a 1 us histogram file, watched for its FIFO thread,
// its histogram read back into quantiles.
#include <sys/types.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace thx::bench {

// One latency measurement (cyclictest's or hapticd's wake-up latency), in microseconds.
struct Latency {
  bool ok = false;
  std::string source;  // "cyclictest" | "hapticd"
  std::string run;     // which run of the benchmark
  std::string command;
  bool fifo = false;
  std::string note;
  std::uint64_t count = 0, overflows = 0;
  double min_us = 0, avg_us = 0, p50_us = 0, p99_us = 0, p999_us = 0, max_us = 0;
  std::vector<std::uint64_t> bins;  // cyclictest's histogram: samples per whole microsecond
};

// The samples `us` microseconds late or more (the histogram's overflows count as such).
std::uint64_t countAtLeastUs(const Latency& l, int us);

// cyclictest --histfile: "# Histogram" then "NNNNNN CCCCCC" per microsecond, then "# Total:",
// "# Min Latencies:", "# Avg Latencies:", "# Max Latencies:", "# Histogram Overflows:".
bool parseCyclictestHistogram(const std::string& text, Latency& l);

struct Job {
  pid_t pid = -1;
  std::vector<std::string> argv;
  std::string log, out;  // out: histogram file (cyclictest) or stats JSON (hapticd)
};

// cyclictest -m -p 80 -i INTERVAL for `seconds`, histogram to WORKDIR/lat_cyclictest_TAG.hist;
// the interval in microseconds (1000: the 1 kHz servo's period).
Job startCyclictest(const std::string& exe, int seconds, const std::string& workdir, const std::string& tag,
                    int interval_us = 1000);
// Watches cyclictest for its SCHED_FIFO thread (policy 1) during its first two seconds. If it
// ends meanwhile, `ended` receives its exit status (it has been reaped).
bool sawFifo(pid_t pid, std::optional<int>& ended);
// Waits for it (unless `status` says it has ended) and reads its histogram.
Latency finishCyclictest(const Job& j, const std::string& run, bool fifo, std::optional<int> status);

}  // namespace thx::bench
