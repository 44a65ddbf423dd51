// Speed against error of the textured mesh renderer (issue 28; docs/meshes.md): force error
// against the exact displaced surface on a textured sphere and cylinder by triangle count and
// frame (CHAI3D's per-triangle frame as the baseline), the largest turn of the force between two
// ticks of a stroke across edges, and the servo's render cost against the triangle count up to
// 500,000 triangles. Measures only; nothing asserted.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"
#include "benchmarks/bench_stamp.hpp"
#include "benchmarks/exact_curved_surfaces.hpp"
#include "server/textured_mesh_renderer.hpp"
#include "textures/texel_slope_steps.hpp"
#include "tools/report/plot.hpp"

namespace {

using namespace thx;
using Clock = std::chrono::steady_clock;

constexpr const char* kHelp = R"(usage: bench_mesh_force [--triangles N,N,...] [--cost-triangles N,N,...] [--texels N]
                        [--probes N] [--cost-ticks N] [--quick] [--no-slope-steps]
                        [--json F] [--csv F] [--md F] [--png F]

Force error of the textured mesh renderer (server/textured_mesh_renderer.hpp) against the exact
contact force of a displaced sphere and cylinder (benchmarks/exact_curved_surfaces.hpp: sine
bumps, V-grooves; relief maps baked in tangent space), by triangle count and frame: per-triangle
(CHAI3D 3.3's), interpolated (force shading, flat point), interpolated + Phong (the default).
Each probe is pressed from outside along the smooth normal in 20 um steps and held 15 ticks; the
error is |F - k (q - p)| at 600 N/m, relative to the RMS exact force. Then the largest turn of the
force between ticks on a stroke across the edges of an untextured sphere, and the servo's render
cost per tick (p50, p99, max) on a textured sphere stroked in contact, by triangle count:
renderForce() from the reading to the force, and apart from it describeContact() and
prepareNextTick(), which the servo runs once the force is written (p99 of them, and of the whole
tick).

  --triangles LIST       tessellations for the error (default 500,2000,5000,20000,80000)
  --cost-triangles LIST  tessellations for the cost (default 1000,5000,20000,100000,500000)
  --texels N             texels around the circumference (default 1024: 0.195 mm texels)
  --probes N             probes per depth (0.25, 0.5, 1, 2 mm; default 1000)
  --cost-ticks N         ticks timed per tessellation (default 100000)
  --quick                a short run (2 tessellations, 40 probes per depth, 5000 ticks)
  --no-slope-steps       no slope steps for the maps (textures/texel_slope_steps.hpp): the renderer
                         reads every texel's neighbourhood, as before they were built (same forces)
  --json/--csv/--md/--png F   results
)";

constexpr double kK = 600.0;
constexpr double kStep = 2e-5;
constexpr int kHoldTicks = 15;
const std::vector<double> kDepths{0.25e-3, 0.5e-3, 1e-3, 2e-3};

struct ModeInfo {
  mesh::FrameMode mode;
  const char* id;
};
const ModeInfo kModes[] = {{mesh::FrameMode::PerTriangle, "per-triangle"},
                           {mesh::FrameMode::Interpolated, "interpolated"},
                           {mesh::FrameMode::InterpolatedPhong, "interpolated+phong"}};


// A tessellated surface with its hierarchy, ready for renderers.
struct Tessellation {
  mesh::GeneratedMesh generated;
  std::unique_ptr<srv::TriangleBvh> bvh;
  double build_ms = 0.0;
  Tessellation(const bench::CurvedSurface& s, int triangles) {
    const auto t0 = Clock::now();
    generated = s.tessellate(triangles);
    bvh = std::make_unique<srv::TriangleBvh>(generated.mesh.positions, generated.mesh.triangles);
    build_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  }
  std::size_t triangles() const { return generated.mesh.triangles.size(); }
  std::size_t bytes() const { return generated.mesh.bytes() + bvh->bytes(); }
};

struct ErrorRow {
  std::string surface, mode;
  std::size_t triangles = 0;
  double rel_rms = 0, rel_median = 0, rel_max = 0, ns_per_tick = 0;
  int no_contact = 0, probes = 0, over_20 = 0;  // over_20: probes whose error is above 20 % of their force
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

ErrorRow measureError(const bench::CurvedSurface& s, const tex::TextureMap& map, const tex::TexelSlopeSteps* slope_steps,
                      const Tessellation& t, const ModeInfo& m,
                      const std::vector<Eigen::Vector2d>& xy, const std::vector<Eigen::Vector3d>& probes,
                      const std::vector<Eigen::Vector3d>& f_exact) {
  srv::RendererConfig rc;
  rc.stiffness_n_per_m = kK;
  const srv::MeshTexture texture{&map, {tex::Filter::Bilinear, tex::Address::Wrap}, true, Eigen::Vector2d::Zero(), slope_steps};
  srv::TexturedMeshRenderer r(t.generated.mesh, *t.bvh, texture,
                              Eigen::Isometry3d::Identity(), rc, m.mode);
  ErrorRow row{s.name(), m.id, t.triangles()};
  double sum_e2 = 0, sum_f2 = 0;
  std::vector<double> ns, rel;
  for (std::size_t i = 0; i < probes.size(); ++i) {
    const Eigen::Vector3d n0 = s.normal(xy[i].x(), xy[i].y());
    const Eigen::Vector3d start = s.base(xy[i].x(), xy[i].y()) + 0.6e-3 * n0;  // outside the envelope
    const int steps = int(std::ceil((start - probes[i]).norm() / kStep));
    r.reset();
    const auto t0 = Clock::now();
    for (int k = 0; k < steps; ++k) r.render(start + (probes[i] - start) * (double(k) / steps), -n0 * kStep * 1000);
    srv::RenderOutput out;
    for (int k = 0; k < kHoldTicks; ++k) out = r.render(probes[i], Eigen::Vector3d::Zero());
    ns.push_back(std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / (steps + kHoldTicks));
    const double e = (out.force_world - f_exact[i]).norm(), f = f_exact[i].norm();
    sum_e2 += e * e;
    sum_f2 += f * f;
    row.rel_max = std::max(row.rel_max, e / f);
    rel.push_back(e / f);
    row.over_20 += e / f > 0.2 ? 1 : 0;
    row.no_contact += out.in_contact ? 0 : 1;
  }
  row.probes = int(probes.size());
  row.rel_rms = std::sqrt(sum_e2 / sum_f2);
  row.rel_median = median(rel);
  row.ns_per_tick = median(ns);
  return row;
}

struct EdgeRow {
  std::size_t triangles = 0;
  std::string mode;
  double largest_step_deg = 0, natural_step_deg = 0;
};

// A stroke along latitude 20 degrees of the untextured sphere, 1 mm deep, 20 mm/s: the largest
// angle between the forces of two consecutive ticks.
EdgeRow measureEdges(const bench::CurvedSurface& s, const Tessellation& t, const ModeInfo& m) {
  srv::RendererConfig rc;
  rc.stiffness_n_per_m = kK;
  srv::TexturedMeshRenderer r(t.generated.mesh, *t.bvh, {}, Eigen::Isometry3d::Identity(), rc, m.mode);
  const double lat = 20 * M_PI / 180, rho = s.radius() - 1e-3;
  auto at = [&](double phi, double radius) {
    return Eigen::Vector3d(radius * std::cos(lat) * std::cos(phi), radius * std::cos(lat) * std::sin(phi), radius * std::sin(lat));
  };
  r.reset();
  for (int k = 0; k <= 60; ++k) r.render(at(0.0, s.radius() + 0.6e-3 - (1.6e-3 * k) / 60), Eigen::Vector3d::Zero());
  EdgeRow row{t.triangles(), m.id};
  const double dphi = kStep / (rho * std::cos(lat));
  row.natural_step_deg = dphi * 180 / M_PI;
  Eigen::Vector3d last = Eigen::Vector3d::Zero();
  for (double phi = 0; phi < 1.0; phi += dphi) {
    const srv::RenderOutput out = r.render(at(phi, rho), Eigen::Vector3d::Zero());
    if (!last.isZero() && !out.force_world.isZero()) {
      row.largest_step_deg = std::max(
          row.largest_step_deg, std::atan2(out.force_world.cross(last).norm(), out.force_world.dot(last)) * 180 / M_PI);
    }
    last = out.force_world;
  }
  return row;
}

struct CostRow {
  std::size_t triangles = 0, bytes = 0;
  double build_ms = 0, p50_us = 0, p99_us = 0, max_us = 0, contact_share = 0;
  // The work done after the force (describeContact: where the contact is; prepareNextTick: for
  // the ticks after it), and the whole tick's.
  double after_p99_us = 0, tick_p99_us = 0;
  // The same stroke with every sweep asked of the hierarchy (TexturedMeshRenderer::useLocalSet).
  double hierarchy_p50_us = 0, hierarchy_p99_us = 0;
};

// The textured sphere stroked in contact, 1 mm under the smooth surface at 50 mm/s along a
// wavy path round the equator; every tick timed, from the reading to the force and after it.
struct StrokeTimes {
  double p50_us = 0, p99_us = 0, max_us = 0, contact_share = 0, after_p99_us = 0, tick_p99_us = 0;
};

double percentile(std::vector<double>& v, double q) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(q * double(v.size())))];
}

