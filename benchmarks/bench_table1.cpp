// The paper's Table 1 on one surface, side by side in one run (issue 16): size, offline memory of
// modal analysis, runtime memory of sound synthesis, physics / visual / haptic time for the scene's
// texture as a normal map and a relief map and as meshes of 256² and 512² quads, with the paper's
// figures beside ours and every cell as a ratio to the normal map. docs/table1.md defines every
// column; benchmarks/run.sh BUILD table1 runs it. Measures, never asserts.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"
#include "benchmarks/bench_stamp.hpp"
#include "benchmarks/table1_modal.hpp"
#include "benchmarks/table1_senses.hpp"
#include "clients/audio/analysis/scene_bodies.hpp"
#include "tools/report/table1_table.hpp"
#include "clients/visual/headless_context.hpp"

namespace {

using namespace thx;
using namespace thx::bench;
using namespace thx::bench::table1;

const char* const kHelp = R"(usage: bench_table1 [--scene FILE] [--md FILE] [--csv FILE] [--workdir DIR] [options]

The paper's Table 1 on one surface (the scene's texture, 512² in scenes/default.yaml): the
texture as a normal map and a relief map, and displaced meshes of 256² and 512² quads. Per column:
size; offline memory of modal analysis (peak resident set of a child process doing only that
solve, above an idle child's; spring-mass lattice for the normal map, the audio client's Tet10
slab for the relief, Tet4 slabs with the mesh's vertices for the meshes: measured at
--fem-mesh-sizes and extrapolated to 256 and 512 by a power-law fit unless listed there); runtime
memory of sound (the impulse-to-modes matrix); physics step, visual frame and haptic tick time.
The paper's figures beside ours, every cell also as a ratio to the normal-map column.

  --scene FILE            default: the source tree's scenes/default.yaml
  --md FILE  --csv FILE   the table (docs/results/table1.{md,csv})
  --workdir DIR           scratch (the PNGs whose size is the file size); default /tmp
  --spring-nodes N        spring-mass lattice nodes per side (default 2 x slab cells + 1: the Tet10
                          slab's top-face grid, so both models sample the surface alike)
  --slab-cells N          the relief's FEM slab, Tet10 cells per side (default 20, the audio client's)
  --slab-layers N         its cells through the thickness (default 2, the audio client's)
  --fem-mesh-sizes LIST   Tet4 cells per side measured for the meshes' fit (default 24,32,48,64,96,128,256,512;
                          256 takes about 2 GB and a minute, 512 about 8 GB and 7 minutes; a mesh
                          size left out is extrapolated by the fit)
  --resolution WxH        visual frame size (default 1280x720)
  --frames N              timed visual frames per column (default 10)
  --steps N  --reps N     timed physics steps per repetition (1000), repetitions (3)
  --passes N              haptic passes over the path (default 5)
  --quick                 small everything (a smoke run)
  --modal-child KIND SIZE LAYERS [--scene FILE]
                          one solve alone (idle, spring, fem-slab, fem-mesh), its reply on stdout:
                          what the program runs in its child processes
)";

struct Options {
  std::string scene, md, csv, workdir = "/tmp";
  int spring_nodes = 0;  // 0: the slab's top-face grid, 2 x slab_cells + 1
  int slab_cells = audio::kSlabCells, slab_layers = audio::kSlabLayers;
  int width = 1280, height = 720, frames = 10, steps = 1000, reps = 3, passes = 5;
  std::vector<int> fem_mesh_sizes{24, 32, 48, 64, 96, 128, 256, 512};
};

std::vector<int> parseList(const std::string& option, const std::string& text) {
  std::vector<int> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) out.push_back(int(cli::parseInteger(option, item, 2, 4096)));
  if (out.size() < 2) throw UsageError(option + " '" + text + "': expected at least two sizes (the fit needs them)");
  return out;
}

