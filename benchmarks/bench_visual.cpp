// Visual client (issue 15): frame time against image error on this machine's renderer (llvmpipe
// without a GPU). Rows: normal mapping; relief with linear 8..64 and binary 4..8 steps, with and
// without self-shadowing; the accelerated search over the relief's max-mipmap (--search maxmip)
// with and without shadows; the displaced meshes at 256^2 and 512^2; at 640x360 and 1280x720.
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
#include "scenes/scene_loader.hpp"
#include "scenes/scene_surface.hpp"

namespace {

using namespace thx;
using namespace thx::visual;

const char* const kHelp = R"(usage: bench_visual [--scene FILE] [--frames N] [--json FILE] [--csv FILE] [--md FILE] [--quick]

Frame time (median over a camera path, glFinish per frame) against image error (vs the exact CPU
ray-vs-relief reference) for normal mapping, relief mapping (linear 8..64 x binary 4..8 steps and
128 ... 1024 x 8, with and without 8 shadow steps), the max-mipmap search (maxmip, with and without shadows) and
displaced meshes 256^2 / 512^2, at 640x360 and 1280x720. Also the max-mipmap's build time.

  --scene FILE   default scenes/marble_bricks.yaml (run from the repository's root)
  --frames N     timed frames per row along the path (default 8; 2 warm-up frames before)
  --json FILE    --csv FILE    --md FILE (the table docs/visual.md shows)
  --quick        640x360 only, fewer relief rows (a smoke run)
  --only-search  only the rows the accelerated search is compared with (normal, relief 16..256
                 linear + 8 binary steps and maxmip, each with and without shadows)
LP_NUM_THREADS is llvmpipe's thread count (default: one per CPU).
)";

struct Row {
  std::string mode;
  int linear = 0, binary = 0, shadow = 0, mesh_n = 0;
  bool maxmip = false;
  int width = 0, height = 0;
  double median_ms = 0, fps = 0;
  double cpu_ms = 0;  // CPU time of all the process's threads per frame (llvmpipe's included)
  double other_texel = 0, mean_lsb = 0;
  int compared = 0;
};

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
  if (r.mode == "relief" && r.maxmip) return std::string("relief maxmip") + (r.shadow ? " sh" : "");
  if (r.mode == "relief")
    return "relief " + std::to_string(r.linear) + "+" + std::to_string(r.binary) +
           (r.shadow ? " sh" + std::to_string(r.shadow) : "");
  if (r.mode == "mesh") return "mesh " + std::to_string(r.mesh_n) + "²";
  return r.mode;
}

