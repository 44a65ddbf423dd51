// Visual client (issue 15): frame time against image error on this machine's renderer (llvmpipe
// without a GPU). Rows: normal mapping; relief with linear 8..64 and binary 4..8 steps, with and
// without self-shadowing; the accelerated search over the relief's max-mipmap (--search maxmip)
// with and without shadows; the displaced meshes at 256^2 and 512^2; a textured sphere of 101,760
// triangles (issue 28: the plane's texture in the mesh's tangent frames) in normal and relief mode,
// filling the frame as the plane does; at 640x360 and 1280x720.
// Time: median over a camera path (glFinish per frame). Error: against the exact CPU reference
// (clients/visual/cpu_reference.hpp; shadows in the reference iff the row has them) on two poses
// of the path: pixels whose hit lands on another texel, mean intensity error in 8-bit LSB.
// Timing is measured here, never asserted (docs/design.md §4 rule 7).
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_stamp.hpp"
#include "clients/visual/frame_renderer.hpp"
#include "clients/visual/headless_context.hpp"
#include "clients/visual/image_error.hpp"
#include "clients/visual/max_mipmap.hpp"
#include "clients/visual/mesh_frame_renderer.hpp"
#include "clients/visual/mesh_image_error.hpp"
#include "meshes/mesh_generators.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_surface.hpp"

namespace {

using namespace thx;
using namespace thx::visual;

const char* const kHelp = R"(usage: bench_visual [--scene FILE] [--frames N] [--json FILE] [--csv FILE] [--md FILE] [--quick]
                    [--only-search | --only-mesh]

Frame time (median over a camera path, glFinish per frame) against image error (vs the exact CPU
ray-vs-relief reference) for normal mapping, relief mapping (linear 8..64 x binary 4..8 steps and
128 ... 1024 x 8, with and without 8 shadow steps), the max-mipmap search (maxmip, with and without shadows) and
displaced meshes 256^2 / 512^2, and a textured sphere of 101,760 triangles (normal, relief 16+8 with and
without 8 shadow steps), at 640x360 and 1280x720. Also the max-mipmap's build time.

  --scene FILE   default scenes/marble_bricks.yaml (run from the repository's root)
  --frames N     timed frames per row along the path (default 8; 2 warm-up frames before)
  --json FILE    --csv FILE    --md FILE (the table docs/visual.md shows)
  --quick        640x360 only, fewer relief rows (a smoke run)
  --only-search  only the rows the accelerated search is compared with (normal, relief 16..256
                 linear + 8 binary steps and maxmip, each with and without shadows)
  --only-mesh    only the plane's normal-mapping rows and the textured sphere's rows beside them
LP_NUM_THREADS is llvmpipe's thread count (default: one per CPU).
)";

struct Row {
  std::string mode;
  bool sphere = false;  // the textured sphere instead of the plane
  int linear = 0, binary = 0, shadow = 0, mesh_n = 0;
  bool maxmip = false;
  int width = 0, height = 0;
  double median_ms = 0, fps = 0;
  double cpu_ms = 0;  // CPU time of all the process's threads per frame (llvmpipe's included)
  double other_texel = 0, mean_lsb = 0;
  int compared = 0;
  double covered = 0;  // share of the frame's pixels on the surface (the error poses' mean)
};

// The textured sphere (issue 28): 320 x 160 segments, 101,760 triangles, 5 cm radius, centred on the
// plane's origin, the scene's texture on tiles of the plane's width. Its path orbits it at 8 cm
// from the centre: the sphere covers the whole frame (38.7 degrees of angular radius against the
// 16:9 frame's 36.6 degrees to a corner), as the plane does on its path.
constexpr int kSphereSegments = 320, kSphereRings = 160;
constexpr int kSphereTriangles = 2 * kSphereSegments * (kSphereRings - 1);  // one triangle a pole quad
constexpr double kSphereRadius = 0.05;

// User + system time of the whole process (every llvmpipe thread): unlike the wall clock, it does
// not grow when other processes take the cores.
double processCpuMs() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  const auto ms = [](const timeval& t) { return double(t.tv_sec) * 1e3 + double(t.tv_usec) * 1e-3; };
  return ms(u.ru_utime) + ms(u.ru_stime);
}

