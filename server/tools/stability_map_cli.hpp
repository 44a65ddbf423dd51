#pragma once
// stability-map's command line: the axes to sweep, the setup, where to write. `--help` text here.
#include <string>
#include <vector>

#include "base/error.hpp"
#include "server/tools/stability_map_sweep.hpp"

namespace thx::srv::stab {

struct CliOptions {
  SweepAxes axes;
  CellSetup setup;
  int threads = 2;
  std::string out_dir = "docs/results";
  std::string basename = "stability_map";  // OUT_DIR/BASENAME.{json,csv,png}
  std::string trace_path;                  // per-tick CSV of the (single) cell
  bool quick = false;
  bool picture = true;
  bool quiet = false;
  std::vector<std::string> argv;  // verbatim, for the JSON
};

extern const char* const kHelpText;

using thx::UsageError;

// Throws thx::UsageError with a message naming the option and what it expects. Returns false
// after printing --help (the caller exits 0).
bool parseCommandLine(int argc, char** argv, CliOptions& options);

// "none", "crease", "passivity+smoothing", "all", ... (any order of the parts).
Mitigations parseMitigations(const std::string& text);

}  // namespace thx::srv::stab