int run(int argc, char** argv) {
  std::string scene_path = "scenes/marble_bricks.yaml", json, csv, md;
  const std::string started = thx::bench::isoNow(), load = thx::bench::loadAverage();
  int frames = 8;
  bool quick = false, only_search = false;
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
    else throw UsageError("unknown option '" + a + "'");
  }
  const scene::Scene scene = scene::loadScene(scene_path);
  const scene::SceneSurface surface = scene::buildSceneSurface(scene);
  const HeadlessContext context;
  std::fprintf(stderr, "bench_visual: %s, %s\n", scene_path.c_str(), context.description().c_str());

  std::vector<Row> rows;
  const std::vector<std::pair<int, int>> sizes =
      quick ? std::vector<std::pair<int, int>>{{640, 360}} : std::vector<std::pair<int, int>>{{640, 360}, {1280, 720}};
  for (const auto& [w, h] : sizes) {
    rows.push_back({"normal", 0, 0, 0, 0, false, w, h});
    for (int shadow : {0, 8}) {
      // Up to 1024 linear steps (with 8 binary): the accelerated search is compared with the
      // linear one at equal error, and the linear search approaches its error only there.
      std::vector<int> linears{8, 16, 32, 64, 128, 256, 512, 1024};
      if (quick && !only_search) linears = {8, 16};
      for (int linear : linears)
        for (int binary : {4, 8})
          if ((binary == 8 || (linear <= 64 && !only_search)) && (!only_search || linear >= 16) &&
              (linear <= 256 || binary == 8))
            rows.push_back({"relief", linear, binary, shadow, 0, false, w, h});
      rows.push_back({"relief", 0, 0, shadow, 0, true, w, h});
    }
    if (!only_search)
      for (int n : {256, 512}) rows.push_back({"mesh", 0, 0, 0, n, false, w, h});
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

  // Reference images per (size, shadows), for the two error poses.
  const std::vector<int> error_poses{0, frames / 2};
  std::map<std::tuple<int, int, bool>, std::vector<ReferenceImage>> references;
  const Eigen::Isometry3d& plane = surface.surface.mapping().plane_to_world;
  for (Row& r : rows) {
    RenderSettings settings = settingsFor(r);
    {
      FrameRenderer timed(surface.surface, settings, r.width, r.height);
      std::vector<double> ms;
      double cpu0 = 0;
      for (int k = -2; k < frames; ++k) {
        if (k == 0) cpu0 = processCpuMs();
        const Camera camera(pathPose(std::max(0, k), frames), plane, r.width, r.height);
        const auto t0 = std::chrono::steady_clock::now();
        timed.render(camera, {});
        const auto t1 = std::chrono::steady_clock::now();
        if (k >= 0) ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      }
      std::nth_element(ms.begin(), ms.begin() + std::ptrdiff_t(ms.size() / 2), ms.end());
      r.median_ms = ms[ms.size() / 2];
      r.fps = 1000.0 / r.median_ms;
      r.cpu_ms = (processCpuMs() - cpu0) / frames;
    }
    settings.hit_buffer = true;
    FrameRenderer checked(surface.surface, settings, r.width, r.height);
    const bool shadows = r.mode == "relief" && r.shadow > 0;
    auto& refs = references[{r.width, r.height, shadows}];
    double sum_texel = 0, sum_lsb = 0;
    for (std::size_t p = 0; p < error_poses.size(); ++p) {
      const Camera camera(pathPose(error_poses[p], frames), plane, r.width, r.height);
      if (refs.size() <= p) {
        const ReferenceLight light{lightDirectionLocal(settings.light), shadows};
        refs.push_back(referenceImage(surface.surface, camera, r.width, r.height, true, light));
      }
      checked.render(camera, {});
      const PixelStats s = compareWithReference(surface.surface, refs[p], checked.framebuffer().readColour(),
                                                checked.framebuffer().readHits());
      sum_texel += s.otherTexelFraction();
      sum_lsb += s.meanError();
      r.compared += s.compared;
    }
    r.other_texel = sum_texel / double(error_poses.size());
    r.mean_lsb = sum_lsb / double(error_poses.size());
    std::fprintf(stderr, "  %4dx%-4d %-18s %8.2f ms %6.1f fps  cpu %7.2f ms  other texel %6.2f %%  mean %5.2f LSB\n", r.width,
                 r.height, label(r).c_str(), r.median_ms, r.fps, r.cpu_ms, 100 * r.other_texel, r.mean_lsb);
  }

  if (!csv.empty()) {
    std::ofstream f(csv);
    f << "mode,search,linear_steps,binary_steps,shadow_steps,mesh_n,width,height,median_ms,fps,cpu_ms_per_frame,other_texel_fraction,mean_error_lsb,pixels_compared\n";
    for (const Row& r : rows)
      f << r.mode << ',' << (r.maxmip ? "maxmip" : "linear") << ',' << r.linear << ',' << r.binary << ',' << r.shadow << ',' << r.mesh_n << ',' << r.width << ','
        << r.height << ',' << r.median_ms << ',' << r.fps << ',' << r.cpu_ms << ',' << r.other_texel << ',' << r.mean_lsb << ','
        << r.compared << '\n';
    if (!f) throw Error(Error::Kind::Io, csv + ": write failed");
  }
  if (!json.empty()) {
    std::ofstream f(json);
    f << "{\n  \"scene\": \"" << scene_path << "\",\n  \"renderer\": \"" << context.description()
      << "\",\n  \"machine\": \"" << thx::bench::machineSummary() << "\",\n  \"measured\": \"" << started << "\",\n  \"load_average\": \"" << load
      << "\",\n  \"build_type\": \"" << thx::bench::buildType()
      << "\",\n  \"frames_per_row\": " << frames << ",\n  \"maxmip_build_ms\": " << build_ms
      << ",\n  \"rows\": [\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const Row& r = rows[i];
      f << "    {\"mode\": \"" << r.mode << "\", \"search\": \"" << (r.maxmip ? "maxmip" : "linear")
        << "\", \"linear_steps\": " << r.linear << ", \"binary_steps\": " << r.binary
        << ", \"shadow_steps\": " << r.shadow << ", \"mesh_n\": " << r.mesh_n << ", \"width\": " << r.width
        << ", \"height\": " << r.height << ", \"median_ms\": " << r.median_ms << ", \"fps\": " << r.fps << ", \"cpu_ms_per_frame\": " << r.cpu_ms
        << ", \"other_texel_fraction\": " << r.other_texel << ", \"mean_error_lsb\": " << r.mean_lsb << "}"
        << (i + 1 < rows.size() ? "," : "") << "\n";
    }
    f << "  ]\n}\n";
    if (!f) throw Error(Error::Kind::Io, json + ": write failed");
  }
  if (!md.empty()) {
    std::ofstream f(md);
    double normal_ms[2] = {0, 0};
    for (const Row& r : rows)
      if (r.mode == "normal") normal_ms[r.width > 640] = r.median_ms;
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
