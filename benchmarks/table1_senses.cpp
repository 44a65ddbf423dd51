#include "benchmarks/table1_senses.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>

#include "base/elapsed.hpp"
#include "benchmarks/bench_physics_grounds.hpp"
#include "clients/visual/frame_renderer.hpp"
#include "clients/visual/mesh_builders.hpp"
#include "rt/clock.hpp"
#include "server/mesh_god_object.hpp"
#include "server/servo_rig.hpp"
#include "server/triangle_bvh.hpp"
#include "server/triangle_mesh.hpp"
#include "server/scene_device.hpp"
#include "textures/texture_io.hpp"

namespace thx::bench::table1 {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const std::size_t k = std::min(v.size() - 1, std::size_t(q * double(v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}

// User + system time of the whole process (llvmpipe's threads included).
double processCpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  const auto s = [](const timeval& t) { return double(t.tv_sec) + double(t.tv_usec) * 1e-6; };
  return s(u.ru_utime) + s(u.ru_stime);
}

volatile double g_sink = 0;

// One render() per tick of `path`, `passes` times from a reset: the median of each pass's median
// tick and the 99th percentile over all ticks (Timing's median_s and p99_s); the ticks in contact
// on the first pass into `contact_ticks`.
template <class Renderer>
Timing timeRenderTicks(Renderer& r, const std::vector<dev::DeviceState>& path, int passes, std::size_t& contact_ticks) {
  std::vector<double> all, medians;
  all.reserve(std::size_t(passes) * path.size());
  contact_ticks = 0;
  for (int pass = 0; pass < passes; ++pass) {
    r.reset();
    std::vector<double> t;
    t.reserve(path.size());
    for (const dev::DeviceState& s : path) {
      const std::int64_t t0 = rt::monotonicNowNs();
      const srv::RenderOutput o = r.render(s.p_world, s.v_world);
      const std::int64_t t1 = rt::monotonicNowNs();
      g_sink = g_sink + o.force_world.z();  // keeps the call from being optimised away
      if (pass == 0 && o.in_contact) ++contact_ticks;
      t.push_back(double(t1 - t0) * 1e-9);
    }
    medians.push_back(median(t));
    all.insert(all.end(), t.begin(), t.end());
  }
  Timing out;
  out.median_s = median(medians);
  out.p99_s = quantile(all, 0.99);
  return out;
}

// The scene's surface as a height field in bench_physics' frame (centred square, z up): bilinear
// in the texture's depth at texel centres, so a ground of the texture's resolution holds exactly
// its texels and a coarser one their averages.
SurfaceSpec specOf(const SceneTexture& st) {
  const tex::TextureMap& map = st.map();
  const double extent = st.scene.surface.size_m.x();
  SurfaceSpec s;
  s.name = st.scene.name;
  s.extent_m = extent;
  const tex::TextureMap* m = &map;
  s.height = [m, extent](double x, double y) {
    const int w = m->width(), h = m->height();
    const double u = std::clamp((x + 0.5 * extent) / extent * w - 0.5, 0.0, double(w - 1));
    const double v = std::clamp((-y + 0.5 * extent) / extent * h - 0.5, 0.0, double(h - 1));
    const int i = std::min(int(u), w - 2), j = std::min(int(v), h - 2);
    const double fu = u - i, fv = v - j;
    const double d = (1 - fu) * (1 - fv) * m->depth(i, j) + fu * (1 - fv) * m->depth(i + 1, j) +
                     (1 - fu) * fv * m->depth(i, j + 1) + fu * fv * m->depth(i + 1, j + 1);
    return -d;
  };
  return s;
}

}  // namespace

Sizes measureSizes(const SceneTexture& st, const std::string& workdir) {
  Sizes s;
  const tex::TextureMap& relief = st.map();
  tex::TextureMap normal(relief.width(), relief.height(), tex::Representation::Normal);
  for (int j = 0; j < relief.height(); ++j)
    for (int i = 0; i < relief.width(); ++i) normal.setNormal(i, j, relief.normal(i, j));
  tex::SaveOptions o;
  o.bit_depth = 8;
  const std::filesystem::path dir(workdir);
  std::filesystem::create_directories(dir);
  tex::saveTexture((dir / "table1_normal.png").string(), normal, o);
  tex::saveTexture((dir / "table1_relief.png").string(), relief, o);
  s.file_bytes[kNormal] = double(std::filesystem::file_size(dir / "table1_normal.png"));
  s.file_bytes[kRelief] = double(std::filesystem::file_size(dir / "table1_relief.png"));
  s.memory_bytes[kNormal] = double(normal.bytes());
  s.memory_bytes[kRelief] = double(relief.bytes());
  s.vertices[kNormal] = s.vertices[kRelief] = std::nan("");
  for (int c : {kMesh256, kMesh512}) {
    const visual::MeshData mesh = visual::displacedGrid(st.surface.surface, c == kMesh256 ? 256 : 512);
    const double bytes = double(mesh.positions.size() * sizeof(Eigen::Vector3f) +
                                mesh.normals.size() * sizeof(Eigen::Vector3f) +
                                mesh.indices.size() * sizeof(std::uint32_t));
    s.file_bytes[std::size_t(c)] = s.memory_bytes[std::size_t(c)] = bytes;
    s.vertices[std::size_t(c)] = double(mesh.positions.size());
  }
  return s;
}

std::array<Timing, kColumns> timePhysics(const SceneTexture& st, int steps, int reps) {
  const SurfaceSpec spec = specOf(st);
  const int n = st.map().width();
  const std::pair<Rep, int> grounds[kColumns] = {{Rep::Normal, n}, {Rep::Relief, n}, {Rep::Mesh, 256}, {Rep::Mesh, 512}};
  std::array<Timing, kColumns> out;
  constexpr double kRadius = 0.006, kMass = 0.00235, kSpeed = 0.05, kDt = 1e-3;
  for (int c = 0; c < kColumns; ++c) {
    const Ground ground(spec, grounds[c].first, grounds[c].second);
    std::vector<double> medians, cpu;
    long long contacts = 0;
    for (int r = 0; r < reps; ++r) {
      Sim sim(ground);
      // Starts on a brick face's height at x = -0.06 and rolls along +x across the head joints.
      const double x0 = -0.06, y0 = 0.0;
      const double z0 = (grounds[c].first == Rep::Normal ? 0.0 : spec.height(x0, y0)) + kRadius + 1e-4;
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.translation() = Eigen::Vector3d(x0, y0, z0);
      sim.object = &sim.world.addSphere(kRadius, kMass, pose, {0.5, 0.0, 0.0});
      phys::setVelocity(*sim.object, {kSpeed, 0, 0}, {0, kSpeed / kRadius, 0});
      for (int k = 0; k < 100; ++k) sim.world.step(kDt);
      std::vector<double> t;
      t.reserve(std::size_t(steps));
      const double cpu0 = processCpuSeconds();
      for (int k = 0; k < steps; ++k) {
        const auto t0 = std::chrono::steady_clock::now();
        sim.world.step(kDt);
        t.push_back(secondsSince(t0));
        contacts += sim.contactPoints();
      }
      cpu.push_back((processCpuSeconds() - cpu0) / steps);
      medians.push_back(median(t));
    }
    out[std::size_t(c)].median_s = median(medians);
    out[std::size_t(c)].cpu_s = median(cpu);
    out[std::size_t(c)].note = std::string(repName(grounds[c].first)) + " " + std::to_string(grounds[c].second) + "², " +
                               (ground.triangles() > 0 ? std::to_string(ground.triangles()) + " triangles, " : "") + "built in " +
                               std::to_string(int(ground.buildMs())) + " ms, " +
                               std::to_string(double(contacts) / double(steps * reps)).substr(0, 4) + " contact points per step";
  }
  return out;
}

std::array<Timing, kColumns> timeVisual(const SceneTexture& st, int width, int height, int frames) {
  std::array<Timing, kColumns> out;
  const tex::TexturedSurface& surface = st.surface.surface;
  const Eigen::Isometry3d& plane = surface.mapping().plane_to_world;
  for (int c = 0; c < kColumns; ++c) {
    visual::RenderSettings settings;
    settings.mode = c == kNormal ? visual::SurfaceMode::Normal : c == kRelief ? visual::SurfaceMode::Relief
                                                                               : visual::SurfaceMode::Mesh;
    settings.mesh_n = c == kMesh512 ? 512 : 256;
    visual::FrameRenderer renderer(surface, settings, width, height);
    std::vector<double> t;
    double cpu0 = 0;
    for (int k = -2; k < frames; ++k) {
      if (k == 0) cpu0 = processCpuSeconds();
      // bench_visual's camera path: a close view sweeping 60 degrees of azimuth.
      visual::CameraPlacement p;
      p.elevation_deg = 35;
      p.azimuth_deg = -120 + 60.0 * std::max(0, k) / std::max(1, frames - 1);
      p.distance_m = 0.08;
      p.target_local = {0.03, -0.015};
      const visual::Camera camera(p, plane, width, height);
      const auto t0 = std::chrono::steady_clock::now();
      renderer.render(camera, {});
      if (k >= 0) t.push_back(secondsSince(t0));
    }
    out[std::size_t(c)].median_s = median(t);
    out[std::size_t(c)].cpu_s = (processCpuSeconds() - cpu0) / frames;
    out[std::size_t(c)].note = visual::modeName(settings) + " at " + std::to_string(width) + "x" + std::to_string(height);
  }
  return out;
}

std::array<Timing, 2> timeHaptics(const SceneTexture& st, int passes, std::vector<dev::DeviceState>& relief_path) {
  std::array<Timing, 2> out;
  for (int c : {kNormal, kRelief}) {
    const bool relief = c == kRelief;
    const Recording rec = recordRun(st.scene, st.map(), relief, /*crease=*/true);
    if (rec.last_contact < rec.first_contact)
      throw Error(Error::Kind::Config, st.scene.name + ": the scripted path never touched the surface");
    const std::vector<dev::DeviceState> path(rec.states.begin() + std::ptrdiff_t(rec.first_contact),
                                             rec.states.begin() + std::ptrdiff_t(rec.last_contact + 1));
    ReplayDevice dummy(srv::deviceSpecFor(st.scene), path);
    ServerRig rig(st.scene, st.map(), relief, /*crease=*/true, dummy);
    std::size_t contact = 0;
    out[std::size_t(c)] = timeRenderTicks(rig.renderer(), path, passes, contact);
    out[std::size_t(c)].note = std::to_string(path.size()) + " ticks of the scripted path (first to last contact), " +
                               std::to_string(passes) + " passes";
    if (relief) relief_path = path;
  }
  return out;
}

Timing timeMeshHaptics(const SceneTexture& st, int mesh_n, const std::vector<dev::DeviceState>& path, int passes) {
  const PlacedSurface placed(st.scene, st.map(), /*relief=*/true);
  const srv::TriangleMesh mesh = srv::reliefGridMesh(placed.surface, mesh_n);
  const srv::TriangleBvh bvh(mesh);
  srv::MeshGodObject r(bvh, placed.surface.mapping(), srv::servoRigConfigFor(st.scene).renderer);
  std::size_t contact = 0;
  Timing out = timeRenderTicks(r, path, passes, contact);
  out.note = "god object on the " + std::to_string(mesh_n) + "^2 mesh (" + std::to_string(mesh.triangles.size()) +
             " triangles, BVH), the relief's " + std::to_string(path.size()) + " ticks (" + std::to_string(contact) +
             " in contact), " + std::to_string(passes) + " passes";
  return out;
}

}  // namespace thx::bench::table1
