// FEM modal analysis: frequency error against DOF, solve time and peak memory, Tet4 and Tet10
// (issue 14). Each case runs in a child process so its peak resident set is its own.
// Writes --csv, --json and a Markdown table (--md) for docs/audio.md; benchmarks/run.sh audio.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_stamp.hpp"
#include "benchmarks/child_reply.hpp"
#include "clients/audio/modal_analysis.hpp"
#include "scenes/materials.hpp"

namespace {

using namespace thx::audio;
using thx::bench::isoNow;
using thx::bench::loadAverage;

const char* const kHelp = R"(usage: bench_audio_fem [--csv FILE] [--json FILE] [--md FILE] [--quick]

Modal analysis (clients/audio, ARPACK shift-invert + SimplicialLDLT) of the validation objects of
docs/audio.md at growing mesh sizes, Tet4 and Tet10: DOF, the largest relative frequency error of
the checked modes against the reference, assembly / factorization / Lanczos time (wall clock, one
thread), and the peak resident set of a child process that does only that solve.
  steel bar 0.3 x 0.02 x 0.01 m, free: modes 7-12 vs converged 3D (574.3 ... 3887.6 Hz)
  steel plate 0.3 x 0.3 x 0.005 m, free: modes 1-6 vs Kirchhoff (Leissa, nu = 0.29)
  steel sphere, free: T2 x5 and S2 x5 vs Lamb
  --quick   only the smaller meshes (a smoke run)
  -h, --help
)";

struct Case {
  std::string object, element;
  int size;  // layers through the bar/plate thickness, cells per side of the sphere
};

struct Outcome {
  int dofs = 0, modes = 0;
  double max_error = 0, first_error = 0;
  double assemble_s = 0, factor_s = 0, iterate_s = 0, total_s = 0;
  long peak_rss_kb = 0;
  bool ok = false;
  std::string error;
};

ElasticMaterial steel() { return *thx::scene::findMaterial("steel"); }

// Solves one case and returns the frequencies' relative errors.
Outcome solveCase(const Case& c) {
  const ElementOrder order = c.element == "tet4" ? ElementOrder::Linear : ElementOrder::Quadratic;
  const ElasticMaterial m = steel();
  ModalSettings s;
  TetMesh mesh;
  std::vector<double> reference;
  double scale = 1.0 / (2 * std::numbers::pi);  // omega -> Hz
  if (c.object == "bar") {
    mesh = boxMesh("bar", {0.3, 0.02, 0.01}, {30 * c.size, 2 * c.size, c.size}, order);
    reference = {574.3, 1135.2, 1572.0, 3044.7, 3051.2, 3887.6};
  } else if (c.object == "plate") {
    mesh = slabMesh("plate", 0.3, 0.3, 0.005, {16 * c.size, 16 * c.size, c.size}, order, false);
    const double d = m.youngs_modulus_pa * std::pow(0.005, 3) / (12 * (1 - m.poisson_ratio * m.poisson_ratio));
    for (double lambda : {13.557, 19.706, 24.221, 34.967, 34.967, 61.137})
      reference.push_back(lambda / (2 * std::numbers::pi * 0.09) * std::sqrt(d / (m.density_kg_per_m3 * 0.005)));
  } else {
    mesh = sphereMesh("sphere", 0.1, c.size, order);
    reference = {2.5011, 2.5011, 2.5011, 2.5011, 2.5011, 2.6450, 2.6450, 2.6450, 2.6450, 2.6450};
    const double cs = std::sqrt(m.youngs_modulus_pa / (2 * (1 + m.poisson_ratio)) / m.density_kg_per_m3);
    scale = 0.1 / cs;  // omega -> eta = omega a / c_s
  }
  s.elastic_modes = int(reference.size());
  Outcome o;
  const ModalSolution sol = analyse(mesh, m, s);
  o.dofs = sol.free_dofs;
  o.modes = int(reference.size());
  for (std::size_t k = 0; k < reference.size(); ++k) {
    const double e = sol.omega_rad_per_s[Eigen::Index(k)] * scale / reference[k] - 1;
    o.max_error = std::max(o.max_error, std::fabs(e));
    if (k == 0) o.first_error = e;  // signed: linear tets err high
  }
  o.assemble_s = sol.assemble_s, o.factor_s = sol.factor_s, o.iterate_s = sol.iterate_s, o.total_s = sol.total_s;
  o.ok = true;
  return o;
}