CameraPlacement pathPose(int k, int n) {
  CameraPlacement c;
  c.elevation_deg = 35;
  c.azimuth_deg = -120 + 60.0 * k / std::max(1, n - 1);
  c.distance_m = 0.08;
  c.target_local = {0.03, -0.015};
  return c;
}

CameraPlacement spherePathPose(int k, int n) {
  CameraPlacement c = pathPose(k, n);
  c.target_local = {0.0, 0.0};
  return c;
}

RenderSettings settingsFor(const Row& r) {
  RenderSettings s;
  s.mode = r.mode == "normal" ? SurfaceMode::Normal : r.mode == "relief" ? SurfaceMode::Relief : SurfaceMode::Mesh;
  s.mesh_n = std::max(1, r.mesh_n);
  s.steps = {std::max(1, r.linear), r.binary, r.shadow,
             r.maxmip ? ReliefSearch::MaxMip : ReliefSearch::Linear};
  s.light = Lighting{40.0, -135.0, 0.0, 0.0};  // the references' lighting
  s.plane_albedo = Eigen::Vector3f::Ones();
  return s;
}

std::string label(const Row& r) {
  if (r.sphere) {
    const std::string steps = r.mode == "relief" ? " " + std::to_string(r.linear) + "+" + std::to_string(r.binary) +
                                                       (r.shadow ? " sh" + std::to_string(r.shadow) : "")
                                                 : "";
    return "sphere " + std::to_string((kSphereTriangles + 500) / 1000) + "k " + r.mode + steps;
  }
  if (r.mode == "relief" && r.maxmip) return std::string("relief maxmip") + (r.shadow ? " sh" : "");
  if (r.mode == "relief")
    return "relief " + std::to_string(r.linear) + "+" + std::to_string(r.binary) +
           (r.shadow ? " sh" + std::to_string(r.shadow) : "");
  if (r.mode == "mesh") return "mesh " + std::to_string(r.mesh_n) + "²";
  return r.mode;
}

// The plane's frames (FrameRenderer, no objects) or the textured sphere's (MeshFrameRenderer):
// both clear, draw and glFinish, so their times compare.
class BenchFrames {
 public:
  BenchFrames(const Row& r, const RenderSettings& settings, const tex::TexturedSurface& plane, const MeshSurface& sphere) {
    if (r.sphere) sphere_ = std::make_unique<MeshFrameRenderer>(sphere, settings, r.width, r.height);
    else plane_ = std::make_unique<FrameRenderer>(plane, settings, r.width, r.height);
  }
  void render(const Camera& camera) {
    if (sphere_) sphere_->render(camera);
    else plane_->render(camera, {});
  }
  const Framebuffer& framebuffer() const { return sphere_ ? sphere_->framebuffer() : plane_->framebuffer(); }

 private:
  std::unique_ptr<FrameRenderer> plane_;
  std::unique_ptr<MeshFrameRenderer> sphere_;
};

