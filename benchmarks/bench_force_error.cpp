// Part 2 of docs/benchmarks.md: force error of the plane proxy against the EXACT height-field
// contact force, beside its cost, for nearest / bilinear / smoothed sampling and crease on/off.
//
// Truth (exact_surfaces.hpp): an analytic surface (sine bumps, V valleys), penalty force
// F = k (q - p) with q the closest point of the continuous surface to the probe p.
// Probes: random (x, y) over several periods, at vertical depths d below the true surface.
// Protocol per probe (a press): reset the renderer, start 0.5 mm above the base plane (above all
// relief), descend vertically at 20 mm/s (20 um per tick, below the recovery rule's 0.2 mm jump)
// to p, hold 15 ticks (the recovery ramp lasts 10), compare the last tick's force with F.
// Cost: wall time of render() over the ticks below the true surface, per tick.
//
// Usage: bench_force_error [--probes N] [--json F] [--csv F] [--png F] [--md F]
#include <algorithm>
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
#include "benchmarks/exact_surfaces.hpp"
#include "benchmarks/plot.hpp"
#include "server/proxy_renderer.hpp"
#include "textures/generators.hpp"
#include "textures/smoothing.hpp"
#include "textures/textured_surface.hpp"

namespace {

using namespace thx;

constexpr double kStiffness = 600.0;  // N/m: the shipped scenes' 0.6 x PHANToM Desktop
constexpr double kStartAbove = 0.5e-3;
constexpr double kStep = 2e-5;  // m per tick
constexpr int kHoldTicks = 15;
constexpr double kSmoothSigma = 1.0;  // texels
const std::vector<int> kSizes{128, 256, 512, 1024};
const std::vector<double> kDepths{0.25e-3, 0.5e-3, 1e-3, 2e-3};

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
  std::string filter;  // nearest | bilinear | smoothed | normal-map
  bool crease = false;
};

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

struct Result {
  std::string surface;
  int size = 0;
  double texel_m = 0;
  Variant v;
  Stats all;
  std::vector<Stats> by_depth;
  double ns_per_tick = 0;
  std::size_t timed_ticks = 0;
};

struct Probe {
  Eigen::Vector3d p;
  std::size_t depth_index;
};

Result run(const bench::ExactSurface& truth, const std::vector<Probe>& probes,
           const std::vector<Eigen::Vector3d>& f_exact, const tex::TextureMap& map, const Variant& v, int size) {
  tex::PlaneMapping mapping;
  mapping.size_m = {truth.extent(), truth.extent()};
  tex::SampleOptions so;
  so.filter = v.filter == "nearest" ? tex::Filter::Nearest : tex::Filter::Bilinear;
  so.address = tex::Address::Wrap;
  const tex::TexturedSurface surface(map, mapping, so, v.filter != "normal-map");
  srv::RendererConfig rc;
  rc.stiffness_n_per_m = kStiffness;
  rc.damping_ns_per_m = 0.0;  // the exact force is a pure spring
  rc.crease_handling = v.crease;
  srv::ProxyRenderer renderer(surface, rc);

  Result res;
  res.surface = truth.name();
  res.size = size;
  res.texel_m = truth.extent() / size;
  res.v = v;
  res.by_depth.resize(kDepths.size());
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
  return res;
}

const char* filterText(const std::string& f) {
  if (f == "smoothed") return "smoothed σ=1 texel + bilinear";
  if (f == "normal-map") return "normal map (depth ignored), bilinear";
  return f.c_str();
}

}  // namespace

