#include "benchmarks/table1_modal.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "benchmarks/child_reply.hpp"
#include "clients/audio/analysis/modal_analysis.hpp"
#include "clients/audio/analysis/scene_bodies.hpp"
#include "clients/audio/analysis/spring_mass.hpp"
#include "scenes/scene_loader.hpp"

namespace thx::bench::table1 {

int runModalChild(const std::string& scene_path, const std::string& kind, int size, int layers) {
  try {
    if (kind == "idle") {
      std::printf("0 0 0 0 0\n");
      return 0;
    }
    const scene::Scene sc = scene::loadScene(scene_path);
    const scene::Surface& s = sc.surface;
    const bool held = s.held == scene::SlabSupport::ClampedEdges;
    audio::ModalSettings settings;
    settings.elastic_modes = kModes;
    settings.shift_hz = 20.0;
    const auto t0 = std::chrono::steady_clock::now();
    audio::ModalSolution sol;
    if (kind == "spring") {
      sol = audio::springMassModes(
          audio::surfaceLattice("surface", s.size_m.x(), s.size_m.y(), s.thickness_m, size, s.material, held), settings);
    } else if (kind == "fem-slab" || kind == "fem-mesh") {
      audio::SceneMeshOptions o;
      o.slab_cells = size;
      o.slab_layers = kind == "fem-slab" ? layers : kMeshLayers;
      o.pen = false;
      o.order = kind == "fem-slab" ? audio::ElementOrder::Quadratic : audio::ElementOrder::Linear;
      const audio::SceneBody body = audio::slabBody(sc, o);
      sol = audio::analyse(body.mesh, body.material, settings);
    } else {
      std::printf("error unknown modal kind '%s' (expected idle, spring, fem-slab, fem-mesh)\n", kind.c_str());
      return 2;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const long long matrix = static_cast<long long>(sol.shapes.size()) * static_cast<long long>(sizeof(double));
    std::printf("%d %d %ld %lld %.4f\n", sol.free_dofs, sol.mesh_dofs, long(sol.shapes.cols()), matrix, seconds);
    return 0;
  } catch (const std::exception& e) {
    std::printf("error %s\n", e.what());
    return 1;
  }
}

ModalProbe probeModal(const std::string& self, const std::string& scene_path, const std::string& kind, int size,
                      int layers) {
  ModalProbe p;
  p.kind = kind;
  p.size = size;
  int fd[2];
  if (pipe(fd) != 0) {
    p.error = "pipe failed";
    return p;
  }
  const std::string size_text = std::to_string(size), layers_text = std::to_string(layers);
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(fd[1], STDOUT_FILENO);
    close(fd[0]);
    close(fd[1]);
    execl(self.c_str(), self.c_str(), "--modal-child", kind.c_str(), size_text.c_str(), layers_text.c_str(), "--scene",
          scene_path.c_str(), static_cast<char*>(nullptr));
    std::printf("error cannot run %s\n", self.c_str());
    std::fflush(stdout);
    _exit(127);
  }
  close(fd[1]);
  const ChildReply reply = readChildReply(pid, fd[0]);
  if (!reply.reaped) {
    p.error = "fork or wait failed";
    return p;
  }
  p.peak_rss_kb = reply.peak_rss_kb;
  const std::string& text = reply.text;
  if (text.rfind("error ", 0) == 0 || text.empty()) {
    p.error = text.empty() ? "the child wrote nothing (status " + std::to_string(reply.status) + ")" : text.substr(6);
    while (!p.error.empty() && p.error.back() == '\n') p.error.pop_back();
    return p;
  }
  std::istringstream in(text);
  in >> p.dofs >> p.mesh_dofs >> p.modes >> p.matrix_bytes >> p.seconds;
  p.ok = bool(in);
  if (!p.ok) p.error = "unreadable reply '" + text + "'";
  return p;
}

long long femMeshNodeDofs(int cells) {
  const long long side = cells + 1;
  return 3 * (kMeshLayers + 1) * side * side;
}

long long femMeshDofs(bool held, int cells) {
  if (!held) return femMeshNodeDofs(cells);
  const long long inner = cells - 1;  // clampedEdges holds every node on the four side faces
  return 3 * (kMeshLayers + 1) * inner * inner;
}

double PowerFit::at(double x) const { return a * std::pow(x, b); }

PowerFit fitPower(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = double(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  PowerFit f;
  f.b = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  f.a = std::exp((sy - f.b * sx) / n);
  return f;
}

}  // namespace thx::bench::table1
