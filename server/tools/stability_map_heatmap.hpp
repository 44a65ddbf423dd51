#pragma once
// The stability map as a picture: one panel per (mitigation combination, representation); in each
// panel, opening angle across and stiffness up, every square coloured by the worst verdict over
// the push forces and lettered with the verdict at each force (S, L, U), lowest force first.
// Drawn with OpenCV core/imgproc into a cv::Mat and written with thx::tex::writePng (no imgcodecs).
#include <string>
#include <vector>

#include "server/tools/stability_map_sweep.hpp"

namespace thx::srv::stab {

// Throws tex::TextureError (from writePng) if the file cannot be written.
void writeHeatmap(const std::string& path, const SweepAxes& axes, const std::vector<CellResult>& results,
                  const std::string& subtitle);

}  // namespace thx::srv::stab
