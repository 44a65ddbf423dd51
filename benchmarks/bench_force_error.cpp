// Part 2 of docs/benchmarks.md: force error of the plane proxy against the EXACT height-field
// contact force, beside its cost, for nearest / bilinear / smoothed sampling and crease on/off
// (with sided ridges, and with issue 3's blended ridges for comparison); on request the paper's
// loop with and without smoothing (docs/stability.md). V-valley errors are also split by where
// the probe lies: near a floor line, near a ridge line, or on a wall between.
//
// Truth (exact_surfaces.hpp): an analytic surface (sine bumps, V valleys), penalty force
// F = k (q - p) with q the closest point of the continuous surface to the probe p.
// Probes: random (x, y) over several periods, at vertical depths d below the true surface.
// Protocol per probe (a press): reset the renderer, start 0.5 mm above the base plane (above all
// relief), descend vertically at 20 mm/s (20 um per tick, below the recovery rule's 0.2 mm jump)
// to p, hold 15 ticks (the recovery ramp lasts 10), compare the last tick's force with F.
// Cost: wall time of render() over the ticks below the true surface, per tick.
//
// Usage: bench_force_error --help (kUsage below).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "rt/clock.hpp"
#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"
#include "benchmarks/bench_stamp.hpp"
#include "benchmarks/exact_surfaces.hpp"
#include "benchmarks/mesh_closest.hpp"
#include "tools/report/plot.hpp"
#include "server/mesh_god_object.hpp"
#include "server/proxy_renderer.hpp"
#include "server/triangle_bvh.hpp"
#include "server/triangle_mesh.hpp"
#include "textures/generators.hpp"
#include "textures/smoothing.hpp"
#include "textures/textured_surface.hpp"

