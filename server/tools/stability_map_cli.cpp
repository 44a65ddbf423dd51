#include "server/tools/stability_map_cli.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "device/hand_script.hpp"

namespace thx::srv::stab {

const char* const kHelpText = R"(usage: stability-map [options]

Sweeps the servo pipeline (plane-proxy renderer -> passivity controller -> safety stage) around
the simulated PHANToM Desktop, lock-step and deterministic, over V-valleys: every combination of
the axes below. In each cell the simulated hand lowers the pen into the floor of one valley,
presses and holds; the last second is measured on the simulator's true state and judged stable,
limit-cycle, unstable, or cannot-hold (the continuous-force budget held the force below the push
and the pen sank through the floor: the valley was not tested; docs/stability.md). Writes OUT_DIR/NAME.json (all cells, all metrics,
setup, thresholds and this command line), NAME.csv and NAME.png (heatmap).

Axes (comma-separated lists; default: the full map):
  --angles LIST           valley opening angles, deg, in [10, 170]   (20,40,...,160)
  --stiffness LIST        stiffness, fraction of the device maximum (0.1,0.25,0.5,0.75,1.0)
  --forces LIST           hand push force, N          (0.5,1,1.5,2,2.25,2.5,3,5)
  --representations LIST  normal, relief                            (normal,relief)
  --mitigations LIST      paper (the source paper's loop: one plane per frame, held between
                          frames, no recovery rule, no passivity controller; the baseline),
                          paper+smoothing (its own mitigation), none (this server's pipeline
                          with every mitigation off), crease, passivity, smoothing, parts joined
                          with '+' (e.g. crease+passivity), or all   (paper, paper+smoothing
                          and all 8 combinations)
  --quick                 a small subset for CI (angles 20,60,120; stiffness 0.25,1.0; force
                          1 N; mitigations paper,none,crease+passivity,all); explicit axes
                          still apply

Setup:
  --tool T                the pen: point (default; the plane-proxy renderer), capsule (a pen
                          with extent, 100 mm x 2 mm, held upright: its tip's ball in the
                          valley) or capsule-across (the same lying level across the ridges);
                          a capsule renders through a 6-DOF virtual coupling (docs/hapticd.md)
                          on relief maps only, and takes the mitigations none, passivity,
                          smoothing and passivity+smoothing (those four by default)
  --hand NAME             default (scenes/default.yaml) or light (light grip, docs/stability.md)
  --damping B             renderer virtual damping, N s/m (default 1.0, as the scenes): the
                          point pen's spring's, or the capsule's coupling's
  --recovery-ticks N      renderer recovery ramp, ticks (default 10 = hapticd; 0 = off; the
                          paper's loop has none)
  --plane-rate HZ         planes per second in the paper's loop (default 100)
  --ridges sided|blend    crease handling at ridges: sided (default, the renderer's) or blend
                          (issue 3's, RendererConfig::sided_ridges = false)
  --smoothing-sigma S     normal smoothing sigma, texels (default 2)
  --aim-offset M          where the hand aims, beside the floor line, m (default 1e-4)
  --duration S            simulated seconds per cell (default 3)
  --window S              measured final window, s (default 1)

Output:
  --out-dir DIR           default docs/results
  --name NAME             file names NAME.{json,csv,png} (default stability_map)
  --no-picture            skip the PNG
  --trace FILE            per-tick CSV of the cell (the axes must select exactly one cell)
  --threads N             worker threads (default 2); results do not depend on it
  --quiet                 no progress on stderr
  -h, --help              this text

Exit status: 0 done (whatever the verdicts), 1 error while running or writing, 2 bad command line.
)";

namespace {

double parseNumber(const std::string& option, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || !end || *end != '\0' || !std::isfinite(v))
    throw UsageError{option + ": expected a number, got '" + text + "'"};
  return v;
}

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) parts.push_back(part);
  return parts;
}

std::vector<double> parseList(const std::string& option, const std::string& text, double lo, double hi,
                              const char* expected) {
  std::vector<double> values;
  for (const std::string& p : split(text)) {
    const double v = parseNumber(option, p);
    if (v < lo || v > hi) throw UsageError{option + ": " + p + " is out of range; expected " + expected};
    values.push_back(v);
  }
  if (values.empty()) throw UsageError{option + ": expected a comma-separated list, got '" + text + "'"};
  return values;
}

}  // namespace