StrokeTimes timeStroke(const bench::CurvedSurface& s, const tex::TextureMap& map, const tex::TexelSlopeSteps* steps,
                       const Tessellation& t, int ticks,
                       bool local_set) {
  srv::RendererConfig rc;
  rc.stiffness_n_per_m = kK;
  const srv::MeshTexture texture{&map, {tex::Filter::Bilinear, tex::Address::Wrap}, true, Eigen::Vector2d::Zero(), steps};
  srv::TexturedMeshRenderer r(t.generated.mesh, *t.bvh, texture,
                              Eigen::Isometry3d::Identity(), rc);
  r.useLocalSet(local_set);
  auto path = [&](int k) -> Eigen::Vector3d {
    const double X = 5e-5 * k, Y = M_PI / 2 * s.radius() + 0.01 * std::sin(X / 0.03);
    return s.base(X, Y) - 1e-3 * s.normal(X, Y);
  };
  r.reset();
  const Eigen::Vector3d n0 = s.normal(0, M_PI / 2 * s.radius());
  for (int k = 0; k <= 60; ++k) r.render(path(0) + n0 * (1.6e-3 * (60 - k) / 60), Eigen::Vector3d::Zero());
  // As the servo does: renderForce() from the reading to the force, then describeContact() and
  // prepareNextTick() once the force is out; each half timed apart, and the two together as the
  // tick's whole work.
  std::vector<double> us(static_cast<std::size_t>(ticks)), after_us(us.size()), tick_us(us.size());
  int contact = 0;
  for (int k = 0; k < ticks; ++k) {
    const Eigen::Vector3d tip = path(k);
    const auto t0 = Clock::now();
    srv::RenderOutput out = r.renderForce(tip, Eigen::Vector3d::Zero());
    const auto t1 = Clock::now();
    r.describeContact(out);
    r.prepareNextTick();
    const auto t2 = Clock::now();
    us[std::size_t(k)] = std::chrono::duration<double, std::micro>(t1 - t0).count();
    after_us[std::size_t(k)] = std::chrono::duration<double, std::micro>(t2 - t1).count();
    tick_us[std::size_t(k)] = std::chrono::duration<double, std::micro>(t2 - t0).count();
    contact += out.in_contact ? 1 : 0;
  }
  StrokeTimes times;
  times.p50_us = percentile(us, 0.5);
  times.p99_us = percentile(us, 0.99);
  times.max_us = us.back();
  times.after_p99_us = percentile(after_us, 0.99);
  times.tick_p99_us = percentile(tick_us, 0.99);
  times.contact_share = double(contact) / ticks;
  return times;
}

