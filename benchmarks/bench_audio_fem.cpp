// FEM modal analysis: frequency error against DOF, solve time and peak memory, Tet4 and Tet10
// (issue 14). Each case runs in a child process so its peak resident set is its own.
// Writes --csv, --json and a Markdown table (--md) for docs/audio.md; benchmarks/run.sh audio.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <functional>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_stamp.hpp"
#include "benchmarks/child_reply.hpp"
#include "clients/audio/analysis/modal_analysis.hpp"
#include "clients/audio/analysis/scene_bodies.hpp"
#include "scenes/materials.hpp"

namespace {

using namespace thx::audio;
using thx::bench::isoNow;
using thx::bench::loadAverage;

const char* const kHelp = R"(usage: bench_audio_fem [--csv FILE] [--json FILE] [--md FILE] [--quick] [--part P]

Modal analysis (clients/audio, ARPACK shift-invert + SimplicialLDLT) of the validation objects of
docs/audio.md at growing mesh sizes, Tet4 and Tet10: DOF, the largest relative frequency error of
the checked modes against the reference, assembly / factorization / Lanczos time (wall clock, one
thread), and the peak resident set of a child process that does only that solve.
  steel bar 0.3 x 0.02 x 0.01 m, free: modes 7-12 vs converged 3D (574.3 ... 3887.6 Hz)
  steel plate 0.3 x 0.3 x 0.005 m, free: modes 1-6 vs Kirchhoff (Leissa, nu = 0.29)
  steel sphere, free: T2 x5 and S2 x5 vs Lamb
Then the shipped scenes' sounding bodies (meshed as clients/audio/analysis/scene_bodies.cpp does, Tet10), at
their shipped mesh size and finer, each against its finest mesh (the reference; the next-finest row
shows how far that one still moves): the surface slab (0.2 x 0.2 x 0.01 m brick, free: the first
30 elastic modes), the pen (plastic cylinder r 5 mm x 12 cm), the marble (glass sphere r 8 mm), a
letter block (wood box 2 x 2 x 1 cm) (first 20 elastic modes each).
Then (part solver) the solve's settings on the shipped slab and on 24 x 24 x 2: the factorization
of K - sigma M (CHOLMOD supernodal, the default, against Eigen's SimplicialLDLT), the shift and
the Lanczos vectors (ncv), each against the default settings' frequencies.
  --quick   only the smaller meshes (a smoke run)
  --part P  validation, objects, solver or all (default all)
  -h, --help
)";

struct Case {
  std::string object, element;
  int size;  // layers through the bar/plate thickness, cells per side of the sphere
};

// One solve, done in a child process: its DOF, times and elastic frequencies (Hz, ascending).
struct Solve {
  int dofs = 0, applications = 0;
  double assemble_s = 0, factor_s = 0, iterate_s = 0, total_s = 0;  // CPU time, but total_s: wall
  double cpu_s = 0;  // the child's CPU time: mesh, assembly, factor, Lanczos
  std::vector<double> hz;
  long peak_rss_kb = 0;
  bool ok = false;
  std::string error;
};

struct Outcome {
  int dofs = 0, modes = 0, applications = 0;
  double max_error = 0, first_error = 0;
  double assemble_s = 0, factor_s = 0, iterate_s = 0, total_s = 0, cpu_s = 0;
  long peak_rss_kb = 0;
  bool ok = false;
  std::string error;
};

// The Markdown tables' cost columns: CPU time by stage (the machine's 2 CPUs are shared with other
// work, which stretches the wall clock but hardly the CPU time), the child's CPU and wall total.
const char* const kTimeColumns =
    "assemble CPU s | factor CPU s | Lanczos CPU s | total CPU s | wall s | peak RSS MB |\n"
    "|---|---|---|---|---|---|---|---|---|---|---|---|\n";

ElasticMaterial material(const char* name) { return *thx::scene::findMaterial(name); }

struct Problem {
  TetMesh mesh;
  ElasticMaterial material;
  int modes = 0;
  ModalSettings settings{};  // its elastic_modes is set from `modes`
};

// Runs make() and the modal analysis in a child; the child reports through a pipe, wait4 gives
// its peak RSS (the mesh, K, M, the factor and the Lanczos vectors of that solve alone).
Solve solveIsolated(const std::function<Problem()>& make) {
  int fd[2];
  if (pipe(fd) != 0) {
    Solve failed;
    failed.error = "pipe failed";
    return failed;
  }
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    std::ostringstream line;
    line.precision(12);
    try {
      const Problem p = make();
      ModalSettings s = p.settings;
      s.elastic_modes = p.modes;
      const ModalSolution sol = analyse(p.mesh, p.material, s);
      line << sol.free_dofs << ' ' << sol.operator_applications << ' ' << sol.assemble_cpu_s << ' '
           << sol.factor_cpu_s << ' ' << sol.iterate_cpu_s << ' ' << sol.total_s << ' ' << processCpuSeconds() << ' '
           << sol.omega_rad_per_s.size();
      for (Eigen::Index k = 0; k < sol.omega_rad_per_s.size(); ++k) line << ' ' << sol.frequencyHz(int(k));
      line << '\n';
    } catch (const std::exception& e) {
      line.str(std::string("error ") + e.what() + "\n");
    }
    const std::string text = line.str();
    if (write(fd[1], text.data(), text.size()) < 0) _exit(2);
    _exit(0);
  }
  close(fd[1]);
  const thx::bench::ChildReply reply = thx::bench::readChildReply(pid, fd[0]);
  const std::string& text = reply.text;
  Solve o;
  o.peak_rss_kb = reply.peak_rss_kb;
  if (text.rfind("error ", 0) == 0 || text.empty()) {
    o.error = text.empty() ? "child failed" : text.substr(6);
    return o;
  }
  std::istringstream in(text);
  std::size_t count = 0;
  in >> o.dofs >> o.applications >> o.assemble_s >> o.factor_s >> o.iterate_s >> o.total_s >> o.cpu_s >> count;
  o.hz.resize(count);
  for (double& f : o.hz) in >> f;
  o.ok = bool(in);
  return o;
}