namespace {

using namespace thx;

double g_stiffness = 600.0;  // N/m: the shipped scenes' 0.6 x PHANToM Desktop (--stiffness)
constexpr double kStartAbove = 0.5e-3;
constexpr double kStep = 2e-5;  // m per tick
constexpr int kHoldTicks = 15;
double g_smooth_sigma = 1.0;  // texels (--smooth)
const std::vector<int> kSizes{128, 256, 512, 1024};
const std::vector<double> kDepths{0.25e-3, 0.5e-3, 1e-3, 2e-3};
constexpr double kRegionReachTexels = 1.5;  // "floor" / "ridge": probes this close to the line
constexpr double kPlotFloorPercent = 0.01;

// A relative error as a percentage, with more digits below 0.1 %.
std::string pct(double rel) {
  const double v = 100.0 * rel;
  if (v == 0.0) return "0 %";
  return v >= 0.1 ? bench::fmt("%.1f %%", v) : bench::fmt("%.2g %%", v);
}

std::int64_t nowNs() { return rt::monotonicNowNs(); }

// Deterministic uniform numbers (splitmix64), independent of the standard library.
struct Rng {
  std::uint64_t s;
  double next() {
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return double(z >> 11) * 0x1.0p-53;
  }
};

struct Variant {
  std::string id;      // --variants name
  std::string filter;  // nearest | bilinear | smoothed | normal-map
  bool crease = false;
  bool sided = true;   // RendererConfig::sided_ridges (crease handling only); false: issue 3's blend
  bool paper = false;  // the paper's loop (server/paper_loop.hpp): a plane per 10 ticks, no recovery rule
};

// Every row the benchmark knows; the default set is all but the paper's loop.
const std::vector<Variant> kAllVariants{
    {"nearest", "nearest", false},
    {"nearest+crease", "nearest", true},
    {"bilinear", "bilinear", false},
    {"bilinear+crease-blend", "bilinear", true, false},
    {"bilinear+crease", "bilinear", true},
    {"smoothed", "smoothed", false},
    {"smoothed+crease", "smoothed", true},
    {"normal-map", "normal-map", false},
    {"normal-map+crease", "normal-map", true},
    {"paper", "bilinear", false, true, true},
    {"paper+smoothed", "smoothed", false, true, true},
    // The relief displaced as a size x size grid mesh (bilinear samples at the grid corners, as
    // the visual client's mesh:N) rendered by the god object over its BVH (server/mesh_god_object.hpp).
    {"mesh", "mesh", false},
};
const char* kDefaultVariants =
    "nearest,nearest+crease,bilinear,bilinear+crease-blend,bilinear+crease,smoothed,smoothed+crease,normal-map,"
    "normal-map+crease";

std::string filterText(const Variant& v) {
  std::string t = v.filter == "smoothed"     ? bench::fmt("smoothed σ=%g texel%s + bilinear", g_smooth_sigma,
                                                          g_smooth_sigma == 1.0 ? "" : "s")
                  : v.filter == "normal-map" ? std::string("normal map (depth ignored), bilinear")
                                             : v.filter;
  if (v.paper) t = "paper's loop (100 Hz plane), " + t;
  if (v.filter == "mesh") t = "mesh N² (god object + BVH)";
  return t;
}
std::string creaseText(const Variant& v) {
  if (v.filter == "mesh") return "(mesh)";
  if (!v.crease) return "off";
  return v.sided ? "on" : "on, ridges blended (issue 3)";
}

struct Stats {
  std::size_t n = 0, no_contact = 0;
  double sum_e2 = 0, sum_f2 = 0, max_e = 0, max_rel = 0;
  std::vector<double> rel;  // per probe |error| / |F_exact|
  void add(double err, double f_exact, bool contact) {
    ++n;
    rel.push_back(err / f_exact);
    no_contact += contact ? 0 : 1;
    sum_e2 += err * err;
    sum_f2 += f_exact * f_exact;
    max_e = std::max(max_e, err);
    max_rel = std::max(max_rel, err / f_exact);
  }
  double rms() const { return n ? std::sqrt(sum_e2 / double(n)) : 0.0; }
  double relRms() const { return sum_f2 > 0 ? std::sqrt(sum_e2 / sum_f2) : 0.0; }
  double medianRel() const {
    if (rel.empty()) return 0.0;
    std::vector<double> r = rel;
    std::nth_element(r.begin(), r.begin() + std::ptrdiff_t(r.size() / 2), r.end());
    return r[r.size() / 2];
  }
};

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

struct ProbeRecord {
  Eigen::Vector3d p, f_exact, f_rendered;
  bool contact = false;
};

struct Result {
  std::vector<ProbeRecord> records;  // only with --probe-csv
  std::string surface;
  int size = 0;
  double texel_m = 0;
  Variant v;
  Stats all;
  std::vector<Stats> by_depth;
  std::array<Stats, 3> by_region;  // V valleys only: floor, ridge, wall (bench::kRegionNames)
  double ns_per_tick = 0;
  std::size_t timed_ticks = 0;
  std::size_t mesh_bytes = 0;  // mesh rows: vertices + triangles + BVH
  double mesh_build_ms = 0;
  // Mesh rows: the error against the mesh's own exact contact (bench::GridMeshReference), relative
  // to the same exact force as `all`, and the probes that lie above the mesh (no mesh contact).
  Stats vs_mesh;
  std::size_t above_mesh = 0;
};

struct Probe {
  Eigen::Vector3d p;
  std::size_t depth_index;
};

bool g_keep_records = false;

// The probes pressed with one renderer (ProxyRenderer or MeshGodObject): errors and cost into res.
template <class Renderer>
void measure(Renderer& renderer, const bench::ExactSurface& truth, const std::vector<Probe>& probes,
             const std::vector<Eigen::Vector3d>& f_exact, Result& res,
             const bench::GridMeshReference* mesh_ref = nullptr) {
  const Eigen::Vector3d v_down(0, 0, -kStep * 1000.0), still = Eigen::Vector3d::Zero();
  // One press; returns the last force. Times the ticks below the true surface into ns_per_tick.
  auto press = [&](const Eigen::Vector3d& p, double& ns_per_tick, std::size_t& timed) {
    const double z_true = truth.z(p.x(), p.y());
    renderer.reset();
    double z = kStartAbove;
    for (; z > z_true && z > p.z(); z -= kStep) renderer.render({p.x(), p.y(), z}, v_down);  // not timed
    const std::int64_t t0 = nowNs();
    std::size_t ticks = 0;
    for (; z > p.z(); z -= kStep, ++ticks) renderer.render({p.x(), p.y(), z}, v_down);
    srv::RenderOutput out;
    for (int k = 0; k < kHoldTicks; ++k, ++ticks) out = renderer.render(p, still);
    ns_per_tick = double(nowNs() - t0) / double(ticks);
    timed = ticks;
    return out;
  };
  // Cost: the median over probes of each pass (robust to bursts of other work), best of three
  // passes (the error pass and two timing passes over the first 1000 probes).
  std::vector<double> pass_median;
  std::vector<double> per_probe;
  per_probe.reserve(probes.size());
  for (std::size_t i = 0; i < probes.size(); ++i) {
    double ns = 0;
    std::size_t ticks = 0;
    const srv::RenderOutput out = press(probes[i].p, ns, ticks);
    per_probe.push_back(ns);
    res.timed_ticks += ticks;
    const double err = (out.force_world - f_exact[i]).norm(), f = f_exact[i].norm();
    res.all.add(err, f, out.in_contact);
    res.by_depth[probes[i].depth_index].add(err, f, out.in_contact);
    if (mesh_ref) {
      const Eigen::Vector3d f_mesh = mesh_ref->force(probes[i].p, g_stiffness);
      res.above_mesh += f_mesh.isZero() ? 1 : 0;
      res.vs_mesh.add((out.force_world - f_mesh).norm(), f, out.in_contact);
    }
    if (const auto* vv = dynamic_cast<const bench::VValleySurface*>(&truth)) {
      // Within 1.5 texels, but at most a quarter period (at 128² a period is 2.56 texels).
      const double reach = std::min(kRegionReachTexels * res.texel_m, vv->period() / 4);
      res.by_region[std::size_t(vv->region(probes[i].p.x(), reach))].add(err, f, out.in_contact);
    }
    if (g_keep_records) res.records.push_back({probes[i].p, f_exact[i], out.force_world, out.in_contact});
  }
  pass_median.push_back(median(per_probe));
  for (int pass = 0; pass < 2; ++pass) {
    per_probe.clear();
    for (std::size_t i = 0; i < probes.size() && i < 1000; ++i) {
      double ns = 0;
      std::size_t ticks = 0;
      press(probes[i].p, ns, ticks);
      per_probe.push_back(ns);
    }
    pass_median.push_back(median(per_probe));
  }
  res.ns_per_tick = *std::min_element(pass_median.begin(), pass_median.end());
}

Result run(const bench::ExactSurface& truth, const std::vector<Probe>& probes,
           const std::vector<Eigen::Vector3d>& f_exact, const tex::TextureMap& map, const Variant& v, int size) {
  tex::PlaneMapping mapping;
  mapping.size_m = {truth.extent(), truth.extent()};
  tex::SampleOptions so;
  so.filter = v.filter == "nearest" ? tex::Filter::Nearest : tex::Filter::Bilinear;
  so.address = tex::Address::Wrap;
  const tex::TexturedSurface surface(map, mapping, so, v.filter != "normal-map");
  srv::RendererConfig rc;
  rc.stiffness_n_per_m = g_stiffness;
  rc.damping_ns_per_m = 0.0;  // the exact force is a pure spring
  rc.crease_handling = v.crease;
  rc.sided_ridges = v.sided;
  if (v.paper) {  // as applyPaperLoop (server/paper_loop.cpp)
    rc.crease_handling = false;
    rc.recovery_ticks = 0;
    rc.plane_hold_ticks = 10;
  }
  Result res;
  res.surface = truth.name();
  res.size = size;
  res.texel_m = truth.extent() / size;
  res.v = v;
  res.by_depth.resize(kDepths.size());
  if (v.filter == "mesh") {
    const std::int64_t t0 = nowNs();
    const srv::TriangleMesh mesh = srv::reliefGridMesh(surface, size);
    const srv::TriangleBvh bvh(mesh);
    res.mesh_build_ms = double(nowNs() - t0) * 1e-6;
    res.mesh_bytes = mesh.bytes() + bvh.bytes();
    srv::MeshGodObject renderer(bvh, mapping, rc);
    const bench::GridMeshReference reference(mesh, size, mapping.size_m);
    measure(renderer, truth, probes, f_exact, res, &reference);
  } else {
    srv::ProxyRenderer renderer(surface, rc);
    measure(renderer, truth, probes, f_exact, res);
  }
  return res;
}


constexpr const char* kUsage = R"(usage: bench_force_error [--probes N] [--json F] [--csv F] [--png F] [--md F]
                         [--surface sine|vvalley] [--sizes 128,256,...] [--variants LIST]
                         [--smooth SIGMA_TEXELS] [--stiffness N_PER_M] [--probe-csv F] [--md-compact 1]

Force error of the texture renderers against exact surfaces (docs/benchmarks.md part 2).
benchmarks/run.sh BUILD_DIR force_error runs it as the docs show (the defaults).