Options parse(int argc, char** argv) {
  Options o;
  o.scene = sourceDir() + "/scenes/default.yaml";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError(a + ": missing value");
      return argv[++i];
    };
    if (a == "--scene") o.scene = value();
    else if (a == "--md") o.md = value();
    else if (a == "--csv") o.csv = value();
    else if (a == "--workdir") o.workdir = value();
    else if (a == "--spring-nodes") o.spring_nodes = int(cli::parseInteger(a, value(), 3, 4096));
    else if (a == "--slab-cells") o.slab_cells = int(cli::parseInteger(a, value(), 1, 400));
    else if (a == "--slab-layers") o.slab_layers = int(cli::parseInteger(a, value(), 1, 100));
    else if (a == "--fem-mesh-sizes") o.fem_mesh_sizes = parseList(a, value());
    else if (a == "--resolution") {
      const std::string v = value();
      const auto x = v.find('x');
      if (x == std::string::npos) throw UsageError(a + " '" + v + "': expected WxH, e.g. 1280x720");
      o.width = int(cli::parseInteger(a, v.substr(0, x), 16, 8192));
      o.height = int(cli::parseInteger(a, v.substr(x + 1), 16, 8192));
    } else if (a == "--frames") o.frames = int(cli::parseInteger(a, value(), 1, 10000));
    else if (a == "--steps") o.steps = int(cli::parseInteger(a, value(), 10, 1000000));
    else if (a == "--reps") o.reps = int(cli::parseInteger(a, value(), 1, 100));
    else if (a == "--passes") o.passes = int(cli::parseInteger(a, value(), 1, 100));
    else if (a == "--quick") {
      o.frames = 3, o.steps = 200, o.reps = 1, o.passes = 1, o.slab_cells = 4;
      o.fem_mesh_sizes = {8, 12, 16};
      o.width = 640, o.height = 360;
    } else throw UsageError("unknown option '" + a + "'");
  }
  if (o.spring_nodes == 0) o.spring_nodes = 2 * o.slab_cells + 1;
  return o;
}

void say(const std::string& line) { std::fprintf(stderr, "bench_table1: %s\n", line.c_str()); }

ModalProbe probeOrThrow(const std::string& self, const Options& o, const std::string& kind, int size) {
  say("modal " + kind + " " + std::to_string(size) + " ...");
  ModalProbe p = probeModal(self, o.scene, kind, size, o.slab_layers);
  if (!p.ok) throw Error(Error::Kind::Config, "modal " + kind + " " + std::to_string(size) + ": " + p.error);
  say(fmt("  %d DOF, %d modes, peak RSS %.1f MB, %.2f s", p.dofs, p.modes, double(p.peak_rss_kb) / 1024.0, p.seconds));
  return p;
}

double kib(double k) { return k * 1024; }
double mib(double m) { return m * 1024 * 1024; }
double gib(double g) { return g * 1024 * 1024 * 1024; }

PaperCell paper(double v, bool star = false) { return {v, star, ""}; }
PaperCell paperText(const std::string& t) { return {std::nan(""), false, t}; }
Cell measured(double v, std::string note = {}) { return {v, Source::Measured, std::move(note)}; }