Mitigations parseMitigations(const std::string& text) {
  if (text == "none") return Mitigations{};
  if (text == "all") return Mitigations{true, true, true};
  if (text == "paper") return Mitigations{.paper_loop = true};
  if (text == "paper+smoothing") return Mitigations{.smoothing = true, .paper_loop = true};
  Mitigations m;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, '+')) {
    if (part == "paper")
      throw UsageError{"--mitigations: 'paper' combines only with smoothing ('paper+smoothing'), got '" + text + "'"};
    if (part == "crease") m.crease = true;
    else if (part == "passivity") m.passivity = true;
    else if (part == "smoothing") m.smoothing = true;
    else
      throw UsageError{"--mitigations: unknown mitigation '" + part + "' in '" + text +
                       "'; expected none, all, paper, paper+smoothing, or crease, passivity, smoothing joined "
                       "with '+'"};
  }
  return m;
}

bool parseCommandLine(int argc, char** argv, CliOptions& o) {
  o.axes = fullAxes();
  o.argv.assign(argv, argv + argc);
  SweepAxes explicit_axes;  // applied after --quick, wherever they appear
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError{a + " needs a value"};
      return argv[++i];
    };
    if (a == "-h" || a == "--help") {
      std::fputs(kHelpText, stdout);
      return false;
    } else if (a == "--angles") {
      explicit_axes.angles_deg = parseList(a, value(), 10.0, 170.0, "an opening angle in [10, 170] deg");
    } else if (a == "--stiffness") {
      explicit_axes.stiffness_fractions = parseList(a, value(), 1e-3, 10.0, "a fraction in [0.001, 10]");
    } else if (a == "--forces") {
      explicit_axes.push_forces_n = parseList(a, value(), 0.0, 50.0, "a force in [0, 50] N");
    } else if (a == "--representations") {
      for (const std::string& p : split(value())) {
        if (p != "normal" && p != "relief")
          throw UsageError{a + ": expected normal or relief, got '" + p + "'"};
        explicit_axes.relief.push_back(p == "relief");
      }
    } else if (a == "--mitigations") {
      for (const std::string& p : split(value())) explicit_axes.mitigations.push_back(parseMitigations(p));
    } else if (a == "--tool") {
      const std::string name = value();
      if (name == "point") {
        o.setup.tool = PenTool::Point;
      } else if (name == "capsule") {
        o.setup.tool = PenTool::Capsule;
      } else if (name == "capsule-across") {
        o.setup.tool = PenTool::CapsuleAcross;
      } else {
        throw UsageError{a + ": expected point, capsule or capsule-across, got '" + name + "'"};
      }
    } else if (a == "--quick") {
      o.quick = true;
    } else if (a == "--hand") {
      const std::string name = value();
      if (name != "default" && name != "light") throw UsageError{a + ": expected default or light, got '" + name + "'"};
      o.setup.hand = handByName(name);
    } else if (a == "--damping") {
      o.setup.virtual_damping_ns_per_m = parseNumber(a, value());
      if (o.setup.virtual_damping_ns_per_m < 0) throw UsageError{a + ": expected a damping >= 0 N s/m"};
    } else if (a == "--recovery-ticks") {
      const double v = parseNumber(a, value());
      if (v < 0 || v > 1000 || v != std::floor(v)) throw UsageError{a + ": expected a whole number of ticks in [0, 1000]"};
      o.setup.recovery_ticks = int(v);
    } else if (a == "--ridges") {
      const std::string name = value();
      if (name != "sided" && name != "blend") throw UsageError{a + ": expected sided or blend, got '" + name + "'"};
      o.setup.sided_ridges = name == "sided";
    } else if (a == "--plane-rate") {
      o.setup.plane_rate_hz = parseNumber(a, value());
      if (o.setup.plane_rate_hz <= 0 || o.setup.plane_rate_hz > 1000)
        throw UsageError{a + ": expected a rate in (0, 1000] Hz (at most the servo rate)"};
    } else if (a == "--smoothing-sigma") {
      o.setup.geometry.smoothing_sigma_texels = parseNumber(a, value());
      if (o.setup.geometry.smoothing_sigma_texels <= 0 || o.setup.geometry.smoothing_sigma_texels > 64)
        throw UsageError{a + ": expected a sigma in (0, 64] texels"};
    } else if (a == "--aim-offset") {
      o.setup.aim_offset_m = parseNumber(a, value());
      if (std::fabs(o.setup.aim_offset_m) > o.setup.geometry.period_m / 2)
        throw UsageError{a + ": expected an offset within half a valley period"};
    } else if (a == "--duration") {
      o.setup.duration_s = parseNumber(a, value());
    } else if (a == "--window") {
      o.setup.window_s = parseNumber(a, value());
    } else if (a == "--out-dir") {
      o.out_dir = value();
    } else if (a == "--name") {
      o.basename = value();
      if (o.basename.empty() || o.basename.find('/') != std::string::npos)
        throw UsageError{a + ": expected a file name without '/'"};
    } else if (a == "--no-picture") {
      o.picture = false;
    } else if (a == "--trace") {
      o.trace_path = value();
    } else if (a == "--threads") {
      const double v = parseNumber(a, value());
      if (v < 1 || v > 256 || v != std::floor(v)) throw UsageError{a + ": expected a whole number in [1, 256]"};
      o.threads = int(v);
    } else if (a == "--quiet") {
      o.quiet = true;
    } else {
      throw UsageError{"unknown argument '" + a + "'"};
    }
  }
  // The press must be in its hold phase for the whole window: hover, descent, push ramp first.
  const dev::HandScriptOptions hand_script;
  const double press_starts_s = o.setup.settle_s + hand_script.approach_s + hand_script.force_ramp_s;
  if (o.setup.window_s < 0.05 || o.setup.window_s > o.setup.duration_s - press_starts_s)
    throw UsageError{"--window: expected at least 0.05 s and at most --duration - " +
                     std::to_string(press_starts_s) + " s (the press must be holding)"};
  if (o.setup.duration_s > 60) throw UsageError{"--duration: expected at most 60 s per cell"};
  if (o.quick) o.axes = quickAxes();
  if (!explicit_axes.angles_deg.empty()) o.axes.angles_deg = explicit_axes.angles_deg;
  if (!explicit_axes.stiffness_fractions.empty()) o.axes.stiffness_fractions = explicit_axes.stiffness_fractions;
  if (!explicit_axes.push_forces_n.empty()) o.axes.push_forces_n = explicit_axes.push_forces_n;
  if (!explicit_axes.relief.empty()) o.axes.relief = explicit_axes.relief;
  if (o.setup.tool != PenTool::Point) {
    // The crease handling and the paper's loop are the point renderer's; a capsule meets creases
    // with its own contacts (server/capsule_contacts.hpp).
    for (const Mitigations& m : explicit_axes.mitigations) {
      if (m.crease || m.paper_loop)
        throw UsageError{"--mitigations: '" + m.name() + "' with --tool " + penToolName(o.setup.tool) +
                         ": a capsule takes none, passivity, smoothing and passivity+smoothing"};
    }
    for (const bool relief : explicit_axes.relief) {
      if (!relief)
        throw UsageError{std::string("--representations: normal with --tool ") + penToolName(o.setup.tool) +
                         ": a capsule rests on a relief's depth (a normal map's planes move with the tool)"};
    }
    o.axes.relief = {true};
    if (explicit_axes.mitigations.empty())
      o.axes.mitigations = {Mitigations{}, Mitigations{false, true, false, false}, Mitigations{false, false, true, false},
                            Mitigations{false, true, true, false}};
  }
  if (!explicit_axes.mitigations.empty()) o.axes.mitigations = explicit_axes.mitigations;
  return true;
}

}  // namespace thx::srv::stab