  --variants LIST  comma-separated rows; default: nearest,nearest+crease,bilinear,
                   bilinear+crease-blend,bilinear+crease,smoothed,smoothed+crease,normal-map,
                   normal-map+crease; also paper, paper+smoothed (the paper's loop: one plane per
                   10 ticks, no recovery rule; docs/stability.md). "+crease" = crease handling
                   with sided ridges (the renderer's default); "+crease-blend" = issue 3's
                   crease handling, which blends the two walls' normals across a ridge.
                   Also mesh: the relief displaced as an N x N grid mesh (N = the row's size,
                   vertices bilinear at the grid corners as the visual client's mesh:N) under
                   the god-object renderer with its BVH (server/mesh_god_object.hpp).
  --smooth SIGMA   Gaussian sigma in texels of the "smoothed" rows (default 1).
  --stiffness K    penalty stiffness in N/m (default 600).
  --probe-csv F    every probe: position, exact and rendered force, contact.
  --md-compact 1   the Markdown without the per-surface detail tables and the self-checks.
)";

}  // namespace

int main(int argc, char** argv) {
  thx::bench::exitOnHelp(argc, argv, kUsage);
  std::string json_path, csv_path, png_path, md_path, probe_csv_path, only_surface, variant_list = kDefaultVariants;
  std::vector<int> sizes = kSizes;
  int probes_per_depth = 2500;
  bool md_compact = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) {
      std::fprintf(stderr, "bench_force_error: %s needs a value\n", a.c_str());
      return 2;
    }
    const char* val = argv[++i];
    if (a == "--json") json_path = val;
    else if (a == "--csv") csv_path = val;
    else if (a == "--png") png_path = val;
    else if (a == "--md") md_path = val;
    else if (a == "--probes") probes_per_depth = std::max(10, std::atoi(val));
    else if (a == "--probe-csv") probe_csv_path = val;
    else if (a == "--md-compact") md_compact = std::strcmp(val, "0") != 0;
    else if (a == "--surface") only_surface = val;
    else if (a == "--variants") variant_list = val;
    else if (a == "--smooth") g_smooth_sigma = std::atof(val);
    else if (a == "--stiffness") g_stiffness = std::atof(val);
    else if (a == "--sizes") {
      sizes.clear();
      for (const char* c = val; *c;) {
        sizes.push_back(std::atoi(c));
        while (*c && *c != ',') ++c;
        if (*c == ',') ++c;
      }
    }
    else {
      std::fprintf(stderr, "%s", kUsage);
      return 2;
    }
  }

  try {
    // The surfaces: the sine generator's defaults, and scenes/vvalley.yaml's valleys.
    std::vector<std::unique_ptr<bench::ExactSurface>> surfaces;
    surfaces.push_back(std::make_unique<bench::SineSurface>(0.5e-3, 0.01, 0.2));
    surfaces.push_back(std::make_unique<bench::VValleySurface>(60.0, 0.004, 0.2));
    if (!only_surface.empty()) {
      std::erase_if(surfaces, [&](const auto& s) { return s->name() != only_surface; });
      if (surfaces.empty()) throw std::runtime_error("--surface: sine or vvalley");
    }
    g_keep_records = !probe_csv_path.empty();
    std::vector<Variant> variants;
    for (std::size_t a = 0; a <= variant_list.size();) {
      std::size_t b = variant_list.find(',', a);
      if (b == std::string::npos) b = variant_list.size();
      const std::string id = variant_list.substr(a, b - a);
      const auto it = std::find_if(kAllVariants.begin(), kAllVariants.end(), [&](const Variant& v) { return v.id == id; });
      if (it == kAllVariants.end()) throw std::runtime_error("--variants: unknown row '" + id + "' (see --help)");
      variants.push_back(*it);
      a = b + 1;
    }
    if (!(g_smooth_sigma >= 0.0) || !(g_stiffness > 0.0)) throw std::runtime_error("--smooth >= 0, --stiffness > 0");

    std::vector<Result> results;
    std::string checks;
    for (const auto& truth_ptr : surfaces) {
      bench::ExactSurface& truth = *truth_ptr;
      // Probe (x, y): 4 periods square around the centre (x, y) in [-20, 20] mm for the sine,
      // [-10, 10] mm (5 valleys) for the valleys.
      const double half = truth.name() == "sine" ? 0.02 : 0.01;
      Rng rng{truth.name() == "sine" ? 11u : 23u};
      std::vector<Eigen::Vector2d> xy(std::size_t(probes_per_depth) * kDepths.size());
      for (auto& q : xy) q = {-half + 2 * half * rng.next(), -half + 2 * half * rng.next()};

      for (int size : sizes) {
        std::fprintf(stderr, "bench_force_error: %s %d²: truth", truth.name().c_str(), size);
        truth.setSize(size);
        std::vector<Probe> probes(xy.size());
        std::vector<Eigen::Vector3d> f_exact(xy.size());
        double worst_golden = 0.0, worst_normal = 0.0;
        for (std::size_t i = 0; i < xy.size(); ++i) {
          const std::size_t di = i % kDepths.size();
          const Eigen::Vector3d p(xy[i].x(), xy[i].y(), truth.z(xy[i].x(), xy[i].y()) - kDepths[di]);
          probes[i] = {p, di};
          const Eigen::Vector3d q = truth.closest(p);
          f_exact[i] = g_stiffness * (q - p);
          if (const auto* vv = dynamic_cast<const bench::VValleySurface*>(&truth)) {
            worst_golden = std::max(worst_golden, (vv->closestGolden(p) - q).norm());
          } else {
            // Optimality: p - q along the surface normal at q (first-order condition).
            const double e = 1e-7, zx = (truth.z(q.x() + e, q.y()) - truth.z(q.x() - e, q.y())) / (2 * e);
            const double zy = (truth.z(q.x(), q.y() + e) - truth.z(q.x(), q.y() - e)) / (2 * e);
            const Eigen::Vector3d n = Eigen::Vector3d(-zx, -zy, 1).normalized();
            worst_normal = std::max(worst_normal, (q - p).cross(n).norm());
          }
        }
        if (truth.name() == "vvalley") {
          checks += bench::fmt("vvalley %d²: closed-form vs golden-section closest points agree to %.1e m. ", size,
                               worst_golden);
        } else {
          checks += bench::fmt("sine %d²: |(q - p) x n(q)| <= %.1e m. ", size, worst_normal);
        }

        const tex::TextureMap raw = tex::generate(truth.request(size));
        tex::SmoothOptions sm;
        sm.sigma_texels = g_smooth_sigma;
        sm.address = tex::Address::Wrap;
        const tex::TextureMap smooth = tex::smoothTexture(raw, sm);
        for (const Variant& v : variants) {
          std::fprintf(stderr, ", %s", v.id.c_str());
          results.push_back(run(truth, probes, f_exact, v.filter == "smoothed" ? smooth : raw, v, size));
        }
        std::fprintf(stderr, "\n");
      }
    }

    // ---- CSV: one row per configuration and depth (depth "all" = every probe).
    std::string csv =
        "surface,size,texel_mm,variant,filter,crease,depth_mm,probes,rms_err_n,max_err_n,rms_force_n,rel_rms,median_rel,"
        "max_rel,no_contact,ns_per_tick\n";
    auto csvRow = [&](const Result& r, const std::string& depth, const Stats& s) {
      csv += bench::fmt("%s,%d,%.4f,%s,%s,%s,%s,%zu,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%zu,%.1f\n", r.surface.c_str(), r.size,
                        r.texel_m * 1e3, r.v.id.c_str(), r.v.filter.c_str(), r.v.crease ? "on" : "off", depth.c_str(),
                        s.n, s.rms(),
                        s.max_e, std::sqrt(s.sum_f2 / double(std::max<std::size_t>(1, s.n))), s.relRms(),
                        s.medianRel(), s.max_rel,
                        s.no_contact, r.ns_per_tick);
    };
    for (const Result& r : results) {
      csvRow(r, "all", r.all);
      for (std::size_t d = 0; d < kDepths.size(); ++d) csvRow(r, bench::fmt("%.2f", kDepths[d] * 1e3), r.by_depth[d]);
      for (std::size_t g = 0; g < r.by_region.size(); ++g) {
        if (r.by_region[g].n > 0) csvRow(r, bench::kRegionNames[g], r.by_region[g]);
      }
    }
    if (!csv_path.empty()) bench::writeTextFile(csv_path, csv);
    if (!probe_csv_path.empty()) {
      std::string pc = "surface,size,variant,x_m,y_m,z_m,fx_exact,fy_exact,fz_exact,fx,fy,fz,contact\n";
      for (const Result& r : results) {
        for (const ProbeRecord& q : r.records) {
          pc += bench::fmt("%s,%d,%s,%.9g,%.9g,%.9g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d\n", r.surface.c_str(), r.size,
                           r.v.id.c_str(), q.p.x(), q.p.y(), q.p.z(), q.f_exact.x(),
                           q.f_exact.y(), q.f_exact.z(), q.f_rendered.x(), q.f_rendered.y(), q.f_rendered.z(),
                           int(q.contact));
        }
      }
      bench::writeTextFile(probe_csv_path, pc);
    }

    // ---- JSON
    std::string js = "{\n";
    js += "  \"benchmark\": \"force error of the plane proxy vs exact height-field contact\",\n";
    js += "  \"machine\": \"" + bench::machineDescription() + "\",\n";
    js += "  \"date\": \"" + bench::isoTimeNow() + "\",\n";
    js += "  \"build_type\": \"" + std::string(bench::buildType()) + "\",\n";
    js += bench::fmt("  \"stiffness_n_per_m\": %g,\n  \"smoothing_sigma_texels\": %g,\n  \"probes_per_depth\": %d,\n",
                     g_stiffness, g_smooth_sigma, probes_per_depth);
    js += "  \"depths_mm\": [";
    for (std::size_t d = 0; d < kDepths.size(); ++d) js += bench::fmt("%s%g", d ? ", " : "", kDepths[d] * 1e3);
    js += "],\n";
    js += bench::fmt(
        "  \"protocol\": \"reset, start %.1f mm above the base plane, descend vertically %.0f um/tick to the probe, "
        "hold %d ticks, compare the last force with k (q - p)\",\n",
        kStartAbove * 1e3, kStep * 1e6, kHoldTicks);
    js += "  \"truth_checks\": \"" + checks + "\",\n";
    js += "  \"surfaces\": [";
    for (std::size_t i = 0; i < surfaces.size(); ++i) {
      js += (i ? ", \"" : "\"") + surfaces[i]->description() + "\"";
    }
    js += "],\n  \"results\": [\n";
    for (std::size_t i = 0; i < results.size(); ++i) {
      const Result& r = results[i];
      js += bench::fmt(
          "    {\"surface\": \"%s\", \"size\": %d, \"texel_mm\": %.4f, \"variant\": \"%s\", \"filter\": \"%s\", "
          "\"crease\": %s, \"sided_ridges\": %s, \"paper_loop\": %s, \"probes\": %zu, \"rms_err_n\": %.6g, \"max_err_n\": %.6g, \"rel_rms\": %.6g, \"median_rel\": %.6g, "
          "\"max_rel\": %.6g, "
          "\"no_contact\": %zu, \"ns_per_tick\": %.1f, \"by_depth_rel_rms\": [",
          r.surface.c_str(), r.size, r.texel_m * 1e3, r.v.id.c_str(), r.v.filter.c_str(), r.v.crease ? "true" : "false",
          r.v.crease && r.v.sided ? "true" : "false", r.v.paper ? "true" : "false", r.all.n,
          r.all.rms(), r.all.max_e, r.all.relRms(), r.all.medianRel(), r.all.max_rel, r.all.no_contact,
          r.ns_per_tick);
      for (std::size_t d = 0; d < kDepths.size(); ++d) js += bench::fmt("%s%.6g", d ? ", " : "", r.by_depth[d].relRms());
      js += "]";
      if (r.v.filter == "mesh") {
        js += bench::fmt(", \"mesh_bytes\": %zu, \"mesh_build_ms\": %.1f, \"rel_rms_vs_mesh\": %.6g, "
                         "\"median_rel_vs_mesh\": %.6g, \"above_mesh\": %zu",
                         r.mesh_bytes, r.mesh_build_ms, r.vs_mesh.relRms(), r.vs_mesh.medianRel(), r.above_mesh);
      }
      if (r.surface == "vvalley") {
        // Each region's share of the relative RMS error (its squared errors over all probes' squared
        // exact force: the three add up in quadrature to rel_rms).
        js += ", \"by_region\": {";
        for (std::size_t g = 0; g < r.by_region.size(); ++g) {
          const Stats& st = r.by_region[g];
          js += bench::fmt("%s\"%s\": {\"probes\": %zu, \"rel_rms_share\": %.6g, \"no_contact\": %zu}", g ? ", " : "",
                           bench::kRegionNames[g], st.n, r.all.sum_f2 > 0 ? std::sqrt(st.sum_e2 / r.all.sum_f2) : 0.0,
                           st.no_contact);
        }
        js += "}";
      }
      js += std::string("}") + (i + 1 < results.size() ? ",\n" : "\n");
    }
    js += "  ]\n}\n";
    if (!json_path.empty()) bench::writeTextFile(json_path, js);

    // ---- Plot: relative RMS error against cost, one panel per surface.
    if (!png_path.empty()) {
      std::vector<bench::PlotPanel> panels;
      for (const auto& s : surfaces) {
        bench::PlotPanel p;
        p.title = s->name() == "sine" ? "sine bumps (A 0.5 mm, period 10 mm)" : "V valleys (60 deg, period 4 mm)";
        p.x_label = "render cost per tick (ns, this VM)";
        p.y_label = "relative RMS force error (%)";
        double x_lo = 1e300, x_hi = 0, y_lo = 1e300, y_hi = 0;
        for (const Variant& v : variants) {
          bench::PlotSeries ps;
          ps.label = std::string(v.paper ? "paper's loop, " : "") +
                     std::string(v.filter == "normal-map" ? "normal map" : v.filter) +
                     (v.crease ? (v.sided ? ", crease on" : ", crease on, ridges blended") : ", crease off");
          ps.color = v.paper                  ? bench::Rgb{148, 103, 189}
                     : v.filter == "nearest"  ? bench::Rgb{214, 39, 40}
                     : v.filter == "bilinear" ? (v.crease && !v.sided ? bench::Rgb{255, 127, 14} : bench::Rgb{31, 119, 180})
                     : v.filter == "smoothed" ? bench::Rgb{44, 160, 44}
                                              : bench::Rgb{127, 127, 127};
          ps.marker = v.crease ? (v.sided ? bench::Marker::Square : bench::Marker::Triangle) : bench::Marker::Circle;
          ps.filled = !v.crease;
          for (const Result& r : results) {
            if (r.surface != s->name() || r.v.id != v.id) continue;
            ps.x.push_back(r.ns_per_tick);
            // A log axis has no 0: errors below the axis' floor are drawn on it.
            ps.y.push_back(std::max(100.0 * r.all.relRms(), kPlotFloorPercent));
            ps.point_labels.push_back(std::to_string(r.size));
            x_lo = std::min(x_lo, r.ns_per_tick);
            x_hi = std::max(x_hi, r.ns_per_tick);
            y_lo = std::min(y_lo, 100.0 * r.all.relRms());
            y_hi = std::max(y_hi, 100.0 * r.all.relRms());
          }
          p.series.push_back(ps);
        }
        p.x_min = std::pow(10.0, std::floor(std::log10(x_lo * 0.8) * 4) / 4);
        p.x_max = std::pow(10.0, std::ceil(std::log10(x_hi * 1.25) * 4) / 4);
        p.y_min = std::pow(10.0, std::floor(std::log10(std::max(y_lo, kPlotFloorPercent) * 0.8)));
        p.y_max = std::pow(10.0, std::ceil(std::log10(y_hi * 1.25)));
        panels.push_back(p);
      }
      bench::writePlotPng(png_path, panels,
                          bench::fmt("Labels: texture size (texels per side over 0.2 m); errors below %g %% drawn "
                                     "at %g %%. k = %g N/m. Regenerate: benchmarks/run.sh BUILD_DIR force_error.",
                                     kPlotFloorPercent, kPlotFloorPercent, g_stiffness));
    }

    // ---- Markdown
    if (!md_path.empty()) {
      std::string md;
      md += "Machine: " + bench::machineDescription() + "; measured " + bench::isoTimeNow() + ".\n\n";
      md += bench::fmt(
          "k = %g N/m; %d probes per depth at vertical depths 0.25 / 0.5 / 1 / 2 mm below the true surface "
          "(%d per row); protocol: reset, descend vertically from %.1f mm above the base plane at %.0f µm/tick, "
          "hold %d ticks, compare the last force with the exact k·(q − p). Errors are |F_rendered − F_exact|; "
          "relative = RMS error / RMS exact force; “no contact” = probes the renderer did not touch at all. "
          "ns/tick: render() over the ticks below the true surface (median over probes, best of 3 passes).\n\n",
          g_stiffness, probes_per_depth, probes_per_depth * int(kDepths.size()), kStartAbove * 1e3, kStep * 1e6,
          kHoldTicks);
      if (!md_compact) md += "Truth self-checks: " + checks + "\n";
      // Compact view first: relative RMS error by size, and the cost.
      md += md_compact ? "" : "\n";
      md += "Relative RMS force error (median relative error in brackets) by texture size (texel over 0.2 m), and "
            "render cost (ns/tick, median over the sizes):\n\n";
      md += "| surface | filter | crease |";
      for (int size : sizes) md += bench::fmt(" %d² (%.2f mm) |", size, 200.0 / size);
      md += " ns/tick |\n|---|---|---|";
      for (std::size_t i = 0; i < sizes.size(); ++i) md += "---|";
      md += "---|\n";
      for (const auto& s : surfaces) {
        for (const Variant& v : variants) {
          md += "| " + s->name() + " | " + filterText(v) + " | " + creaseText(v) + " |";
          std::vector<double> cost;
          for (int size : sizes) {
            for (const Result& r : results) {
              if (r.surface != s->name() || r.size != size || r.v.id != v.id) continue;
              md += bench::fmt(" %s (%s) |", pct(r.all.relRms()).c_str(), pct(r.all.medianRel()).c_str());
              cost.push_back(r.ns_per_tick);
            }
          }
          std::sort(cost.begin(), cost.end());
          md += bench::fmt(" %.0f |\n", cost.empty() ? 0.0 : (cost[(cost.size() - 1) / 2] + cost[cost.size() / 2]) / 2);
        }
      }
      bool any_mesh = false;
      for (const Result& r : results) any_mesh = any_mesh || r.v.filter == "mesh";
      if (any_mesh) {
        md += "\n**Mesh rows, split.** The same rendered forces against the mesh's own exact contact (k·(q − p), q "
              "the closest point of the mesh, zero above it): what the god object adds to what the mesh cannot "
              "represent. Relative to the same RMS exact force as above; “above mesh”: probes below the true surface "
              "but above the mesh (no contact is right for the mesh there).\n\n";
        md += "| surface | mesh | vs exact surface | vs the mesh's own contact | no contact | above mesh | mesh + BVH "
              "(MB) | build (ms) |\n|---|---|---|---|---|---|---|---|\n";
        for (const Result& r : results) {
          if (r.v.filter != "mesh") continue;
          md += bench::fmt("| %s | %d² | %s (%s) | %s (%s) | %zu | %zu | %.1f | %.0f |\n", r.surface.c_str(), r.size,
                           pct(r.all.relRms()).c_str(), pct(r.all.medianRel()).c_str(), pct(r.vs_mesh.relRms()).c_str(),
                           pct(r.vs_mesh.medianRel()).c_str(), r.all.no_contact, r.above_mesh,
                           double(r.mesh_bytes) / 1e6, r.mesh_build_ms);
        }
      }
      for (const auto& s : surfaces) {
        if (md_compact) break;
        md += "\n**" + s->description() + "**\n\n";
        md += "| size (texel) | filter | crease | RMS err (mN) | relative RMS | median relative | max err (mN) | "
              "max relative | no contact | ns/tick |\n";
        md += "|---|---|---|---|---|---|---|---|---|---|\n";
        for (const Result& r : results) {
          if (r.surface != s->name()) continue;
          md += bench::fmt("| %d² (%.3f mm) | %s | %s | %.1f | %s | %s | %.0f | %.0f %% | %zu | %.0f |\n", r.size,
                           r.texel_m * 1e3, filterText(r.v).c_str(), creaseText(r.v).c_str(), r.all.rms() * 1e3,
                           pct(r.all.relRms()).c_str(), pct(r.all.medianRel()).c_str(), r.all.max_e * 1e3,
                           100.0 * r.all.max_rel, r.all.no_contact, r.ns_per_tick);
        }
      }
      // Where the V-valley error lives: probes by their horizontal distance to the nearest floor or
      // ridge line, each region's share of the relative RMS error (the shares add in quadrature).
      bool any_valley = false;
      for (const Result& r : results) any_valley = any_valley || r.surface == "vvalley";
      if (any_valley) {
        md += "\n**Where the V-valley error lives.** Probes by their horizontal distance to the nearest floor or "
              "ridge line: within 1.5 texels (at most a quarter period) of a floor (“floor”), of a ridge (“ridge”), or "
              "neither (“wall”). "
              "Each cell: that region's share of the row's relative RMS error (its squared errors over every "
              "probe's squared exact force, so the three shares add up in quadrature to the row's error), its "
              "probes, and in brackets those that got no contact.\n\n";
        md += "| size | filter | crease | relative RMS | floor | ridge | wall |\n|---|---|---|---|---|---|---|\n";
        for (const Result& r : results) {
          if (r.surface != "vvalley") continue;
          md += bench::fmt("| %d² | %s | %s | %s |", r.size, filterText(r.v).c_str(), creaseText(r.v).c_str(),
                           pct(r.all.relRms()).c_str());
          for (const Stats& st : r.by_region) {
            md += bench::fmt(" %s of %zu (%zu) |", pct(r.all.sum_f2 > 0 ? std::sqrt(st.sum_e2 / r.all.sum_f2) : 0.0).c_str(),
                             st.n, st.no_contact);
          }
          md += "\n";
        }
      }
      bench::writeTextFile(md_path, md);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_force_error: %s\n", e.what());
    return 1;
  }
  return 0;
}
