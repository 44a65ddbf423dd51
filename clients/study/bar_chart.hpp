#pragma once
// Grouped bar charts with error bars, for study-analyze's plots (ID rate per cue condition,
// ratings per representation). tools/report/plot.hpp (thx_plot) draws scatter and line plots
// for the benchmarks and the report; this one draws bars. OpenCV imgproc into a
// cv::Mat, written as PNG through thx::tex::writePng.
#include <cstdint>
#include <string>
#include <vector>

namespace thx::study {

struct BarSeries {
  std::string label;  // legend entry
  std::uint8_t r = 0, g = 0, b = 0;
  std::vector<double> values;  // one per category; NaN draws no bar and "n/a"
  std::vector<double> errors;  // half-length of each error bar (empty: none; NaN: none for that bar)
};

struct BarPanel {
  std::string title, y_label;
  std::vector<std::string> categories;
  double y_max = 1;  // the axis runs from 0 to y_max
  std::vector<BarSeries> series;
};

// Panels side by side. Throws thx::tex::TextureError when the file cannot be written,
// std::logic_error (a caller's bug) when a series has another count than the categories or
// y_max is not > 0.
void writeBarChartPng(const std::string& path, const std::vector<BarPanel>& panels, const std::string& caption,
                      int panel_width = 560, int panel_height = 440);

}  // namespace thx::study