int run(int argc, char** argv) {
  std::string scene_path = "scenes/marble_bricks.yaml", json, csv, md;
  const std::string started = thx::bench::isoNow(), load = thx::bench::loadAverage();
  int frames = 8;
  bool quick = false, only_search = false, only_mesh = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError(a + ": missing value");
      return argv[++i];
    };
    if (a == "--scene") scene_path = value();
    else if (a == "--frames") frames = int(cli::parseInteger(a, value(), 1, 1000));
    else if (a == "--json") json = value();
    else if (a == "--csv") csv = value();
    else if (a == "--md") md = value();
    else if (a == "--quick") quick = true;
    else if (a == "--only-search") only_search = true;
    else if (a == "--only-mesh") only_mesh = true;
    else throw UsageError("unknown option '" + a + "'");
  }
  if (only_search && only_mesh) throw UsageError("--only-search and --only-mesh exclude each other");
  const scene::Scene scene = scene::loadScene(scene_path);
  const scene::SceneSurface surface = scene::buildSceneSurface(scene);
  const HeadlessContext context;
  std::fprintf(stderr, "bench_visual: %s, %s\n", scene_path.c_str(), context.description().c_str());

  std::vector<Row> rows;
  const std::vector<std::pair<int, int>> sizes =
      quick ? std::vector<std::pair<int, int>>{{640, 360}} : std::vector<std::pair<int, int>>{{640, 360}, {1280, 720}};
  for (const auto& [w, h] : sizes) {
    rows.push_back({"normal", false, 0, 0, 0, 0, false, w, h});
    if (only_mesh) {
      rows.push_back({"normal", true, 0, 0, 0, 0, false, w, h});
      for (int shadow : {0, 8}) rows.push_back({"relief", true, 16, 8, shadow, 0, false, w, h});
      continue;
    }
    for (int shadow : {0, 8}) {
      // Up to 1024 linear steps (with 8 binary): the accelerated search is compared with the
      // linear one at equal error, and the linear search approaches its error only there.
      std::vector<int> linears{8, 16, 32, 64, 128, 256, 512, 1024};
      if (quick && !only_search) linears = {8, 16};
      for (int linear : linears)
        for (int binary : {4, 8})
          if ((binary == 8 || (linear <= 64 && !only_search)) && (!only_search || linear >= 16) &&
              (linear <= 256 || binary == 8))
            rows.push_back({"relief", false, linear, binary, shadow, 0, false, w, h});
      rows.push_back({"relief", false, 0, 0, shadow, 0, true, w, h});
    }
    if (!only_search) {
      for (int n : {256, 512}) rows.push_back({"mesh", false, 0, 0, 0, n, false, w, h});
      rows.push_back({"normal", true, 0, 0, 0, 0, false, w, h});
      for (int shadow : {0, 8}) rows.push_back({"relief", true, 16, 8, shadow, 0, false, w, h});
    }
  }

  // The max-mipmap is built at load (no cache): its cost, median of 5 builds.
  double build_ms = 0;
  int levels = 0;
  {
    std::vector<double> t;
    for (int k = 0; k < 5; ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      const MaxMipmap m = buildMaxMipmap(surface.surface.map(), surface.surface.sampling());
      t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      levels = m.topLevel() + 1;
    }
    std::sort(t.begin(), t.end());
    build_ms = t[t.size() / 2];
    std::fprintf(stderr, "  max-mipmap of the %dx%d map: %d levels, %.2f ms to build\n",
                 surface.surface.map().width(), surface.surface.map().height(), levels, build_ms);
  }

  // The textured sphere, built once if a row draws it.
  const Eigen::Isometry3d& plane = surface.surface.mapping().plane_to_world;
  std::unique_ptr<mesh::GeneratedMesh> sphere;
  MeshSurface sphere_surface;
  std::unique_ptr<MeshReference> sphere_reference;
  if (std::any_of(rows.begin(), rows.end(), [](const Row& r) { return r.sphere; })) {
    sphere = std::make_unique<mesh::GeneratedMesh>(
        mesh::sphere(kSphereRadius, kSphereSegments, kSphereRings, scene.surface.size_m.x()));
    sphere_surface.mesh = &sphere->mesh;
    sphere_surface.tile_m = sphere->tile_used_m;
    sphere_surface.map = &surface.surface.map();
    sphere_surface.filter = surface.surface.sampling().filter;
    sphere_surface.use_relief = surface.surface.usesRelief();
    sphere_surface.mesh_to_world = plane;
    sphere_reference = std::make_unique<MeshReference>(sphere_surface);
    std::fprintf(stderr, "  textured sphere: %zu triangles, %zu vertices, tile %.4g x %.4g m\n",
                 sphere->mesh.triangles.size(), sphere->mesh.positions.size(), sphere->tile_used_m.x(),
                 sphere->tile_used_m.y());
  }

  // Reference images per (surface, size, shadows), for the two error poses.
  const std::vector<int> error_poses{0, frames / 2};
  std::map<std::tuple<bool, int, int, bool>, std::vector<ReferenceImage>> references;
  for (Row& r : rows) {
    RenderSettings settings = settingsFor(r);
    const auto camera_at = [&](int k) {
      return Camera(r.sphere ? spherePathPose(k, frames) : pathPose(k, frames), plane, r.width, r.height);
    };
    {
      BenchFrames timed(r, settings, surface.surface, sphere_surface);
      std::vector<double> ms;
      double cpu0 = 0;
      for (int k = -2; k < frames; ++k) {
        if (k == 0) cpu0 = processCpuMs();
        const Camera camera = camera_at(std::max(0, k));
        const auto t0 = std::chrono::steady_clock::now();
        timed.render(camera);
        const auto t1 = std::chrono::steady_clock::now();
        if (k >= 0) ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      }
      std::nth_element(ms.begin(), ms.begin() + std::ptrdiff_t(ms.size() / 2), ms.end());
      r.median_ms = ms[ms.size() / 2];
      r.fps = 1000.0 / r.median_ms;
      r.cpu_ms = (processCpuMs() - cpu0) / frames;
    }
    settings.hit_buffer = true;
    BenchFrames checked(r, settings, surface.surface, sphere_surface);
    const bool shadows = r.mode == "relief" && r.shadow > 0;
    auto& refs = references[{r.sphere, r.width, r.height, shadows}];
    double sum_texel = 0, sum_lsb = 0, sum_covered = 0;
    for (std::size_t p = 0; p < error_poses.size(); ++p) {
      const Camera camera = camera_at(error_poses[p]);
      if (refs.size() <= p) {
        // The sphere's light is in its frame, which is turned as the plane's.
        const ReferenceLight light{lightDirectionLocal(settings.light), shadows};
        refs.push_back(r.sphere ? meshReferenceImage(*sphere_reference, camera, r.width, r.height, true, light)
                                : referenceImage(surface.surface, camera, r.width, r.height, true, light));
      }
      checked.render(camera);
      const Rgba8Image colour = checked.framebuffer().readColour();
      const FloatImage hits = checked.framebuffer().readHits();
      const PixelStats s = r.sphere ? compareWithMeshReference(*sphere_reference, refs[p], colour, hits)
                                    : compareWithReference(surface.surface, refs[p], colour, hits);
      sum_texel += s.otherTexelFraction();
      sum_lsb += s.meanError();
      r.compared += s.compared;
      long on = 0;
      for (std::size_t k = 3; k < hits.rgba.size(); k += 4) on += hits.rgba[k] == 1.0f;
      sum_covered += double(on) / (double(r.width) * r.height);
    }
    r.other_texel = sum_texel / double(error_poses.size());
    r.mean_lsb = sum_lsb / double(error_poses.size());
    r.covered = sum_covered / double(error_poses.size());
    std::fprintf(stderr,
                 "  %4dx%-4d %-26s %8.2f ms %6.1f fps  cpu %7.2f ms  other texel %6.2f %%  mean %5.2f LSB  covers "
                 "%5.1f %%\n",
                 r.width, r.height, label(r).c_str(), r.median_ms, r.fps, r.cpu_ms, 100 * r.other_texel, r.mean_lsb,
                 100 * r.covered);
  }

  if (!csv.empty()) {
    std::ofstream f(csv);
    f << "mode,search,linear_steps,binary_steps,shadow_steps,mesh_n,width,height,median_ms,fps,cpu_ms_per_frame,other_texel_fraction,mean_error_lsb,pixels_compared,surface,covered_fraction\n";
    for (const Row& r : rows)
      f << r.mode << ',' << (r.maxmip ? "maxmip" : "linear") << ',' << r.linear << ',' << r.binary << ',' << r.shadow << ',' << r.mesh_n << ',' << r.width << ','
        << r.height << ',' << r.median_ms << ',' << r.fps << ',' << r.cpu_ms << ',' << r.other_texel << ',' << r.mean_lsb << ','
        << r.compared << ',' << (r.sphere ? "sphere" : "plane") << ',' << r.covered << '\n';
    if (!f) throw Error(Error::Kind::Io, csv + ": write failed");
  }
  if (!json.empty()) {
    std::ofstream f(json);
    f << "{\n  \"scene\": \"" << scene_path << "\",\n  \"renderer\": \"" << context.description()
      << "\",\n  \"machine\": \"" << thx::bench::machineSummary() << "\",\n  \"measured\": \"" << started << "\",\n  \"load_average\": \"" << load
      << "\",\n  \"build_type\": \"" << thx::bench::buildType()
      << "\",\n  \"frames_per_row\": " << frames << ",\n  \"maxmip_build_ms\": " << build_ms
      << ",\n";
    // The plane's rows in "rows" (what tools/report reads), the sphere's in "textured_mesh_rows".
    const auto array = [&](const char* name, bool sphere_rows, const char* after) {
      f << "  \"" << name << "\": [\n";
      bool first = true;
      for (const Row& r : rows) {
        if (r.sphere != sphere_rows) continue;
        f << (first ? "" : ",\n");
        first = false;
        f << "    {\"mode\": \"" << r.mode << "\", \"search\": \"" << (r.maxmip ? "maxmip" : "linear")
          << "\", \"linear_steps\": " << r.linear << ", \"binary_steps\": " << r.binary
          << ", \"shadow_steps\": " << r.shadow << ", \"mesh_n\": " << r.mesh_n << ", \"width\": " << r.width
          << ", \"height\": " << r.height << ", \"median_ms\": " << r.median_ms << ", \"fps\": " << r.fps << ", \"cpu_ms_per_frame\": " << r.cpu_ms
          << ", \"other_texel_fraction\": " << r.other_texel << ", \"mean_error_lsb\": " << r.mean_lsb
          << ", \"covered_fraction\": " << r.covered;
        if (sphere_rows) f << ", \"surface\": \"sphere\", \"triangles\": " << sphere->mesh.triangles.size();
        f << "}";
      }
      f << (first ? "" : "\n") << "  ]" << after << "\n";
    };
    array("rows", false, ",");
    array("textured_mesh_rows", true, "");
    f << "}\n";
    if (!f) throw Error(Error::Kind::Io, json + ": write failed");
  }
  if (!md.empty()) {
    std::ofstream f(md);
    double normal_ms[2] = {0, 0};
    for (const Row& r : rows)
      if (r.mode == "normal" && !r.sphere) normal_ms[r.width > 640] = r.median_ms;
    f << "| rows | size | median ms | fps | CPU ms / frame | × normal | other texel | mean error (LSB) |\n"
         "|---|---|---|---|---|---|---|---|\n";
    for (const Row& r : rows) {
      char line[256];
      std::snprintf(line, sizeof line, "| %s | %dx%d | %.1f | %.1f | %.1f | %.1f | %.2f %% | %.2f |\n",
                    label(r).c_str(), r.width, r.height, r.median_ms, r.fps, r.cpu_ms, r.median_ms / normal_ms[r.width > 640],
                    100 * r.other_texel, r.mean_lsb);
      f << line;
    }
    if (!f) throw Error(Error::Kind::Io, md + ": write failed");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return thx::bench::benchMain(argc, argv, kHelp, "bench_visual", run); }