int run(int argc, char** argv) {
  if (argc >= 5 && std::string(argv[1]) == "--modal-child") {
    const std::string scene = argc >= 7 && std::string(argv[5]) == "--scene" ? argv[6] : sourceDir() + "/scenes/default.yaml";
    return runModalChild(scene, argv[2], std::atoi(argv[3]), std::atoi(argv[4]));
  }
  const Options o = parse(argc, argv);
  char self_buf[4096];
  const ssize_t len = readlink("/proc/self/exe", self_buf, sizeof self_buf - 1);
  if (len <= 0) throw Error(Error::Kind::Io, "/proc/self/exe: cannot be read (needed to run the modal children)");
  const std::string self(self_buf, std::size_t(len));
  const std::string started = isoNow();

  const SceneTexture st = loadSceneTexture(o.scene);
  say(o.scene + ": " + std::to_string(st.map().width()) + "² texture");

  // Offline modal memory first (child processes; nothing else runs meanwhile).
  const ModalProbe idle = probeOrThrow(self, o, "idle", 0);
  const ModalProbe spring = probeOrThrow(self, o, "spring", o.spring_nodes);
  const ModalProbe slab = probeOrThrow(self, o, "fem-slab", o.slab_cells);
  std::vector<ModalProbe> mesh_points;
  for (int n : o.fem_mesh_sizes) mesh_points.push_back(probeOrThrow(self, o, "fem-mesh", n));
  auto above = [&](const ModalProbe& p) { return std::max(0.0, double(p.peak_rss_kb - idle.peak_rss_kb) * 1024.0); };
  std::vector<double> fx, fy;
  for (const ModalProbe& p : mesh_points)
    if (above(p) > 0) fx.push_back(p.dofs), fy.push_back(above(p));
  if (fx.size() < 2) throw Error(Error::Kind::Config, "the FEM mesh points grew no memory above the idle child: no fit");
  const PowerFit fit = fitPower(fx, fy);
  const bool held = st.scene.surface.held == scene::SlabSupport::ClampedEdges;
  // The 256² and 512² rows are placed on the fit by femMeshDofs's count: it must be the count
  // the solves had, or the extrapolation reads the fit at the wrong abscissa.
  for (const ModalProbe& p : mesh_points)
    if (p.dofs != femMeshDofs(held, p.size))
      throw Error(Error::Kind::Config, fmt("fem-mesh %d: the solve had %d DOF, femMeshDofs counts %lld", p.size, p.dofs,
                                           femMeshDofs(held, p.size)));

  say("sizes ...");
  const Sizes sizes = measureSizes(st, o.workdir);
  say("physics ...");
  const auto physics = timePhysics(st, o.steps, o.reps);
  say("visual ...");
  std::array<Timing, kColumns> visual;
  std::string renderer;
  {
    const visual::HeadlessContext context;
    renderer = context.description();
    visual = timeVisual(st, o.width, o.height, o.frames);
  }
  say("haptics ...");
  std::vector<dev::DeviceState> relief_path;
  const auto haptic = timeHaptics(st, o.passes, relief_path);
  std::array<Timing, 2> mesh_haptic;
  for (int k = 0; k < 2; ++k) {
    mesh_haptic[std::size_t(k)] = timeMeshHaptics(st, k == 0 ? 256 : 512, relief_path, o.passes);
  }

  std::vector<Metric> metrics;
  {
    Metric m{"size", "size (texture PNG / mesh arrays)", Unit::Bytes, {}, {}};
    for (int c = 0; c < kColumns; ++c) m.ours[std::size_t(c)] = measured(sizes.file_bytes[std::size_t(c)]);
    m.paper = {paper(kib(10)), paper(kib(110)), paper(mib(4.5)), paper(mib(19))};
    metrics.push_back(m);
  }
  {
    Metric m{"vertices", "mesh vertices", Unit::Count, {}, {}};
    for (int c = kMesh256; c <= kMesh512; ++c) m.ours[std::size_t(c)] = measured(sizes.vertices[std::size_t(c)]);
    m.paper = {PaperCell{}, PaperCell{}, paper(66500), paper(264200)};
    metrics.push_back(m);
  }
  {
    Metric m{"memory", "size in memory (texels / mesh arrays)", Unit::Bytes, {}, {}};
    for (int c = 0; c < kColumns; ++c) m.ours[std::size_t(c)] = measured(sizes.memory_bytes[std::size_t(c)]);
    metrics.push_back(m);
  }
  {
    Metric m{"offline_modal_memory", "offline memory, modal analysis", Unit::Bytes, {}, {}};
    m.ours[kNormal] = measured(above(spring), fmt("spring-mass lattice %d², %d DOF", o.spring_nodes, spring.dofs));
    m.ours[kRelief] = measured(above(slab), fmt("Tet10 slab %d² x %d cells, %d DOF", o.slab_cells, o.slab_layers, slab.dofs));
    for (int c = kMesh256; c <= kMesh512; ++c) {
      const int n = c == kMesh256 ? 256 : 512;
      const ModalProbe* hit = nullptr;
      for (const ModalProbe& p : mesh_points)
        if (p.size == n) hit = &p;
      const long long dofs = femMeshDofs(held, n);
      m.ours[std::size_t(c)] = hit ? measured(above(*hit), fmt("Tet4 slab %d² x %d, %d DOF", n, kMeshLayers, hit->dofs))
                                   : Cell{fit.at(double(dofs)), Source::Extrapolated,
                                          fmt("Tet4 slab %d² x %d, %lld DOF, fit %.3g x DOF^%.3f", n, kMeshLayers, dofs, fit.a, fit.b)};
    }
    m.paper = {paper(mib(2.7)), paper(gib(1)), paper(gib(288), true), paper(gib(4500), true)};
    metrics.push_back(m);
  }
  {
    Metric m{"sound_runtime_memory", "runtime memory, sound (impulse-to-modes matrix)", Unit::Bytes, {}, {}};
    m.ours[kNormal] = measured(double(spring.matrix_bytes), fmt("%d x %d x 8 B", spring.mesh_dofs, spring.modes));
    m.ours[kRelief] = measured(double(slab.matrix_bytes), fmt("%d x %d x 8 B", slab.mesh_dofs, slab.modes));
    for (int c = kMesh256; c <= kMesh512; ++c) {
      const long long rows = femMeshNodeDofs(c == kMesh256 ? 256 : 512);
      m.ours[std::size_t(c)] = {double(rows) * kModes * 8.0, Source::Computed, fmt("%lld x %d x 8 B", rows, kModes)};
    }
    m.paper = {paper(kib(270)), paper(mib(18)), paper(mib(450), true), paper(mib(1700), true)};
    metrics.push_back(m);
  }
  {
    Metric m{"physics_step", "physics time (one 1 ms step)", Unit::Seconds, {}, {}};
    for (int c = 0; c < kColumns; ++c)
      m.ours[std::size_t(c)] = measured(physics[std::size_t(c)].median_s, physics[std::size_t(c)].note);
    m.paper = {paper(175e-6), paper(2.2e-3), paper(3.0e-3), paper(4.9e-3)};
    metrics.push_back(m);
  }
  {
    Metric m{"visual_frame", fmt("visual time (one frame, %dx%d)", o.width, o.height), Unit::Seconds, {}, {}};
    for (int c = 0; c < kColumns; ++c)
      m.ours[std::size_t(c)] = measured(visual[std::size_t(c)].median_s, visual[std::size_t(c)].note);
    m.paper = {paper(486e-6), paper(900e-6), paper(2.1e-3), paper(7.0e-3)};
    metrics.push_back(m);
  }
  {
    Metric m{"haptic_tick", "haptic time (one servo tick's render)", Unit::Seconds, {}, {}};
    m.ours[kNormal] = measured(haptic[0].median_s, haptic[0].note);
    m.ours[kRelief] = measured(haptic[1].median_s, haptic[1].note);
    for (int k = 0; k < 2; ++k)
      m.ours[std::size_t(kMesh256 + k)] = measured(mesh_haptic[std::size_t(k)].median_s, mesh_haptic[std::size_t(k)].note);
    m.paper = {paper(60e-6), paper(60e-6), paperText("not measurable"), paperText("not measurable")};
    metrics.push_back(m);
  }

  std::ostringstream md;
  md << "Measured " << started << " on " << machineDescription() << ", "
     << "RelWithDebInfo (-O2); renderer " << renderer << ". Surface: `" << o.scene.substr(o.scene.rfind('/') + 1)
     << "` (" << st.scene.name << ", " << st.map().width() << "² texture over " << st.scene.surface.size_m.x() << " x "
     << st.scene.surface.size_m.y() << " m, " << st.scene.surface.material.name << ", slab "
     << st.scene.surface.thickness_m * 1e3 << " mm, " << (held ? "edges held" : "free") << "). "
     << "Each cell: ours, then the paper's, with (× the normal-map column's). * extrapolated (the fit below), "
        "† computed from counts, not allocated.\n\n";
  md << markdownTable(metrics);
  md << "\nOffline modal memory: peak resident set of a child process that does only that solve, minus an idle "
        "child's (the same program, nothing solved: "
     << fmt("%.1f MB", double(idle.peak_rss_kb) / 1024.0) << "); " << kModes << " elastic modes at a 20 Hz shift in every solve.\n\n"
     << "| solve | size | DOF | modes | peak RSS | above idle | time | fit |\n|---|---|---|---|---|---|---|---|\n";
  auto probe_line = [&](const ModalProbe& p, const std::string& what, const std::string& fit_text) {
    md << "| " << what << " | " << p.size << " | " << p.dofs << " | " << p.modes << " | "
       << formatValue(double(p.peak_rss_kb) * 1024.0, Unit::Bytes) << " | " << formatValue(above(p), Unit::Bytes) << " | "
       << fmt("%.2f s", p.seconds) << " | " << fit_text << " |\n";
  };
  probe_line(spring, "spring-mass lattice (normal map), nodes per side", "");
  probe_line(slab, "Tet10 slab (relief map), cells per side", "");
  for (const ModalProbe& p : mesh_points)
    probe_line(p, "Tet4 slab (mesh), cells per side", formatValue(fit.at(p.dofs), Unit::Bytes));
  for (int n : {256, 512}) {
    if (std::any_of(mesh_points.begin(), mesh_points.end(), [&](const ModalProbe& p) { return p.size == n; })) continue;
    const long long dofs = femMeshDofs(held, n);
    md << "| Tet4 slab (mesh), cells per side | " << n << " | " << dofs << " | | | | | "
       << formatValue(fit.at(double(dofs)), Unit::Bytes) << "* |\n";
  }
  md << "\nFit of the Tet4 points: memory above idle = " << fmt("%.4g", fit.a) << " × DOF^" << fmt("%.3f", fit.b)
     << " (least squares on the logarithms).\n\n";
  md << "CPU per frame (visual, every thread of the process): ";
  for (int c = 0; c < kColumns; ++c)
    md << (c ? ", " : "") << columnName(c) << " " << formatValue(visual[std::size_t(c)].cpu_s, Unit::Seconds);
  md << ". CPU per physics step: ";
  for (int c = 0; c < kColumns; ++c)
    md << (c ? ", " : "") << columnName(c) << " " << formatValue(physics[std::size_t(c)].cpu_s, Unit::Seconds);
  md << ". Physics grounds: ";
  for (int c = 0; c < kColumns; ++c) md << (c ? "; " : "") << physics[std::size_t(c)].note;
  md << ". Haptic p99 per tick: normal " << formatValue(haptic[0].p99_s, Unit::Seconds) << ", relief "
     << formatValue(haptic[1].p99_s, Unit::Seconds) << " (" << haptic[1].note << ").\n";

  if (!o.md.empty()) writeTextFile(o.md, md.str());
  if (!o.csv.empty()) writeTextFile(o.csv, csvTable(metrics));
  std::fputs(md.str().c_str(), stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return thx::bench::benchMain(argc, argv, kHelp, "bench_table1", run); }