// Errors of `hz` against `reference`, mode by mode in ascending order (for two sorted lists this
// pairing gives the smallest largest error, so a near-degenerate pair ordered differently on two
// meshes costs nothing).
void compare(const std::vector<double>& hz, const std::vector<double>& reference, Outcome& o) {
  o.modes = int(std::min(hz.size(), reference.size()));
  o.max_error = 0;
  for (int k = 0; k < o.modes; ++k) {
    const double e = hz[std::size_t(k)] / reference[std::size_t(k)] - 1;
    o.max_error = std::max(o.max_error, std::fabs(e));
    if (k == 0) o.first_error = e;  // signed: stiff meshes err high
  }
}

Outcome fromSolve(const Solve& s) {
  Outcome o;
  o.dofs = s.dofs, o.assemble_s = s.assemble_s, o.factor_s = s.factor_s, o.iterate_s = s.iterate_s;
  o.total_s = s.total_s, o.cpu_s = s.cpu_s, o.applications = s.applications;
  o.peak_rss_kb = s.peak_rss_kb, o.ok = s.ok, o.error = s.error;
  return o;
}

// A validation object against its analytic or converged reference (docs/audio.md §8).
Outcome runValidation(const Case& c) {
  const ElementOrder order = c.element == "tet4" ? ElementOrder::Linear : ElementOrder::Quadratic;
  const ElasticMaterial m = material("steel");
  std::vector<double> reference;
  double scale = 1.0;  // Hz -> the reference's unit
  std::function<Problem()> make;
  if (c.object == "bar") {
    reference = {574.3, 1135.2, 1572.0, 3044.7, 3051.2, 3887.6};
    make = [&] { return Problem{boxMesh("bar", {0.3, 0.02, 0.01}, {30 * c.size, 2 * c.size, c.size}, order), m, 6}; };
  } else if (c.object == "plate") {
    const double d = m.youngs_modulus_pa * std::pow(0.005, 3) / (12 * (1 - m.poisson_ratio * m.poisson_ratio));
    for (double lambda : {13.557, 19.706, 24.221, 34.967, 34.967, 61.137})
      reference.push_back(lambda / (2 * std::numbers::pi * 0.09) * std::sqrt(d / (m.density_kg_per_m3 * 0.005)));
    make = [&] {
      return Problem{slabMesh("plate", 0.3, 0.3, 0.005, {16 * c.size, 16 * c.size, c.size}, order, false), m, 6};
    };
  } else {
    reference = {2.5011, 2.5011, 2.5011, 2.5011, 2.5011, 2.6450, 2.6450, 2.6450, 2.6450, 2.6450};
    const double cs = std::sqrt(m.youngs_modulus_pa / (2 * (1 + m.poisson_ratio)) / m.density_kg_per_m3);
    scale = 2 * std::numbers::pi * 0.1 / cs;  // Hz -> eta = omega a / c_s
    make = [&] { return Problem{sphereMesh("sphere", 0.1, c.size, order), m, 10}; };
  }
  const Solve s = solveIsolated(make);
  Outcome o = fromSolve(s);
  if (!o.ok) return o;
  std::vector<double> scaled = s.hz;
  for (double& f : scaled) f *= scale;
  compare(scaled, reference, o);
  return o;
}

