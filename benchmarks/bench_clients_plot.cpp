// Part 5b of docs/benchmarks.md (issue 17): the plot of bench_clients' sweeps. Reads the per-client
// CSVs that `bench_clients --clients-list ... --csv F` writes and draws, against the number of
// clients N: the CPU per client (mean over each class: batched CONTACT at 1 kHz, DEVICE_STATE at
// 60 Hz), hapticd's CPU, and the worst delivered share. A client's cost that follows its own
// subscription is a flat line; one that grows with N pays for the others' traffic.
//
// Usage: bench_clients_plot --png OUT.png LABEL=FILE.csv [LABEL=FILE.csv ...]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tools/report/plot.hpp"

namespace {

using thx::bench::Marker;
using thx::bench::PlotPanel;
using thx::bench::PlotSeries;
using thx::bench::Rgb;

[[noreturn]] void usage(const std::string& why) {
  std::fprintf(stderr, "bench_clients_plot: %s\nusage: bench_clients_plot --png OUT.png LABEL=FILE.csv [...]\n",
               why.c_str());
  std::exit(2);
}

struct Point {  // one N of one sweep
  double cpu_batch = 0, cpu_state = 0, server_cpu = 0, worst_delivered = 1;
  int n_batch = 0, n_state = 0;
};

// N -> point, from bench_clients' CSV (header names the columns).
std::map<int, Point> readSweep(const std::string& path) {
  std::ifstream in(path);
  if (!in) usage("cannot read '" + path + "'");
  std::string line;
  std::getline(in, line);
  std::map<std::string, std::size_t> col;
  {
    std::stringstream h(line);
    std::string name;
    for (std::size_t k = 0; std::getline(h, name, ','); ++k) col[name] = k;
  }
  for (const char* need : {"n", "batch", "cpu_pct", "delivered", "server_cpu_pct"}) {
    if (!col.count(need)) usage("'" + path + "' has no column '" + need + "': expected a bench_clients sweep CSV");
  }
  std::map<int, Point> sweep;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) f.push_back(cell);
    if (f.size() < col.size()) continue;
    Point& p = sweep[std::stoi(f[col["n"]])];
    const double cpu = std::stod(f[col["cpu_pct"]]);
    if (f[col["batch"]] == "1") {
      p.cpu_batch += cpu;
      ++p.n_batch;
    } else {
      p.cpu_state += cpu;
      ++p.n_state;
    }
    p.server_cpu = std::stod(f[col["server_cpu_pct"]]);
    p.worst_delivered = std::min(p.worst_delivered, std::stod(f[col["delivered"]]));
  }
  for (auto& [n, p] : sweep) {
    if (p.n_batch) p.cpu_batch /= p.n_batch;
    if (p.n_state) p.cpu_state /= p.n_state;
  }
  return sweep;
}

}  // namespace

int main(int argc, char** argv) {
  std::string png;
  std::vector<std::pair<std::string, std::string>> inputs;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      std::puts("usage: bench_clients_plot --png OUT.png LABEL=FILE.csv [LABEL=FILE.csv ...]\n"
                "Plots bench_clients sweeps: CPU per client, hapticd's CPU and the worst delivered share against N.");
      return 0;
    }
    if (a == "--png") {
      if (i + 1 >= argc) usage("--png needs a value");
      png = argv[++i];
    } else if (a.find('=') != std::string::npos) {
      inputs.emplace_back(a.substr(0, a.find('=')), a.substr(a.find('=') + 1));
    } else {
      usage("unexpected argument '" + a + "': expected --png OUT.png or LABEL=FILE.csv");
    }
  }
  if (png.empty() || inputs.empty()) usage("--png and at least one LABEL=FILE.csv are required");

  const Rgb colors[] = {{31, 119, 180}, {214, 39, 40}, {44, 160, 44}, {148, 103, 189}, {255, 127, 14}, {23, 190, 207}};
  PlotPanel cpu{"CPU per client (mean of its class)", "clients N", "CPU % of one core", true, true, 1, 64, 0.1, 100, {}};
  PlotPanel server{"hapticd CPU", "clients N", "CPU % of one core", true, false, 1, 64, 0, 60, {}};
  PlotPanel delivered{"worst delivered share", "clients N", "% of messages / samples", true, false, 1, 64, 0, 100, {}};
  double max_n = 1, max_cpu = 1, max_server = 10;
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    const auto sweep = readSweep(inputs[k].second);
    const Rgb c = colors[k % 6];
    PlotSeries b{inputs[k].first + " 1k", c, Marker::Square, true, true, {}, {}, {}};
    PlotSeries s{inputs[k].first + " 60Hz", c, Marker::Circle, false, true, {}, {}, {}};
    PlotSeries h{inputs[k].first, c, Marker::Circle, true, true, {}, {}, {}};
    PlotSeries d{inputs[k].first, c, Marker::Circle, true, true, {}, {}, {}};
    for (const auto& [n, p] : sweep) {
      max_n = std::max(max_n, double(n));
      if (p.n_batch && p.cpu_batch > 0) b.x.push_back(n), b.y.push_back(p.cpu_batch);
      if (p.n_state && p.cpu_state > 0) s.x.push_back(n), s.y.push_back(p.cpu_state);
      max_cpu = std::max({max_cpu, p.cpu_batch, p.cpu_state});
      h.x.push_back(n), h.y.push_back(p.server_cpu);
      max_server = std::max(max_server, p.server_cpu);
      d.x.push_back(n), d.y.push_back(100 * p.worst_delivered);
    }
    if (!b.x.empty()) cpu.series.push_back(b);
    if (!s.x.empty()) cpu.series.push_back(s);
    server.series.push_back(h);
    delivered.series.push_back(d);
  }
  for (PlotPanel* p : {&cpu, &server, &delivered}) p->x_max = max_n;
  cpu.y_max = std::pow(10.0, std::ceil(std::log10(max_cpu)));
  server.y_max = 10 * std::ceil(max_server / 10);
  try {
    thx::bench::writePlotPng(png, {cpu, server, delivered},
                             "bench_clients sweeps (issue 17) against the number of clients N. Left: squares = batched "
                             "CONTACT at 1 kHz, open circles = DEVICE_STATE at 60 Hz",
                             560, 480);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_clients_plot: %s\n", e.what());
    return 1;
  }
  std::printf("bench_clients_plot: wrote %s\n", png.c_str());
  return 0;
}
