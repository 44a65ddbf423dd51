#pragma once
// A small scatter/line plot drawn with OpenCV imgproc into a cv::Mat and written as PNG through
// thx::tex::writePng (no OpenCV imgcodecs). Panels side by side, log or linear axes.
#include <cstdint>
#include <string>
#include <vector>

namespace thx::bench {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

enum class Marker { Circle, Square, Triangle };

struct PlotSeries {
  std::string label;  // legend entry
  Rgb color;
  Marker marker = Marker::Circle;
  bool filled = true;
  bool connect = true;  // draw a line through the points in order
  std::vector<double> x, y;
  std::vector<std::string> point_labels;  // optional, drawn beside each point
};

struct PlotPanel {
  std::string title, x_label, y_label;
  bool log_x = true, log_y = true;
  double x_min = 1, x_max = 10, y_min = 1, y_max = 10;
  std::vector<PlotSeries> series;
};

// Throws on I/O errors (thx::tex::TextureError from writePng).
void writePlotPng(const std::string& path, const std::vector<PlotPanel>& panels, const std::string& caption,
                  int panel_width = 640, int panel_height = 520);

}  // namespace thx::bench