int main(int argc, char** argv) {
  thx::bench::exitOnHelp(argc, argv, R"(usage: bench_force_error [--probes N] [--json F] [--csv F] [--png F] [--md F]

Force error of the texture renderers against exact surfaces (docs/benchmarks.md part 2).
benchmarks/run.sh BUILD_DIR force_error runs it as the docs show.
)");
  std::string json_path, csv_path, png_path, md_path;
  int probes_per_depth = 2500;
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
    else {
      std::fprintf(stderr, "usage: bench_force_error [--probes N] [--json F] [--csv F] [--png F] [--md F]\n");
      return 2;
    }
  }

  try {
    // The surfaces: the sine generator's defaults, and scenes/vvalley.yaml's valleys.
    std::vector<std::unique_ptr<bench::ExactSurface>> surfaces;
    surfaces.push_back(std::make_unique<bench::SineSurface>(0.5e-3, 0.01, 0.2));
    surfaces.push_back(std::make_unique<bench::VValleySurface>(60.0, 0.004, 0.2));
    const std::vector<Variant> variants{{"nearest", false},  {"nearest", true},  {"bilinear", false},
                                        {"bilinear", true},  {"smoothed", false}, {"smoothed", true},
                                        {"normal-map", false}, {"normal-map", true}};

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

      for (int size : kSizes) {
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
          f_exact[i] = kStiffness * (q - p);
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
        sm.sigma_texels = kSmoothSigma;
        sm.address = tex::Address::Wrap;
        const tex::TextureMap smooth = tex::smoothTexture(raw, sm);
        for (const Variant& v : variants) {
          std::fprintf(stderr, ", %s/%s", v.filter.c_str(), v.crease ? "crease" : "nocrease");
          results.push_back(run(truth, probes, f_exact, v.filter == "smoothed" ? smooth : raw, v, size));
        }
        std::fprintf(stderr, "\n");
      }
    }

    // ---- CSV: one row per configuration and depth (depth "all" = every probe).
    std::string csv =
        "surface,size,texel_mm,filter,crease,depth_mm,probes,rms_err_n,max_err_n,rms_force_n,rel_rms,median_rel,max_rel,"
        "no_contact,ns_per_tick\n";
    auto csvRow = [&](const Result& r, const std::string& depth, const Stats& s) {
      csv += bench::fmt("%s,%d,%.4f,%s,%s,%s,%zu,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%zu,%.1f\n", r.surface.c_str(), r.size,
                        r.texel_m * 1e3, r.v.filter.c_str(), r.v.crease ? "on" : "off", depth.c_str(), s.n, s.rms(),
                        s.max_e, std::sqrt(s.sum_f2 / double(std::max<std::size_t>(1, s.n))), s.relRms(),
                        s.medianRel(), s.max_rel,
                        s.no_contact, r.ns_per_tick);
    };
    for (const Result& r : results) {
      csvRow(r, "all", r.all);
      for (std::size_t d = 0; d < kDepths.size(); ++d) csvRow(r, bench::fmt("%.2f", kDepths[d] * 1e3), r.by_depth[d]);
    }
    if (!csv_path.empty()) bench::writeTextFile(csv_path, csv);

    // ---- JSON
    std::string js = "{\n";
    js += "  \"benchmark\": \"force error of the plane proxy vs exact height-field contact\",\n";
    js += "  \"machine\": \"" + bench::machineDescription() + "\",\n";
    js += "  \"date\": \"" + bench::isoTimeNow() + "\",\n";
    js += bench::fmt("  \"stiffness_n_per_m\": %g,\n  \"probes_per_depth\": %d,\n", kStiffness, probes_per_depth);
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
          "    {\"surface\": \"%s\", \"size\": %d, \"texel_mm\": %.4f, \"filter\": \"%s\", \"crease\": %s, "
          "\"probes\": %zu, \"rms_err_n\": %.6g, \"max_err_n\": %.6g, \"rel_rms\": %.6g, \"median_rel\": %.6g, "
          "\"max_rel\": %.6g, "
          "\"no_contact\": %zu, \"ns_per_tick\": %.1f, \"by_depth_rel_rms\": [",
          r.surface.c_str(), r.size, r.texel_m * 1e3, r.v.filter.c_str(), r.v.crease ? "true" : "false", r.all.n,
          r.all.rms(), r.all.max_e, r.all.relRms(), r.all.medianRel(), r.all.max_rel, r.all.no_contact,
          r.ns_per_tick);
      for (std::size_t d = 0; d < kDepths.size(); ++d) js += bench::fmt("%s%.6g", d ? ", " : "", r.by_depth[d].relRms());
      js += std::string("]}") + (i + 1 < results.size() ? ",\n" : "\n");
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
          ps.label = std::string(v.filter == "normal-map" ? "normal map" : v.filter) + (v.crease ? ", crease on" : ", crease off");
          ps.color = v.filter == "nearest"    ? bench::Rgb{214, 39, 40}
                     : v.filter == "bilinear" ? bench::Rgb{31, 119, 180}
                     : v.filter == "smoothed" ? bench::Rgb{44, 160, 44}
                                              : bench::Rgb{127, 127, 127};
          ps.marker = v.crease ? bench::Marker::Square : bench::Marker::Circle;
          ps.filled = !v.crease;
          for (const Result& r : results) {
            if (r.surface != s->name() || r.v.filter != v.filter || r.v.crease != v.crease) continue;
            ps.x.push_back(r.ns_per_tick);
            ps.y.push_back(100.0 * r.all.relRms());
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
        p.y_min = std::pow(10.0, std::floor(std::log10(std::max(y_lo, 1e-3) * 0.8)));
        p.y_max = std::pow(10.0, std::ceil(std::log10(y_hi * 1.25)));
        panels.push_back(p);
      }
      bench::writePlotPng(png_path, panels,
                          "Points labelled by texture size (texels per side over 0.2 m). Regenerate: "
                          "benchmarks/run.sh BUILD_DIR force_error. k = 600 N/m; errors of the renderer as built.");
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
          kStiffness, probes_per_depth, probes_per_depth * int(kDepths.size()), kStartAbove * 1e3, kStep * 1e6,
          kHoldTicks);
      md += "Truth self-checks: " + checks + "\n";
      // Compact view first: relative RMS error by size, and the cost.
      md += "\nRelative RMS force error (median relative error in brackets) by texture size (texel over 0.2 m), and "
            "render cost (ns/tick, median over the four sizes):\n\n";
      md += "| surface | filter | crease |";
      for (int size : kSizes) md += bench::fmt(" %d² (%.2f mm) |", size, 200.0 / size);
      md += " ns/tick |\n|---|---|---|";
      for (std::size_t i = 0; i < kSizes.size(); ++i) md += "---|";
      md += "---|\n";
      for (const auto& s : surfaces) {
        for (const Variant& v : variants) {
          md += "| " + s->name() + " | " + filterText(v.filter) + " | " + (v.crease ? "on" : "off") + " |";
          std::vector<double> cost;
          for (int size : kSizes) {
            for (const Result& r : results) {
              if (r.surface != s->name() || r.size != size || r.v.filter != v.filter || r.v.crease != v.crease) continue;
              md += bench::fmt(" %.1f %% (%.1f %%) |", 100.0 * r.all.relRms(), 100.0 * r.all.medianRel());
              cost.push_back(r.ns_per_tick);
            }
          }
          std::sort(cost.begin(), cost.end());
          md += bench::fmt(" %.0f |\n", cost.empty() ? 0.0 : (cost[(cost.size() - 1) / 2] + cost[cost.size() / 2]) / 2);
        }
      }
      for (const auto& s : surfaces) {
        md += "\n**" + s->description() + "**\n\n";
        md += "| size (texel) | filter | crease | RMS err (mN) | relative RMS | median relative | max err (mN) | "
              "max relative | no contact | ns/tick |\n";
        md += "|---|---|---|---|---|---|---|---|---|---|\n";
        for (const Result& r : results) {
          if (r.surface != s->name()) continue;
          md += bench::fmt("| %d² (%.3f mm) | %s | %s | %.1f | %.1f %% | %.1f %% | %.0f | %.0f %% | %zu | %.0f |\n",
                           r.size, r.texel_m * 1e3, filterText(r.v.filter), r.v.crease ? "on" : "off",
                           r.all.rms() * 1e3, 100.0 * r.all.relRms(), 100.0 * r.all.medianRel(), r.all.max_e * 1e3, 100.0 * r.all.max_rel, r.all.no_contact,
                           r.ns_per_tick);
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