CostRow measureCost(const bench::CurvedSurface& s, const tex::TextureMap& map, const tex::TexelSlopeSteps* steps,
                    int triangles, int ticks) {
  const Tessellation t(s, triangles);
  // The hierarchy alone first, then the default (the local set): the same mesh, already in
  // memory for both.
  const StrokeTimes hierarchy = timeStroke(s, map, steps, t, ticks, false);
  const StrokeTimes local = timeStroke(s, map, steps, t, ticks, true);
  CostRow row;
  row.triangles = t.triangles();
  row.bytes = t.bytes();
  row.build_ms = t.build_ms;
  row.p50_us = local.p50_us;
  row.p99_us = local.p99_us;
  row.max_us = local.max_us;
  row.contact_share = local.contact_share;
  row.after_p99_us = local.after_p99_us;
  row.tick_p99_us = local.tick_p99_us;
  row.hierarchy_p50_us = hierarchy.p50_us;
  row.hierarchy_p99_us = hierarchy.p99_us;
  return row;
}

int run(int argc, char** argv) {
  std::vector<int> triangle_counts{500, 2000, 5000, 20000, 80000}, cost_counts{1000, 5000, 20000, 100000, 500000};
  int texels = 1024, probes_per_depth = 1000, cost_ticks = 100000;
  bool slope_steps = true;
  std::string json, csv, md, png;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      triangle_counts = {2000, 5000};
      cost_counts = {5000, 100000};
      probes_per_depth = 40;
      cost_ticks = 5000;
      continue;
    }
    if (a == "--no-slope-steps") {
      slope_steps = false;
      continue;
    }
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--triangles") triangle_counts = cli::parseIntegerList(a, v, 8, 4'000'000);
    else if (a == "--cost-triangles") cost_counts = cli::parseIntegerList(a, v, 8, 4'000'000);
    else if (a == "--texels") texels = int(cli::parseInteger(a, v, 16, 8192));
    else if (a == "--probes") probes_per_depth = int(cli::parseInteger(a, v, 1, 100000));
    else if (a == "--cost-ticks") cost_ticks = int(cli::parseInteger(a, v, 100, 10'000'000));
    else if (a == "--json") json = v;
    else if (a == "--csv") csv = v;
    else if (a == "--md") md = v;
    else if (a == "--png") png = v;
    else throw UsageError("unknown option " + a + " (see --help)");
  }

  std::vector<ErrorRow> errors;
  std::vector<EdgeRow> edges;
  std::vector<CostRow> costs;
  std::string checks;
  for (const auto& [shape, field] : {std::pair<std::string, std::string>{"sphere", "sine"}, {"cylinder", "sine"}, {"cylinder", "vgrooves"}}) {
    auto s = bench::makeCurvedSurface(shape, field);
    const Eigen::Vector2d ext = s->extent();
    const int w = texels, h = int(std::lround(texels * ext.y() / ext.x()));
    std::fprintf(stderr, "bench_mesh_force: %s: baking %dx%d", s->name().c_str(), w, h);
    const tex::TextureMap map = s->bake(w, h);
    // As hapticd builds them with the scene's surface (scenes/scene_surface.hpp); off, the renderer
    // reads every texel's neighbourhood (the same forces, more work).
    const tex::TexelSlopeSteps built_steps(map);
    const tex::TexelSlopeSteps* steps = slope_steps ? &built_steps : nullptr;
    // Probes: (X, Y) uniform in the surface's probe range, each at the four depths under the
    // displaced surface along the smooth normal.
    std::mt19937_64 rng(shape == "sphere" ? 11u : (field == "sine" ? 23u : 37u));
    std::uniform_real_distribution<double> U(0.0, 1.0);
    const Eigen::Vector4d range = s->probeRange();
    std::vector<Eigen::Vector2d> xy;
    std::vector<Eigen::Vector3d> probes, f_exact;
    double worst_normal = 0.0;
    for (int i = 0; i < probes_per_depth * int(kDepths.size()); ++i) {
      const Eigen::Vector2d c(range[0] + (range[1] - range[0]) * U(rng), range[2] + (range[3] - range[2]) * U(rng));
      const Eigen::Vector3d p = s->surface(c.x(), c.y()) - kDepths[std::size_t(i) % kDepths.size()] * s->normal(c.x(), c.y());
      const Eigen::Vector3d q = s->closest(p);
      xy.push_back(c);
      probes.push_back(p);
      f_exact.push_back(kK * (q - p));
      if (field == "sine") {
        // Optimality: q - p along the displaced surface's normal at q.
        const Eigen::Vector2d qc = s->paramsOf(q);
        Eigen::Vector2d best = qc;
        double bd = 1e9;
        for (int k = -4; k <= 4; ++k) {  // q's own parameters (the radial projection of a displaced point moves it)
          for (int l = -4; l <= 4; ++l) {
            const Eigen::Vector2d c2 = qc + Eigen::Vector2d(k, l) * 2e-4;
            if ((s->surface(c2.x(), c2.y()) - q).norm() < bd) bd = (s->surface(c2.x(), c2.y()) - q).norm(), best = c2;
          }
        }
        const double e = 1e-7;
        const Eigen::Vector3d sx = s->surface(best.x() + e, best.y()) - s->surface(best.x() - e, best.y());
        const Eigen::Vector3d sy = s->surface(best.x(), best.y() + e) - s->surface(best.x(), best.y() - e);
        worst_normal = std::max(worst_normal, (q - p).normalized().cross(sx.cross(sy).normalized()).norm() * (q - p).norm());
      }
    }
    if (field == "sine") checks += bench::fmt("%s: |(q - p) x n(q)| <= %.1e m. ", s->name().c_str(), worst_normal);
    for (int n : triangle_counts) {
      const Tessellation t(*s, n);
      std::fprintf(stderr, ", %zu", t.triangles());
      for (const ModeInfo& m : kModes) errors.push_back(measureError(*s, map, steps, t, m, xy, probes, f_exact));
      if (shape == "sphere") {
        for (const ModeInfo& m : kModes) edges.push_back(measureEdges(*s, t, m));
      }
    }
    if (shape == "sphere") {
      for (int n : cost_counts) {
        std::fprintf(stderr, ", cost %d", n);
        costs.push_back(measureCost(*s, map, steps, n, cost_ticks));
      }
    }
    std::fprintf(stderr, "\n");
  }

  // ---- results
  const std::string stamp = bench::fmt("%s, %s build, %s", bench::isoNow().c_str(), bench::buildType(),
                                       bench::machineSummary().c_str());
  std::string c = "table,surface,triangles,frame,rel_rms,rel_median,rel_max,over_20pct,no_contact,probes,ns_per_tick,"
                  "largest_step_deg,natural_step_deg,bytes,build_ms,p50_us,p99_us,max_us,contact_share,hierarchy_p50_us,"
                  "hierarchy_p99_us,after_p99_us,tick_p99_us\n";
  for (const ErrorRow& r : errors) {
    c += bench::fmt("error,%s,%zu,%s,%.6g,%.6g,%.6g,%d,%d,%d,%.1f,,,,,,,,,,,,\n", r.surface.c_str(), r.triangles, r.mode.c_str(),
                    r.rel_rms, r.rel_median, r.rel_max, r.over_20, r.no_contact, r.probes, r.ns_per_tick);
  }
  for (const EdgeRow& r : edges) {
    c += bench::fmt("edges,sphere+untextured,%zu,%s,,,,,,,,%.5g,%.5g,,,,,,,,,,\n", r.triangles, r.mode.c_str(), r.largest_step_deg,
                    r.natural_step_deg);
  }
  for (const CostRow& r : costs) {
    c += bench::fmt("cost,sphere+sine,%zu,interpolated+phong,,,,,,,,,,%zu,%.1f,%.3f,%.3f,%.3f,%.4f,%.3f,%.3f,%.3f,%.3f\n",
                    r.triangles, r.bytes, r.build_ms, r.p50_us, r.p99_us, r.max_us, r.contact_share, r.hierarchy_p50_us,
                    r.hierarchy_p99_us, r.after_p99_us, r.tick_p99_us);
  }
  if (!csv.empty()) bench::writeTextFile(csv, c);
  if (!json.empty()) {
    std::string j = "{\n  \"benchmark\": \"textured mesh force error, edge steps and render cost\",\n";
    j += bench::fmt("  \"stamp\": \"%s\",\n  \"build_type\": \"%s\",\n  \"stiffness_n_per_m\": %g,\n  \"texels\": %d,\n", stamp.c_str(),
                    bench::buildType(), kK, texels);
    j += "  \"rows\": [\n";
    for (std::size_t i = 0; i < errors.size(); ++i) {
      const ErrorRow& r = errors[i];
      j += bench::fmt("    {\"surface\": \"%s\", \"triangles\": %zu, \"frame\": \"%s\", \"rel_rms\": %.6g, \"rel_median\": %.6g, "
                      "\"rel_max\": %.6g, \"over_20pct\": %d, \"no_contact\": %d, \"probes\": %d, \"ns_per_tick\": %.1f}%s\n",
                      r.surface.c_str(), r.triangles, r.mode.c_str(), r.rel_rms, r.rel_median, r.rel_max, r.over_20,
                      r.no_contact, r.probes, r.ns_per_tick, i + 1 < errors.size() ? "," : "");
    }
    j += "  ],\n  \"edges\": [\n";
    for (std::size_t i = 0; i < edges.size(); ++i) {
      j += bench::fmt("    {\"triangles\": %zu, \"frame\": \"%s\", \"largest_step_deg\": %.5g, \"natural_step_deg\": %.5g}%s\n",
                      edges[i].triangles, edges[i].mode.c_str(), edges[i].largest_step_deg, edges[i].natural_step_deg,
                      i + 1 < edges.size() ? "," : "");
    }
    j += "  ],\n  \"cost\": [\n";
    for (std::size_t i = 0; i < costs.size(); ++i) {
      const CostRow& r = costs[i];
      j += bench::fmt("    {\"triangles\": %zu, \"bytes\": %zu, \"build_ms\": %.1f, \"p50_us\": %.3f, \"p99_us\": %.3f, "
                      "\"max_us\": %.3f, \"contact_share\": %.4f, \"hierarchy_p50_us\": %.3f, \"hierarchy_p99_us\": %.3f, "
                      "\"after_p99_us\": %.3f, \"tick_p99_us\": %.3f}%s\n",
                      r.triangles, r.bytes, r.build_ms, r.p50_us, r.p99_us, r.max_us, r.contact_share, r.hierarchy_p50_us,
                      r.hierarchy_p99_us, r.after_p99_us, r.tick_p99_us, i + 1 < costs.size() ? "," : "");
    }
    j += "  ]\n}\n";
    bench::writeTextFile(json, j);
  }
  if (!md.empty()) {
    std::string t = bench::fmt("Measured %s. Stiffness %g N/m, relief maps of %d texels around (0.195 mm texels at 1024), bilinear, "
                               "slope steps %s. Checks of the truth: %s\n\n",
                               stamp.c_str(), kK, texels, slope_steps ? "on" : "off (--no-slope-steps)", checks.c_str());
    t += "Errors relative to the RMS exact force (RMS), or each probe's own (median, max, and the probes above 20 %).\n\n";
    t += "| surface | triangles | frame | RMS error | median | max | probes > 20 % | no contact | ns/tick |\n"
         "|---|---:|---|---:|---:|---:|---:|---:|---:|\n";
    for (const ErrorRow& r : errors) {
      t += bench::fmt("| %s | %zu | %s | %.2f %% | %.3f %% | %.1f %% | %d | %d / %d | %.0f |\n", r.surface.c_str(), r.triangles,
                      r.mode.c_str(), 100 * r.rel_rms, 100 * r.rel_median, 100 * r.rel_max, r.over_20, r.no_contact, r.probes,
                      r.ns_per_tick);
    }
    t += "\n**Across edges** (untextured sphere, a stroke along latitude 20° 1 mm deep at 20 mm/s): the largest turn of the "
         "force between two ticks, against the turn of the surface normal per tick.\n\n";
    t += "| triangles | frame | largest turn per tick | the normal's turn per tick |\n|---:|---|---:|---:|\n";
    for (const EdgeRow& r : edges) {
      t += bench::fmt("| %zu | %s | %.3f° | %.3f° |\n", r.triangles, r.mode.c_str(), r.largest_step_deg, r.natural_step_deg);
    }
    t += "\n**Render cost** (textured sphere, interpolated + Phong, stroked 1 mm deep at 50 mm/s; every `renderForce()` timed, "
         "from the reading to the force; after it, as in the servo once the force is written, `describeContact()` and "
         "`prepareNextTick()` timed apart, and the two halves together as the tick's whole work; the sweeps from the leaves around the pen, the default, "
         "and from the hierarchy every time, the same stroke just before):\n\n";
    t += "| triangles | mesh + BVH | build | p50 | p99 | max | in contact | after the force: p99 | whole tick: p99 | "
         "hierarchy only: p50 | p99 |\n"
         "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const CostRow& r : costs) {
      t += bench::fmt("| %zu | %.1f MB | %.0f ms | %.2f µs | %.2f µs | %.1f µs | %.1f %% | %.2f µs | %.2f µs | %.2f µs | %.2f µs |\n",
                      r.triangles, double(r.bytes) / 1e6, r.build_ms, r.p50_us, r.p99_us, r.max_us, 100 * r.contact_share,
                      r.after_p99_us, r.tick_p99_us, r.hierarchy_p50_us, r.hierarchy_p99_us);
    }
    bench::writeTextFile(md, t);
  }
  if (!png.empty()) {
    bench::PlotPanel err, cost;
    err.title = "Force error against triangles", err.x_label = "triangles", err.y_label = "RMS force error (%)";
    cost.title = "Render cost against triangles", cost.x_label = "triangles", cost.y_label = "microseconds per tick";
    const bench::Rgb colours[] = {{200, 60, 40}, {60, 120, 200}, {40, 150, 70}};
    const bench::Marker markers[] = {bench::Marker::Circle, bench::Marker::Square, bench::Marker::Triangle};
    double ymin = 1e9, ymax = 0, xmin = 1e9, xmax = 0;
    int si = 0;
    for (const std::string surface : {"sphere+sine", "cylinder+sine", "cylinder+vgrooves"}) {
      for (int mi = 0; mi < 3; ++mi) {
        bench::PlotSeries series;
        series.label = surface + ", " + kModes[mi].id;
        series.color = colours[mi];
        series.marker = markers[si];
        for (const ErrorRow& r : errors) {
          if (r.surface != surface || r.mode != kModes[mi].id) continue;
          series.x.push_back(double(r.triangles));
          series.y.push_back(100 * r.rel_rms);
          ymin = std::min(ymin, 100 * r.rel_rms), ymax = std::max(ymax, 100 * r.rel_rms);
          xmin = std::min(xmin, double(r.triangles)), xmax = std::max(xmax, double(r.triangles));
        }
        if (!series.x.empty()) err.series.push_back(series);
      }
      ++si;
    }
    err.x_min = xmin / 1.5, err.x_max = xmax * 1.5, err.y_min = ymin / 1.5, err.y_max = ymax * 1.5;
    bench::PlotSeries p50, p99;
    p50.label = "p50", p50.color = {60, 120, 200};
    p99.label = "p99", p99.color = {200, 60, 40}, p99.marker = bench::Marker::Square;
    double cmin = 1e9, cmax = 0;
    bench::PlotSeries p99_hierarchy, p99_tick;
    p99_hierarchy.label = "p99, hierarchy only", p99_hierarchy.color = {150, 150, 150};
    p99_hierarchy.marker = bench::Marker::Square;
    p99_tick.label = "p99, whole tick (render + after the force)", p99_tick.color = {40, 150, 70};
    p99_tick.marker = bench::Marker::Triangle;
    for (const CostRow& r : costs) {
      p50.x.push_back(double(r.triangles)), p50.y.push_back(r.p50_us);
      p99.x.push_back(double(r.triangles)), p99.y.push_back(r.p99_us);
      p99_hierarchy.x.push_back(double(r.triangles)), p99_hierarchy.y.push_back(r.hierarchy_p99_us);
      p99_tick.x.push_back(double(r.triangles)), p99_tick.y.push_back(r.tick_p99_us);
      cmin = std::min(cmin, r.p50_us), cmax = std::max({cmax, r.p99_us, r.hierarchy_p99_us, r.tick_p99_us});
    }
    cost.series = {p50, p99, p99_tick, p99_hierarchy};
    if (!costs.empty()) {
      cost.x_min = double(costs.front().triangles) / 1.5, cost.x_max = double(costs.back().triangles) * 1.5;
      cost.y_min = cmin / 1.5, cost.y_max = cmax * 1.5;
    }
    bench::writePlotPng(png, {err, cost}, "bench_mesh_force: textured meshes, speed against error (" + stamp + ")");
  }
  std::fputs(c.c_str(), stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_mesh_force", run); }
