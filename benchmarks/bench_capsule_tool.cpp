// The pen with extent's cost against its contacts (issue 30; docs/hapticd.md "A pen with extent").
// The capsule tool (server/capsule_tool.hpp) on the default scene's bricks (scenes/default.yaml as
// hapticd builds them) and on a steep V-valley, fed a kinematic device pose: the pen upright, at
// 45 degrees, and lying flat, each pressed 1 mm into the surface and stroked at 50 mm/s; the point
// pen (ProxyRenderer, hapticd's renderer) on the upright stroke as the baseline. Every step() is
// timed. Measures only; nothing asserted.
//
// Usage: bench_capsule_tool --help (kHelp below).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"
#include "benchmarks/bench_stamp.hpp"
#include "device/device_specs.hpp"
#include "rt/clock.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_surface.hpp"
#include "server/capsule_tool.hpp"
#include "server/proxy_renderer.hpp"
#include "textures/generators.hpp"

namespace {

using namespace thx;

constexpr const char* kHelp = R"(usage: bench_capsule_tool [--seconds S] [--json F] [--csv F] [--md F]

The pen with extent (a capsule 100 mm long, 2 mm radius, on a 6-DOF simulated device with the
default scene's 600 N/m) against the number of its contacts: on the default scene's bricks
(1024² relief) and on a steep V-valley (60 degree opening, 4 mm period, 1024² over 0.2 m), the
pen upright, at 45 degrees and lying flat across the grooves, its centre pressed 1 mm below where
it rests and stroked at 50 mm/s across the texture; the point pen (hapticd's plane renderer) on the
upright stroke as the baseline. Per row: contacts held per tick (mean and largest), texels examined
and solver sweeps per tick, the step's time (p50, p99, max; every tick timed), and the deepest
penetration left at a tick.

  --seconds S       length of each stroke (default 4: 4000 ticks at 1 kHz)
  --json/--csv/--md F   results
)";

struct Row {
  std::string surface, pen;
  int ticks = 0;
  double contacts_mean = 0.0;
  int contacts_max = 0;
  double texels_mean = 0.0, sweeps_mean = 0.0;
  double p50_us = 0.0, p99_us = 0.0, max_us = 0.0;
  double penetration_max_m = 0.0;
  double in_contact = 0.0;
};

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const std::size_t k = std::min(v.size() - 1, std::size_t(q * double(v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}

// The pen's orientation: upright (identity), tilted about y by `tilt` (the tip leads along +x).
Eigen::Quaterniond penAt(double tilt_rad) { return Eigen::Quaterniond(Eigen::AngleAxisd(-tilt_rad, Eigen::Vector3d::UnitY())); }

// Where the tool's centre rests over (x, y): the tool itself, placed clear above and pulled towards
// a device pose far below, comes to rest on the surface.
double restingCentreZ(const tex::TexturedSurface& surface, const srv::CapsuleToolConfig& config,
                      const Eigen::Quaterniond& q, double x, double y) {
  srv::CapsuleTool tool(surface, dev::simulated6DofSpec(), config);
  dev::DeviceState s;
  s.q_world = q;
  s.p_world = Eigen::Vector3d(x, y, -0.05) - 0.5 * config.length_m * (q * Eigen::Vector3d::UnitZ());
  for (int t = 0; t < 50; ++t) tool.step(s);
  return tool.centreLocal().z();
}

Row strokeCapsule(const std::string& surface_name, const std::string& pen_name, const tex::TexturedSurface& surface,
                  double tilt_rad, double seconds) {
  srv::CapsuleToolConfig config;
  config.length_m = 0.10;
  config.radius_m = 0.002;
  config.stiffness_n_per_m = 600.0;
  config.damping_ns_per_m = 1.0;  // as hapticd on the default scene (device.damping)
  config.rot_stiffness_nm_per_rad = 0.5;
  const Eigen::Quaterniond q = penAt(tilt_rad);
  const Eigen::Vector3d axis = q * Eigen::Vector3d::UnitZ();
  const double speed = 0.05, x0 = -0.5 * speed * seconds, y = 0.0013;
  const double rest_z = restingCentreZ(surface, config, q, x0, y);
  srv::CapsuleTool tool(surface, dev::simulated6DofSpec(), config);
  const int ticks = int(std::lround(seconds * 1000.0));
  std::vector<double> times;
  times.reserve(std::size_t(ticks));
  Row row;
  row.surface = surface_name;
  row.pen = pen_name;
  row.ticks = ticks;
  for (int t = 0; t < ticks; ++t) {
    dev::DeviceState s;
    s.q_world = q;
    const Eigen::Vector3d centre(x0 + speed * t * 1e-3, y, rest_z - 0.001);
    s.p_world = centre - 0.5 * config.length_m * axis;
    s.v_world = {speed, 0.0, 0.0};
    const std::int64_t a = rt::monotonicNowNs();
    const srv::ToolOutput out = tool.step(s);
    times.push_back(double(rt::monotonicNowNs() - a) * 1e-3);
    row.contacts_mean += out.contacts;
    row.contacts_max = std::max(row.contacts_max, out.contacts);
    row.texels_mean += out.texels_examined;
    row.sweeps_mean += out.solver_sweeps;
    row.penetration_max_m = std::max(row.penetration_max_m, out.penetration_m);
    row.in_contact += out.in_contact;
  }
  row.contacts_mean /= ticks;
  row.texels_mean /= ticks;
  row.sweeps_mean /= ticks;
  row.in_contact /= ticks;
  row.p50_us = quantile(times, 0.5);
  row.p99_us = quantile(times, 0.99);
  row.max_us = *std::max_element(times.begin(), times.end());
  return row;
}

Row strokePoint(const std::string& surface_name, const tex::TexturedSurface& surface, double seconds) {
  srv::RendererConfig config;
  config.stiffness_n_per_m = 600.0;
  config.damping_ns_per_m = 1.0;
  srv::ProxyRenderer renderer(surface, config);
  const double speed = 0.05, x0 = -0.5 * speed * seconds, y = 0.0013;
  const int ticks = int(std::lround(seconds * 1000.0));
  std::vector<double> times;
  Row row;
  row.surface = surface_name;
  row.pen = "point pen (plane renderer)";
  row.ticks = ticks;
  for (int t = 0; t < ticks; ++t) {
    const Eigen::Vector3d tip(x0 + speed * t * 1e-3, y, surface.at(x0 + speed * t * 1e-3, y).height_m - 0.001);
    const std::int64_t a = rt::monotonicNowNs();
    const srv::RenderOutput out = renderer.render(tip, {speed, 0.0, 0.0});
    times.push_back(double(rt::monotonicNowNs() - a) * 1e-3);
    row.contacts_mean += out.in_contact;
    row.contacts_max = std::max(row.contacts_max, int(out.in_contact));
    row.in_contact += out.in_contact;
  }
  row.contacts_mean /= ticks;
  row.in_contact /= ticks;
  row.p50_us = quantile(times, 0.5);
  row.p99_us = quantile(times, 0.99);
  row.max_us = *std::max_element(times.begin(), times.end());
  return row;
}

int run(int argc, char** argv) {
  double seconds = 4.0;
  std::string json, csv, md;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw UsageError(a + ": expected a value after it");
    const std::string v = argv[++i];
    if (a == "--seconds") {
      seconds = std::stod(v);
      if (!(seconds >= 0.5 && seconds <= 60.0)) throw UsageError("--seconds: " + v + " is outside 0.5 .. 60");
    } else if (a == "--json")
      json = v;
    else if (a == "--csv")
      csv = v;
    else if (a == "--md")
      md = v;
    else
      throw UsageError("unknown option " + a);
  }
  const bench::SceneTexture bricks = bench::loadSceneTexture(bench::sourceDir() + "/scenes/default.yaml");
  tex::GenerateRequest valley_request;
  valley_request.kind = "vvalley";
  valley_request.size = 1024;
  valley_request.params = {{"extent", 0.2}, {"angle_deg", 60.0}, {"period", 0.004}};
  const tex::TextureMap valley_map = tex::generate(valley_request);
  tex::PlaneMapping valley_mapping;
  valley_mapping.size_m = {0.2, 0.2};
  const tex::TexturedSurface valley(valley_map, valley_mapping, {}, true);

  std::vector<Row> rows;
  const double pi = std::numbers::pi;
  for (const auto& [name, surface] : {std::pair<std::string, const tex::TexturedSurface*>{"bricks 1024²", &bricks.surface.surface},
                                      {"vvalley 60° 1024²", &valley}}) {
    std::fprintf(stderr, "bench_capsule_tool: %s\n", name.c_str());
    rows.push_back(strokePoint(name, *surface, seconds));
    rows.push_back(strokeCapsule(name, "capsule upright", *surface, 0.0, seconds));
    rows.push_back(strokeCapsule(name, "capsule at 45°", *surface, pi / 4, seconds));
    rows.push_back(strokeCapsule(name, "capsule lying flat", *surface, pi / 2, seconds));
  }

  const std::string stamp =
      bench::fmt("%s, %s build, %s", bench::isoNow().c_str(), bench::buildType(), bench::machineSummary().c_str());
  if (!csv.empty()) {
    std::string c = "surface,pen,ticks,in_contact,contacts_mean,contacts_max,texels_mean,sweeps_mean,p50_us,p99_us,max_us,penetration_max_m\n";
    for (const Row& r : rows)
      c += bench::fmt("%s,%s,%d,%.4f,%.2f,%d,%.1f,%.1f,%.3f,%.3f,%.3f,%.3g\n", r.surface.c_str(), r.pen.c_str(), r.ticks,
                      r.in_contact, r.contacts_mean, r.contacts_max, r.texels_mean, r.sweeps_mean, r.p50_us, r.p99_us,
                      r.max_us, r.penetration_max_m);
    bench::writeTextFile(csv, c);
  }
  if (!json.empty()) {
    std::string j = "{\"benchmark\": \"the pen with extent's cost against its contacts\", \"stamp\": \"" + stamp +
                    "\", \"rows\": [";
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const Row& r = rows[k];
      j += bench::fmt("%s{\"surface\": \"%s\", \"pen\": \"%s\", \"ticks\": %d, \"in_contact\": %.4f, \"contacts_mean\": %.2f, "
                      "\"contacts_max\": %d, \"texels_mean\": %.1f, \"sweeps_mean\": %.1f, \"p50_us\": %.3f, "
                      "\"p99_us\": %.3f, \"max_us\": %.3f, \"penetration_max_m\": %.3g}",
                      k ? ", " : "", r.surface.c_str(), r.pen.c_str(), r.ticks, r.in_contact, r.contacts_mean,
                      r.contacts_max, r.texels_mean, r.sweeps_mean, r.p50_us, r.p99_us, r.max_us, r.penetration_max_m);
    }
    bench::writeTextFile(json, j + "]}\n");
  }
  std::string t = "Measured " + stamp + " (`bench_capsule_tool`, " + bench::fmt("%.0f", seconds * 1000) +
                  " ticks a row):\n\n| surface | pen | in contact | contacts (mean / max) | texels examined | solver sweeps | p50 | p99 | max | deepest |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Row& r : rows)
    t += bench::fmt("| %s | %s | %.1f %% | %.1f / %d | %.0f | %.0f | %.2f µs | %.2f µs | %.1f µs | %.3g µm |\n",
                    r.surface.c_str(), r.pen.c_str(), 100 * r.in_contact, r.contacts_mean, r.contacts_max, r.texels_mean,
                    r.sweeps_mean, r.p50_us, r.p99_us, r.max_us, r.penetration_max_m * 1e6);
  if (!md.empty()) bench::writeTextFile(md, t);
  std::fputs(t.c_str(), stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_capsule_tool", run); }
