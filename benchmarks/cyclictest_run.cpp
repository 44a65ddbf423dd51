#include "benchmarks/cyclictest_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <thread>

#include "benchmarks/bench_rig.hpp"
#include "benchmarks/proc_tools.hpp"

namespace thx::bench {

bool parseCyclictestHistogram(const std::string& text, Latency& l) {
  std::vector<std::uint64_t> bins;
  std::istringstream is(text);
  std::string line;
  while (std::getline(is, line)) {
    long long v = 0, c = 0;
    if (line.empty()) continue;
    if (line[0] == '#') {
      if (std::sscanf(line.c_str(), "# Min Latencies: %lld", &v) == 1) l.min_us = double(v);
      if (std::sscanf(line.c_str(), "# Avg Latencies: %lld", &v) == 1) l.avg_us = double(v);
      if (std::sscanf(line.c_str(), "# Max Latencies: %lld", &v) == 1) l.max_us = double(v);
      if (std::sscanf(line.c_str(), "# Histogram Overflows: %lld", &v) == 1) l.overflows = std::uint64_t(v);
      continue;
    }
    if (std::sscanf(line.c_str(), "%lld %lld", &v, &c) == 2 && v >= 0) {
      if (std::size_t(v) >= bins.size()) bins.resize(std::size_t(v) + 1, 0);
      bins[std::size_t(v)] = std::uint64_t(c);
    }
  }
  std::uint64_t total = l.overflows;
  for (auto c : bins) total += c;
  if (total == 0) return false;
  l.count = total;
  auto q = [&](double p) {
    const std::uint64_t want = std::uint64_t(std::ceil(p * double(total)));
    std::uint64_t acc = 0;
    for (std::size_t i = 0; i < bins.size(); ++i) {
      acc += bins[i];
      if (acc >= want) return double(i);
    }
    return l.max_us;  // in the overflow
  };
  l.p50_us = q(0.5);
  l.p99_us = q(0.99);
  l.p999_us = q(0.999);
  l.bins = std::move(bins);
  return true;
}

std::uint64_t countAtLeastUs(const Latency& l, int us) {
  std::uint64_t n = l.overflows;
  for (std::size_t i = std::size_t(std::max(us, 0)); i < l.bins.size(); ++i) n += l.bins[i];
  return n;
}

Job startCyclictest(const std::string& exe, int seconds, const std::string& workdir, const std::string& tag,
                    int interval_us) {
  Job j;
  j.out = workdir + "/lat_cyclictest_" + tag + ".hist";
  j.log = workdir + "/lat_cyclictest_" + tag + ".log";
  std::remove(j.out.c_str());
  std::remove(j.log.c_str());
  const long long loops = (long long)seconds * 1000000LL / interval_us;
  j.argv = {exe, "-m", "-p", "80", "-i", std::to_string(interval_us), "-l", std::to_string(loops), "-q", "-h", "10000",
            "--histfile=" + j.out};
  j.pid = spawn(j.argv, j.log);
  return j;
}

bool sawFifo(pid_t pid, std::optional<int>& ended) {
  for (int i = 0; i < 40; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if ((ended = test::pollExit(pid))) return false;
    for (const auto& [tid, policy] : threadPolicies(pid)) {
      if (policy == 1) return true;
    }
  }
  return false;
}

Latency finishCyclictest(const Job& j, const std::string& run, bool fifo, std::optional<int> status) {
  Latency l;
  l.source = "cyclictest";
  l.run = run;
  l.command = test::commandLine(j.argv);
  const int st = status ? *status : test::waitExit(j.pid);
  l.fifo = fifo;
  l.ok = st == 0 && parseCyclictestHistogram(test::slurp(j.out), l);
  const std::string log = test::slurp(j.log);
  if (!l.ok) l.note = fmt("cyclictest failed (exit %d): %s", st, log.substr(0, 300).c_str());
  if (!fifo) l.note += (l.note.empty() ? "" : "; ") + std::string("cyclictest did NOT get SCHED_FIFO");
  return l;
}

}  // namespace thx::bench
