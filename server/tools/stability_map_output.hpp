#pragma once
// stability-map's machine-readable output: JSON (everything: setup, thresholds, axes, the command
// line, a summary and every cell with every metric) and CSV (one row per cell). Files are written
// whole to a temporary name and renamed, so a reader never sees half a file.
#include <string>
#include <vector>

#include "server/tools/stability_map_cli.hpp"

namespace thx::srv::stab {

// Throws std::runtime_error naming the file if it cannot be written.
void writeJson(const std::string& path, const CliOptions& options, const std::vector<CellResult>& results);
void writeCsv(const std::string& path, const std::vector<CellResult>& results);

// The command line as one shell-quoted string.
std::string commandLine(const std::vector<std::string>& argv);

}  // namespace thx::srv::stab