// A shipped scene's sounding body at one mesh size.
struct BodySize {
  std::string label;  // the mesh, e.g. "16x16x1"
  std::function<TetMesh()> mesh;
  bool shipped = false;  // the size scene_bodies.cpp uses
};

struct SceneObject {
  std::string object, material, scenes;
  int modes = 20;
  std::vector<BodySize> sizes;  // coarse to fine; the last is the reference
};

std::vector<SceneObject> sceneObjects(bool quick) {
  const ElementOrder q = ElementOrder::Quadratic;
  std::vector<SceneObject> objects;
  {  // surface.size 0.2 x 0.2, thickness 1 cm (the default), free: every shipped scene
    SceneObject slab{"surface slab 0.2 x 0.2 x 0.01 m, free", "brick", "all (default: brick)", 30, {}};
    auto s = [&](int n, int layers) {
      return BodySize{std::to_string(n) + "x" + std::to_string(n) + "x" + std::to_string(layers),
                      [=] { return slabMesh("surface", 0.2, 0.2, 0.01, {n, n, layers}, q, false); },
                      n == kSlabCells && layers == kSlabLayers};
    };
    // 16x16x1: the size shipped before; 32x32x2 against the 3-layer reference bounds its own error.
    slab.sizes = quick ? std::vector<BodySize>{s(8, 1), s(8, 2)}
                       : std::vector<BodySize>{s(16, 1), s(16, 2), s(20, 2), s(24, 2), s(32, 2), s(32, 3)};
    objects.push_back(slab);
  }
  {  // device.pen: r 5 mm, 12 cm; cells across, cubes along (cellsAlong(l, r))
    SceneObject pen{"pen, cylinder r 5 mm x 12 cm", "plastic", "all (device.pen)", 20, {}};
    auto s = [&](int n, bool shipped = false) {
      return BodySize{std::to_string(n) + "x" + std::to_string(n) + "x" + std::to_string(12 * n),
                      [=] { return cylinderMesh("pen", 0.005, 0.12, n, 12 * n, q); }, shipped};
    };
    pen.sizes = quick ? std::vector<BodySize>{s(2, true), s(3)} : std::vector<BodySize>{s(2, true), s(3), s(4)};
    objects.push_back(pen);
  }
  {  // sphere: kSphereCells per side; frequencies scale as 1/r, so one radius stands for all
    SceneObject ball{"sphere (marble r 8 mm)", "glass", "default, marble_*, dimple_ball, pen_pushes_ball*, pinball, zigzag_street", 20, {}};
    auto s = [&](int n) {
      return BodySize{std::to_string(n) + " per side", [=] { return sphereMesh("marble", 0.008, n, q); },
                      n == kSphereCells};
    };
    ball.sizes = quick ? std::vector<BodySize>{s(2), s(4)} : std::vector<BodySize>{s(4), s(5), s(6), s(8)};
    objects.push_back(ball);
  }
  {  // box: cubes as near as its edges allow, kBoxCellsShortest on the shortest edge
    SceneObject box{"box (letter block 2 x 2 x 1 cm)", "wood", "letter_blocks", 20, {}};
    auto s = [&](int n) {
      return BodySize{std::to_string(2 * n) + "x" + std::to_string(2 * n) + "x" + std::to_string(n),
                      [=] { return boxMesh("A", {0.02, 0.02, 0.01}, {2 * n, 2 * n, n}, q); }, n == kBoxCellsShortest};
    };
    // 2x2x1: the size shipped before.
    box.sizes = quick ? std::vector<BodySize>{s(1), s(2)} : std::vector<BodySize>{s(1), s(3), s(4), s(5), s(6)};
    objects.push_back(box);
  }
  return objects;
}

