// modal-analyze: one object's audible modes, offline (see kModalHelp in modal_options.cpp).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "base/error.hpp"
#include "clients/audio/audible_modes.hpp"
#include "clients/audio/modal_options.hpp"

namespace {

using namespace thx::audio;

double t60(double decay_per_s) { return decay_per_s > 0 ? std::log(1000.0) / decay_per_s : INFINITY; }

void writeCsv(const std::string& path, const AudibleModes& modes) {
  std::ofstream out(path);
  if (!out) throw thx::Error(thx::Error::Kind::Io, path + ": cannot be written");
  out << "mode,frequency_hz,decay_per_s,damping_ratio,t60_s,members\n";
  char line[256];
  for (std::size_t k = 0; k < modes.size(); ++k) {
    std::snprintf(line, sizeof line, "%zu,%.6f,%.6g,%.6g,%.6g,%d\n", k, modes.frequency_hz[k], modes.decay_per_s[k],
                  modes.damping_ratio[k], t60(modes.decay_per_s[k]), modes.members[k]);
    out << line;
  }
  if (!out) throw thx::Error(thx::Error::Kind::Io, path + ": write failed");
}

int run(const ModalOptions& o) {
  const TetMesh mesh = buildMesh(o);
  AnalysisOptions ao;
  ao.cache_dir = o.cache_dir;
  if (!o.quiet) ao.progress = [](const std::string& line) { std::fprintf(stderr, "modal-analyze: %s\n", line.c_str()); };
  const ModalSolution s = analyse(mesh, o.material, o.settings, ao);
  const AudibleModes modes = audibleModes(s, o.material, o.audible);
  std::printf("# %s: %s, %s, %zu elements, %d DOFs (%d free), %d rigid modes dropped, %ld elastic modes "
              "computed, %zu audible (%d out of band, %d overdamped, %d merged away, %d truncated); %s %.3f s\n",
              mesh.name.c_str(), o.material.name.c_str(), mesh.order == ElementOrder::Linear ? "Tet4" : "Tet10",
              mesh.tets.size(), s.mesh_dofs, s.free_dofs, s.rigid_modes, long(s.omega_rad_per_s.size()), modes.size(),
              modes.dropped_out_of_band, modes.dropped_overdamped, modes.merged_away, modes.truncated,
              s.from_cache ? "read from cache in" : "solved in", s.total_s);
  std::printf("%5s %14s %12s %12s %10s %7s\n", "mode", "frequency_hz", "decay_per_s", "damping", "t60_s", "members");
  for (std::size_t k = 0; k < modes.size(); ++k)
    std::printf("%5zu %14.3f %12.4g %12.4g %10.4g %7d\n", k, modes.frequency_hz[k], modes.decay_per_s[k],
                modes.damping_ratio[k], t60(modes.decay_per_s[k]), modes.members[k]);
  if (!o.csv.empty()) writeCsv(o.csv, modes);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const ModalOptions o = parseModalOptions(std::vector<std::string>(argv + 1, argv + argc));
    if (o.help) {
      std::fputs(kModalHelp, stdout);
      return 0;
    }
    return run(o);
  } catch (const thx::Error& e) {
    std::fprintf(stderr, "modal-analyze: %s\n", e.what());
    if (e.kind() == thx::Error::Kind::Usage) std::fprintf(stderr, "(modal-analyze --help lists the options)\n");
    return thx::exitStatus(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "modal-analyze: %s\n", e.what());
    return 1;
  }
}
