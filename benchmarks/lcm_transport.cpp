// lcm_transport: what an LCM udpm process pays for traffic it did not subscribe to (issue 17).
// Not part of the product: a measuring tool for benchmarks/transport.sh. Its modes and options:
// kUsage below (`lcm_transport --help`).
#include <sys/resource.h>
#include <time.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

namespace {

double now() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

struct Args {
  std::string mode, url = "udpm://239.255.76.67:7860?ttl=0", channel;
  double rate = 1000, seconds = 10;
  int bytes = 200;
  bool none = false;
};

class Counter {
 public:
  void on(const lcm::ReceiveBuffer*, const std::string&) { ++n; }
  long n = 0;
};

}  // namespace

constexpr const char* kUsage =
    "usage: lcm_transport flood|listen [options]\n"
    "What an LCM udpm process pays for traffic it did not subscribe to (issue 17; benchmarks/transport.sh).\n"
    "  flood  --url URL --channel C --rate HZ --bytes B --seconds S\n"
    "         publish B-byte messages on C at HZ (in bursts once per millisecond) for S seconds\n"
    "  listen --url URL (--channel C | --none) --seconds S\n"
    "         subscribe to exactly C (or to nothing, LCM opened) and handle traffic for S seconds;\n"
    "         prints one JSON line: messages handled, CPU seconds (user, system), wall seconds\n"
    "Defaults: --url udpm://239.255.76.67:7860?ttl=0 --rate 1000 --bytes 200 --seconds 10\n";

int main(int argc, char** argv) {
  Args a;
  if (argc >= 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0))
    return std::fputs(kUsage, stdout), 0;
  if (argc < 2) return std::fputs(kUsage, stderr), 2;
  a.mode = argv[1];
  if (a.mode != "flood" && a.mode != "listen")
    return std::fprintf(stderr, "lcm_transport: unknown mode '%s': expected flood or listen\n%s", a.mode.c_str(), kUsage), 2;
  for (int i = 2; i < argc; ++i) {
    const std::string k = argv[i];
    auto v = [&] { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
    if (k == "--url") a.url = v();
    else if (k == "--channel") a.channel = v();
    else if (k == "--rate") a.rate = std::atof(v().c_str());
    else if (k == "--bytes") a.bytes = std::atoi(v().c_str());
    else if (k == "--seconds") a.seconds = std::atof(v().c_str());
    else if (k == "--none") a.none = true;
    else return std::fprintf(stderr, "lcm_transport: unknown argument %s\n", k.c_str()), 2;
  }
  lcm::LCM lcm(a.url);
  if (!lcm.good()) return std::fprintf(stderr, "lcm_transport: cannot open %s\n", a.url.c_str()), 1;
  const double t0 = now();
  if (a.mode == "flood") {
    std::vector<char> buf(std::size_t(a.bytes), 'x');
    long sent = 0;
    timespec next{};
    clock_gettime(CLOCK_MONOTONIC, &next);
    while (now() - t0 < a.seconds) {
      const long due = long((now() - t0) * a.rate);
      while (sent < due) lcm.publish(a.channel, buf.data(), unsigned(buf.size())), ++sent;
      next.tv_nsec += 1'000'000;
      if (next.tv_nsec >= 1'000'000'000) next.tv_nsec -= 1'000'000'000, ++next.tv_sec;
      clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
    }
    std::printf("{\"mode\": \"flood\", \"sent\": %ld, \"seconds\": %.3f}\n", sent, now() - t0);
    return 0;
  }
  Counter c;
  if (!a.none) lcm.subscribe(a.channel, &Counter::on, &c);
  rusage r0{}, r1{};
  getrusage(RUSAGE_SELF, &r0);
  const double w0 = now();
  while (now() - w0 < a.seconds) lcm.handleTimeout(100);
  getrusage(RUSAGE_SELF, &r1);
  auto sec = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  const double user = sec(r1.ru_utime) - sec(r0.ru_utime), sys = sec(r1.ru_stime) - sec(r0.ru_stime);
  std::printf("{\"mode\": \"listen\", \"channel\": \"%s\", \"handled\": %ld, \"user_s\": %.4f, \"sys_s\": %.4f, "
              "\"wall_s\": %.3f, \"cpu_pct\": %.3f}\n",
              a.none ? "" : a.channel.c_str(), c.n, user, sys, now() - w0, 100 * (user + sys) / (now() - w0));
  return 0;
}
