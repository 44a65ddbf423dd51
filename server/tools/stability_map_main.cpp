// stability-map: sweeps the servo pipeline over V-valleys on the simulated PHANToM and writes the
// stability map (docs/stability.md). `stability-map --help` for the options.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "base/program_main.hpp"
#include "server/tools/stability_map_cli.hpp"
#include "server/tools/stability_map_heatmap.hpp"
#include "server/tools/stability_map_output.hpp"

namespace {

using namespace thx::srv::stab;
using Clock = std::chrono::steady_clock;  // progress display only; never enters the results

// Progress on stderr: rewritten in place on a terminal, every 10 % otherwise.
class Progress {
 public:
  explicit Progress(bool quiet) : quiet_(quiet), tty_(isatty(STDERR_FILENO) != 0), start_(Clock::now()) {}
  void operator()(std::size_t done, std::size_t total) {
    if (quiet_) return;
    const double elapsed_s = std::chrono::duration<double>(Clock::now() - start_).count();
    const std::size_t decile = done * 10 / total;
    const bool last = done == total;
    if (!tty_ && !last && decile == last_decile_) return;
    if (tty_ && !last && elapsed_s - last_print_s_ < 0.2) return;
    last_decile_ = decile;
    last_print_s_ = elapsed_s;
    const double eta_s = done > 0 ? elapsed_s * double(total - done) / double(done) : 0.0;
    std::fprintf(stderr, "%sstability-map: %zu / %zu cells (%.0f%%), %.1f s elapsed, ETA %.1f s%s", tty_ ? "\r" : "",
                 done, total, 100.0 * double(done) / double(total), elapsed_s, eta_s, tty_ && !last ? "" : "\n");
    std::fflush(stderr);
  }

 private:
  bool quiet_, tty_;
  Clock::time_point start_;
  std::size_t last_decile_ = 0;
  double last_print_s_ = -1.0;
};

// --trace: every tick of the one selected cell, truth beside the servo's record.
int runTrace(const CliOptions& o, const CellParams& cell) {
  std::ofstream out(o.trace_path);
  if (!out) throw thx::Error(thx::Error::Kind::Io, o.trace_path + ": cannot open for writing");
  out << "t_s,x_true_m,y_true_m,z_true_m,vx_true_m_per_s,vz_true_m_per_s,x_read_m,z_read_m,fx_out_n,fy_out_n,"
         "fz_out_n,fx_render_n,fz_render_n,depth_m,num_planes,recovering,pc_damping_ns_per_m,pc_energy_j,"
         "safety_flags,motor_work_j,kinetic_energy_j,proxy_x_m,proxy_z_m\n";
  const ValleyMap valley = buildValleyMap(cell.angle_deg, cell.mitigations.smoothing, o.setup.geometry);
  const CellResult r = simulateCell(cell, valley, o.setup, [&](const thx::srv::TickRecord& t, const thx::dev::SimTruth& s) {
    char line[512];
    std::snprintf(line, sizeof line,
                  "%.4f,%.9g,%.9g,%.9g,%.6g,%.6g,%.9g,%.9g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%d,%.6g,%.6g,%u,%.6g,%.6g,%.9g,%.9g\n",
                  s.t_s, s.p_world_m.x(), s.p_world_m.y(), s.p_world_m.z(), s.v_world_m_per_s.x(),
                  s.v_world_m_per_s.z(), t.p_world[0], t.p_world[2], t.f_out[0], t.f_out[1], t.f_out[2], t.f_render[0],
                  t.f_render[2], t.depth_m, int(t.num_planes), int(t.recovering), t.pc_damping_ns_per_m, t.pc_energy_j,
                  t.safety_flags, s.motor_work_j, s.kinetic_energy_j, t.proxy_world[0], t.proxy_world[2]);
    out << line;
  });
  std::fprintf(stderr, "stability-map: wrote %s: %s (%s)\n", o.trace_path.c_str(), verdictName(r.metrics.verdict),
               r.metrics.reason.c_str());
  return out ? 0 : 1;
}

int run(const CliOptions& o) {
  const std::vector<CellParams> cells = enumerateCells(o.axes);
  if (cells.empty()) throw UsageError("the axes select no cell");
  if (!o.trace_path.empty()) {
    if (cells.size() != 1)
      throw UsageError("--trace needs the axes to select exactly one cell, they select " +
                       std::to_string(cells.size()));
    return runTrace(o, cells.front());
  }
  std::filesystem::create_directories(o.out_dir);
  const std::string base = (std::filesystem::path(o.out_dir) / o.basename).string();

  Progress progress(o.quiet);
  const std::vector<CellResult> results =
      runSweep(cells, o.setup, o.threads, [&](std::size_t done, std::size_t total) { progress(done, total); });

  writeJson(base + ".json", o, results);
  writeCsv(base + ".csv", results);
  if (o.picture) {
    // A capsule first (the picture is as wide as the map): which pen, then the rest.
    char pen[96] = "";
    if (o.setup.tool != PenTool::Point)
      std::snprintf(pen, sizeof pen, "pen: %s, %g x %g mm; ", penToolName(o.setup.tool), o.setup.capsule_length_m * 1e3,
                    o.setup.capsule_radius_m * 1e3);
    char subtitle[352];
    std::snprintf(subtitle, sizeof subtitle,
                  "%shand '%s' (%.3g kg, %.3g N/m, %.3g N s/m); B %.3g N s/m; recovery %d ticks; smoothing sigma %.3g "
                  "texels; window: last %.3g of %.3g s",
                  pen, o.setup.hand.name.c_str(), o.setup.hand.mass_kg, o.setup.hand.stiffness_n_per_m,
                  o.setup.hand.damping_ns_per_m, o.setup.virtual_damping_ns_per_m, o.setup.recovery_ticks,
                  o.setup.geometry.smoothing_sigma_texels, o.setup.window_s, o.setup.duration_s);
    writeHeatmap(base + ".png", o.axes, results, subtitle);
  }

  int counts[kVerdicts] = {};
  for (const CellResult& r : results) ++counts[int(r.metrics.verdict)];
  if (!o.quiet)
    std::fprintf(stderr,
                 "stability-map: %zu cells: %d stable, %d limit-cycle, %d unstable, %d cannot-hold; wrote "
                 "%s.{json,csv%s}\n",
                 results.size(), counts[0], counts[1], counts[2], counts[3], base.c_str(), o.picture ? ",png" : "");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return thx::runProgram("stability-map", kHelpText, argc, argv, [&](const std::vector<std::string>&) {
    CliOptions options;
    if (!parseCommandLine(argc, argv, options)) return 0;  // --help (runProgram answers it first)
    return run(options);
  });
}