// Runs solveCase in a child; the child reports through a pipe, wait4 gives its peak RSS.
Outcome runIsolated(const Case& c) {
  int fd[2];
  if (pipe(fd) != 0) return {.error = "pipe failed"};
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    std::string line;
    try {
      const Outcome o = solveCase(c);
      char buf[512];
      std::snprintf(buf, sizeof buf, "%d %d %.9g %.9g %.6f %.6f %.6f %.6f\n", o.dofs, o.modes, o.max_error,
                    o.first_error, o.assemble_s, o.factor_s, o.iterate_s, o.total_s);
      line = buf;
    } catch (const std::exception& e) {
      line = std::string("error ") + e.what() + "\n";
    }
    if (write(fd[1], line.data(), line.size()) < 0) _exit(2);
    _exit(0);
  }
  close(fd[1]);
  const thx::bench::ChildReply reply = thx::bench::readChildReply(pid, fd[0]);
  const std::string& text = reply.text;
  Outcome o;
  o.peak_rss_kb = reply.peak_rss_kb;
  if (text.rfind("error ", 0) == 0 || text.empty()) {
    o.error = text.empty() ? "child failed" : text.substr(6);
    return o;
  }
  std::istringstream in(text);
  in >> o.dofs >> o.modes >> o.max_error >> o.first_error >> o.assemble_s >> o.factor_s >> o.iterate_s >> o.total_s;
  o.ok = bool(in);
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  thx::bench::exitOnHelp(argc, argv, kHelp);
  std::string csv, json, md;
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "bench_audio_fem: %s: missing value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--csv") csv = value();
    else if (a == "--json") json = value();
    else if (a == "--md") md = value();
    else if (a == "--quick") quick = true;
    else {
      std::fprintf(stderr, "bench_audio_fem: unknown option '%s' (--help lists them)\n", a.c_str());
      return 2;
    }
  }
  std::vector<Case> cases{{"bar", "tet4", 1}, {"bar", "tet4", 2}, {"bar", "tet4", 4}, {"bar", "tet10", 1},
                          {"bar", "tet10", 2}, {"plate", "tet4", 1}, {"plate", "tet10", 1}, {"sphere", "tet4", 4},
                          {"sphere", "tet4", 8}, {"sphere", "tet10", 2}, {"sphere", "tet10", 4}};
  if (!quick) {
    for (const Case& c : std::vector<Case>{{"bar", "tet4", 6}, {"bar", "tet10", 3}, {"plate", "tet4", 2},
                                           {"plate", "tet10", 2}, {"sphere", "tet4", 12}, {"sphere", "tet10", 6}})
      cases.push_back(c);
  }
  const std::string started = isoNow(), load = loadAverage();
  std::ostringstream csv_text, json_text, md_text;
  csv_text << "object,element,size,dofs,modes,max_rel_error,first_rel_error,assemble_s,factor_s,iterate_s,total_s,peak_rss_mb\n";
  json_text << "{\n  \"measured\": \"" << started << "\",\n  \"load_average\": \"" << load << "\",\n  \"cases\": [\n";
  md_text << "Measured " << started << " (" << long(sysconf(_SC_NPROCESSORS_ONLN)) << " CPUs, load average " << load
          << " at start), one thread, RelWithDebInfo (-O2). Size: elements through the thickness (bar: 30n x 2n x n "
             "cells; plate: 16n x 16n x n), cells per side of the sphere's cube. Error: the largest relative error "
             "of the checked modes (bar 7-12 vs converged 3D, plate 1-6 vs Kirchhoff, sphere T2/S2 x5 vs Lamb). "
             "Peak RSS: the child process that did only that solve.\n\n"
          << "| object | element | size | DOF | max error | first mode error | assemble s | factor s | Lanczos s | "
             "total s | peak RSS MB |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  bool first = true;
  for (const Case& c : cases) {
    std::fprintf(stderr, "bench_audio_fem: %s %s %d ...\n", c.object.c_str(), c.element.c_str(), c.size);
    const Outcome o = runIsolated(c);
    if (!o.ok) {
      std::fprintf(stderr, "bench_audio_fem: %s %s %d failed: %s\n", c.object.c_str(), c.element.c_str(), c.size,
                   o.error.c_str());
      continue;
    }
    const double rss_mb = double(o.peak_rss_kb) / 1024.0;
    char line[512];
    std::snprintf(line, sizeof line, "%s,%s,%d,%d,%d,%.6g,%.6g,%.4f,%.4f,%.4f,%.4f,%.1f\n", c.object.c_str(),
                  c.element.c_str(), c.size, o.dofs, o.modes, o.max_error, o.first_error, o.assemble_s, o.factor_s,
                  o.iterate_s, o.total_s, rss_mb);
    csv_text << line;
    std::snprintf(line, sizeof line,
                  "%s    {\"object\": \"%s\", \"element\": \"%s\", \"size\": %d, \"dofs\": %d, \"modes\": %d, "
                  "\"max_rel_error\": %.6g, \"first_rel_error\": %.6g, \"assemble_s\": %.4f, \"factor_s\": %.4f, "
                  "\"iterate_s\": %.4f, \"total_s\": %.4f, \"peak_rss_mb\": %.1f}",
                  first ? "" : ",\n", c.object.c_str(), c.element.c_str(), c.size, o.dofs, o.modes, o.max_error,
                  o.first_error, o.assemble_s, o.factor_s, o.iterate_s, o.total_s, rss_mb);
    json_text << line;
    first = false;
    std::snprintf(line, sizeof line, "| %s | %s | %d | %d | %.2f %% | %+.2f %% | %.2f | %.2f | %.2f | %.2f | %.0f |\n",
                  c.object.c_str(), c.element == "tet4" ? "Tet4" : "Tet10", c.size, o.dofs, 100 * o.max_error,
                  100 * o.first_error, o.assemble_s, o.factor_s, o.iterate_s, o.total_s, rss_mb);
    md_text << line;
    std::fputs(line, stdout);
  }
  json_text << "\n  ]\n}\n";
  auto save = [](const std::string& path, const std::string& text) {
    if (path.empty()) return;
    std::ofstream out(path);
    out << text;
    if (!out) std::fprintf(stderr, "bench_audio_fem: %s: cannot be written\n", path.c_str());
  };
  save(csv, csv_text.str());
  save(json, json_text.str());
  save(md, md_text.str());
  return 0;
}