// The solver's settings compared on one slab (the same modes every time; the error column is the
// largest difference from the default settings' frequencies, so it shows they agree).
struct SolverVariant {
  std::string label;
  ModalSettings settings;
};

std::vector<SolverVariant> solverVariants() {
  std::vector<SolverVariant> v;
  ModalSettings s;  // the defaults: CHOLMOD, shift 20 Hz, ncv max(2 nev + 1, nev + 40)
  v.push_back({"CHOLMOD supernodal (default)", s});
  ModalSettings ldlt = s;
  ldlt.factorization = Factorization::SimplicialLdlt;
  v.push_back({"Eigen SimplicialLDLT, AMD", ldlt});
  for (double hz : {200.0, 400.0}) {
    ModalSettings shifted = s;
    shifted.shift_hz = hz;
    v.push_back({"CHOLMOD, shift " + std::to_string(int(hz)) + " Hz", shifted});
  }
  for (int ncv : {50, 100}) {
    ModalSettings lanczos = s;
    lanczos.lanczos_vectors = ncv;
    v.push_back({"CHOLMOD, ncv " + std::to_string(ncv), lanczos});
  }
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  thx::bench::exitOnHelp(argc, argv, kHelp);
  std::string csv, json, md, part = "all";
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
    else if (a == "--part") {
      part = value();
      if (part != "all" && part != "validation" && part != "objects" && part != "solver") {
        std::fprintf(stderr, "bench_audio_fem: --part: expected validation, objects, solver or all, got '%s'\n",
                     part.c_str());
        return 2;
      }
    } else {
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
  if (part == "objects" || part == "solver") cases.clear();
  const std::string started = isoNow(), load = loadAverage();
  std::ostringstream csv_text, json_text, md_text, md_objects;
  csv_text << "part,object,element,size,dofs,modes,max_rel_error,first_rel_error,op_applications,assemble_cpu_s,"
              "factor_cpu_s,iterate_cpu_s,cpu_s,wall_s,peak_rss_mb\n";
  json_text << "{\n  \"machine\": \"" << thx::bench::machineSummary() << "\",\n  \"measured\": \"" << started
            << "\",\n  \"load_average\": \"" << load << "\",\n  \"build_type\": \"" << thx::bench::buildType()
            << "\",\n  \"cases\": [\n";
  md_text << "Measured " << started << " (" << long(sysconf(_SC_NPROCESSORS_ONLN)) << " CPUs, load average " << load
          << " at start), one thread, RelWithDebInfo (-O2), `bench_audio_fem"
          << (quick ? " --quick" : "") << (part != "all" ? " --part " + part : std::string()) << "`.";
  bool first = true;
  // One result: a CSV line, a JSON object, a Markdown row.
  auto record = [&](const char* part_name, const std::string& object, const std::string& element, const std::string& size,
                    const Outcome& o, std::ostringstream& md_out, const std::string& note) {
    const double rss_mb = double(o.peak_rss_kb) / 1024.0;
    char line[1024];
    std::snprintf(line, sizeof line, "%s,\"%s\",%s,%s,%d,%d,%.6g,%.6g,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.1f\n", part_name,
                  object.c_str(), element.c_str(), size.c_str(), o.dofs, o.modes, o.max_error, o.first_error,
                  o.applications, o.assemble_s, o.factor_s, o.iterate_s, o.cpu_s, o.total_s, rss_mb);
    csv_text << line;
    std::snprintf(line, sizeof line,
                  "%s    {\"part\": \"%s\", \"object\": \"%s\", \"element\": \"%s\", \"size\": \"%s\", \"dofs\": %d, "
                  "\"modes\": %d, \"max_rel_error\": %.6g, \"first_rel_error\": %.6g, \"op_applications\": %d, "
                  "\"assemble_cpu_s\": %.4f, \"factor_cpu_s\": %.4f, \"iterate_cpu_s\": %.4f, \"cpu_s\": %.4f, "
                  "\"wall_s\": %.4f, \"peak_rss_mb\": %.1f}",
                  first ? "" : ",\n", part_name, object.c_str(), element.c_str(), size.c_str(), o.dofs, o.modes,
                  o.max_error, o.first_error, o.applications, o.assemble_s, o.factor_s, o.iterate_s, o.cpu_s, o.total_s,
                  rss_mb);
    json_text << line;
    first = false;
    std::string error = note;
    if (error.empty()) {
      std::snprintf(line, sizeof line, "%.2f %% | %+.2f %%", 100 * o.max_error, 100 * o.first_error);
      error = line;
    }
    std::snprintf(line, sizeof line, "| %s | %s | %s | %d | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.0f |\n",
                  object.c_str(), element.c_str(), size.c_str(), o.dofs, error.c_str(), o.assemble_s, o.factor_s,
                  o.iterate_s, o.cpu_s, o.total_s, rss_mb);
    md_out << line;
    std::fputs(line, stdout);
    std::fflush(stdout);
  };

  if (!cases.empty()) {
    md_text << "\n\nValidation objects (steel). Size: elements through the thickness (bar: 30n x 2n x n cells; plate: "
               "16n x 16n x n), cells per side of the sphere's cube. Error: the largest relative error of the checked "
               "modes (bar 7-12 vs converged 3D, plate 1-6 vs Kirchhoff, sphere T2/S2 x5 vs Lamb). Peak RSS: the child "
               "process that did only that solve.\n\n"
            << "| object | element | size | DOF | max error | first mode error | " << kTimeColumns;
  }
  for (const Case& c : cases) {
    std::fprintf(stderr, "bench_audio_fem: %s %s %d ...\n", c.object.c_str(), c.element.c_str(), c.size);
    const Outcome o = runValidation(c);
    if (!o.ok) {
      std::fprintf(stderr, "bench_audio_fem: %s %s %d failed: %s\n", c.object.c_str(), c.element.c_str(), c.size,
                   o.error.c_str());
      continue;
    }
    record("validation", c.object, c.element == "tet4" ? "Tet4" : "Tet10", std::to_string(c.size), o, md_text, "");
  }

  if (part == "all" || part == "objects") {
    md_objects << (cases.empty() ? "\n\n" : "\n") << "The shipped scenes' sounding bodies, Tet10, meshed as `clients/audio/analysis/scene_bodies.cpp` does "
                  "(**bold**: the size it uses), each against its finest mesh (the reference row; the row above it "
                  "shows how much the last refinement still moved). Error: the largest relative error of the first "
                  "N elastic modes, in ascending order, against the reference's. Frequencies scale as 1/size, so one "
                  "sphere stands for every ball of the scenes (ν of glass 0.20, steel 0.29: the marble's is shown).\n\n"
               << "| body (material; N modes) | element | cells | DOF | max error | first mode error | " << kTimeColumns;
    for (const SceneObject& obj : sceneObjects(quick)) {
      std::vector<Solve> solves;
      for (const BodySize& b : obj.sizes) {
        std::fprintf(stderr, "bench_audio_fem: %s %s ...\n", obj.object.c_str(), b.label.c_str());
        const ElasticMaterial m = material(obj.material.c_str());
        solves.push_back(solveIsolated([&] { return Problem{b.mesh(), m, obj.modes}; }));
        if (!solves.back().ok)
          std::fprintf(stderr, "bench_audio_fem: %s %s failed: %s\n", obj.object.c_str(), b.label.c_str(),
                       solves.back().error.c_str());
      }
      const Solve& ref = solves.back();
      if (!ref.ok) continue;
      const std::string name = obj.object + " (" + obj.material + "; " + std::to_string(obj.modes) + ")";
      for (std::size_t k = 0; k < solves.size(); ++k) {
        if (!solves[k].ok) continue;
        Outcome o = fromSolve(solves[k]);
        const bool is_ref = k + 1 == solves.size();
        if (!is_ref) compare(solves[k].hz, ref.hz, o);
        else o.modes = int(ref.hz.size());
        char lowest[64];
        std::snprintf(lowest, sizeof lowest, "reference | lowest %.0f Hz", ref.hz.empty() ? 0.0 : ref.hz[0]);
        const std::string label = obj.sizes[k].shipped ? "**" + obj.sizes[k].label + "**" : obj.sizes[k].label;
        record("objects", name, "Tet10", label, o, md_objects, is_ref ? lowest : "");
      }
    }
  }
  std::ostringstream md_solver;
  if (part == "all" || part == "solver") {
    md_solver << "\nThe solve's settings, the surface slab (brick, 30 elastic modes + 6 rigid): the factorization of "
                 "K - sigma M, the shift, the Lanczos vectors (ncv; default max(2 nev + 1, nev + 40) = 76). Error: the "
                 "largest difference from the first row's frequencies. OP: applications of (K - sigma M)^-1 M.\n\n"
              << "| slab, settings | element | cells | DOF | max difference | OP | " << kTimeColumns;
    const std::vector<std::pair<int, int>> slabs =
        quick ? std::vector<std::pair<int, int>>{{8, 2}}
              : std::vector<std::pair<int, int>>{{kSlabCells, kSlabLayers}, {24, 2}};
    for (const auto& [cells, layers] : slabs) {
      const std::string label = std::to_string(cells) + "x" + std::to_string(cells) + "x" + std::to_string(layers);
      std::vector<double> reference;
      for (const SolverVariant& v : solverVariants()) {
        std::fprintf(stderr, "bench_audio_fem: solver %s, %s ...\n", label.c_str(), v.label.c_str());
        const ElasticMaterial m = material("brick");
        const Solve s = solveIsolated([&] {
          return Problem{slabMesh("surface", 0.2, 0.2, 0.01, {cells, cells, layers}, ElementOrder::Quadratic, false), m,
                         30, v.settings};
        });
        if (!s.ok) {
          std::fprintf(stderr, "bench_audio_fem: solver %s failed: %s\n", v.label.c_str(), s.error.c_str());
          continue;
        }
        Outcome o = fromSolve(s);
        if (reference.empty()) reference = s.hz;
        compare(s.hz, reference, o);
        char diff[64];
        std::snprintf(diff, sizeof diff, "%.1e | %d", o.max_error, o.applications);
        record("solver", v.label, "Tet10", label, o, md_solver, diff);
      }
    }
  }
  json_text << "\n  ]\n}\n";
  md_text << md_objects.str() << md_solver.str();
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
