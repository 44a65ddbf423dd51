#include "tools/report/plot.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "textures/png_io.hpp"

namespace thx::bench {

namespace {

cv::Scalar bgr(Rgb c) { return cv::Scalar(c.b, c.g, c.r); }

const cv::Scalar kBlack(0, 0, 0), kGrid(225, 225, 225), kText(40, 40, 40);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

struct Axis {
  double lo, hi;
  bool log;
  int p0, p1;  // pixel positions of lo and hi
  double t(double v) const {
    const double a = log ? std::log10(std::max(v, 1e-300)) : v;
    const double l = log ? std::log10(lo) : lo, h = log ? std::log10(hi) : hi;
    return p0 + (a - l) / (h - l) * (p1 - p0);
  }
  std::vector<double> ticks() const {
    std::vector<double> t;
    if (log) {
      // Narrow ranges (about a decade) get more mantissas so the axis stays readable.
      const bool narrow = std::log10(hi / lo) <= 1.3;
      const std::vector<double> mantissas = narrow ? std::vector<double>{1, 1.5, 2, 3, 4, 5, 7}
                                                   : std::vector<double>{1, 2, 5};
      for (int e = int(std::floor(std::log10(lo))); e <= int(std::ceil(std::log10(hi))); ++e) {
        for (double m : mantissas) {
          const double v = m * std::pow(10.0, e);
          if (v >= lo * 0.999 && v <= hi * 1.001) t.push_back(v);
        }
      }
    } else {
      const double span = hi - lo, step0 = std::pow(10.0, std::floor(std::log10(span / 5)));
      double step = step0;
      for (double m : {1.0, 2.0, 5.0, 10.0}) {
        if (span / (m * step0) <= 8) {
          step = m * step0;
          break;
        }
      }
      for (double v = std::ceil(lo / step) * step; v <= hi + 1e-12 * span; v += step) t.push_back(v);
    }
    return t;
  }
};

std::string tickText(double v) {
  char buf[32];
  if (v >= 1e4 || (v < 1e-2 && v > 0)) {
    std::snprintf(buf, sizeof buf, "%.0e", v);
  } else {
    std::snprintf(buf, sizeof buf, "%g", v);
  }
  return buf;
}

void drawMarker(cv::Mat& img, cv::Point c, const PlotSeries& s) {
  const cv::Scalar col = bgr(s.color);
  const int th = s.filled ? cv::FILLED : 2;
  switch (s.marker) {
    case Marker::Circle:
      cv::circle(img, c, 5, col, th, cv::LINE_AA);
      break;
    case Marker::Square:
      cv::rectangle(img, c - cv::Point(5, 5), c + cv::Point(5, 5), col, th, cv::LINE_AA);
      break;
    case Marker::Triangle: {
      std::vector<cv::Point> pts{c + cv::Point(0, -6), c + cv::Point(6, 5), c + cv::Point(-6, 5)};
      if (s.filled) {
        cv::fillConvexPoly(img, pts, col, cv::LINE_AA);
      } else {
        cv::polylines(img, pts, true, col, 2, cv::LINE_AA);
      }
      break;
    }
  }
}

void drawPanel(cv::Mat& img, const PlotPanel& p, cv::Rect area) {
  const int left = area.x + 70, right = area.x + area.width - 15, top = area.y + 40, bottom = area.y + area.height - 60;
  const Axis ax{p.x_min, p.x_max, p.log_x, left, right}, ay{p.y_min, p.y_max, p.log_y, bottom, top};
  for (double v : ax.ticks()) {
    const int x = int(std::lround(ax.t(v)));
    cv::line(img, {x, top}, {x, bottom}, kGrid, 1);
    const std::string s = tickText(v);
    int base = 0;
    const cv::Size ts = cv::getTextSize(s, kFont, 0.4, 1, &base);
    cv::putText(img, s, {x - ts.width / 2, bottom + 16}, kFont, 0.4, kText, 1, cv::LINE_AA);
  }
  for (double v : ay.ticks()) {
    const int y = int(std::lround(ay.t(v)));
    cv::line(img, {left, y}, {right, y}, kGrid, 1);
    const std::string s = tickText(v);
    int base = 0;
    const cv::Size ts = cv::getTextSize(s, kFont, 0.4, 1, &base);
    cv::putText(img, s, {left - ts.width - 6, y + 4}, kFont, 0.4, kText, 1, cv::LINE_AA);
  }
  cv::rectangle(img, {left, top}, {right, bottom}, kBlack, 1);
  cv::putText(img, p.title, {left, top - 14}, kFont, 0.55, kBlack, 1, cv::LINE_AA);
  {
    int base = 0;
    const cv::Size ts = cv::getTextSize(p.x_label, kFont, 0.45, 1, &base);
    cv::putText(img, p.x_label, {(left + right - ts.width) / 2, bottom + 40}, kFont, 0.45, kBlack, 1, cv::LINE_AA);
  }
  {
    // Vertical y label: draw into a strip and rotate.
    int base = 0;
    const cv::Size ts = cv::getTextSize(p.y_label, kFont, 0.45, 1, &base);
    cv::Mat strip(ts.height + 8, ts.width + 8, img.type(), cv::Scalar(255, 255, 255));
    cv::putText(strip, p.y_label, {4, ts.height + 2}, kFont, 0.45, kBlack, 1, cv::LINE_AA);
    cv::Mat rotated;
    cv::rotate(strip, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
    const int y0 = std::max(0, (top + bottom - rotated.rows) / 2);
    const int x0 = area.x + 4;
    if (y0 + rotated.rows <= img.rows && x0 + rotated.cols <= img.cols) {
      rotated.copyTo(img(cv::Rect(x0, y0, rotated.cols, rotated.rows)));
    }
  }
  auto inside = [&](double x, double y) { return x >= p.x_min && x <= p.x_max && y >= p.y_min && y <= p.y_max; };
  auto point = [&](double x, double y) { return cv::Point(int(std::lround(ax.t(x))), int(std::lround(ay.t(y)))); };
  for (const PlotSeries& s : p.series) {
    if (s.connect) {
      for (std::size_t i = 1; i < s.x.size(); ++i) {
        if (!inside(s.x[i - 1], s.y[i - 1]) || !inside(s.x[i], s.y[i])) continue;
        cv::line(img, point(s.x[i - 1], s.y[i - 1]), point(s.x[i], s.y[i]), bgr(s.color), 1, cv::LINE_AA);
      }
    }
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!inside(s.x[i], s.y[i])) continue;
      const cv::Point c = point(s.x[i], s.y[i]);
      drawMarker(img, c, s);
      if (i < s.point_labels.size() && !s.point_labels[i].empty()) {
        cv::putText(img, s.point_labels[i], c + cv::Point(7, -5), kFont, 0.33, bgr(s.color), 1, cv::LINE_AA);
      }
    }
  }
}

}  // namespace

void writePlotPng(const std::string& path, const std::vector<PlotPanel>& panels, const std::string& caption,
                  int panel_width, int panel_height) {
  // Legend: the union of series labels (first panel's styles), in a band under the panels.
  std::vector<const PlotSeries*> legend;
  for (const PlotPanel& p : panels) {
    for (const PlotSeries& s : p.series) {
      const bool seen = std::any_of(legend.begin(), legend.end(), [&](const PlotSeries* l) { return l->label == s.label; });
      if (!seen && !s.label.empty()) legend.push_back(&s);
    }
  }
  const int per_row = std::max(1, int(panels.size()) * panel_width / 260);
  const int legend_rows = (int(legend.size()) + per_row - 1) / per_row;
  const int width = int(panels.size()) * panel_width, height = panel_height + 22 * legend_rows + 40;
  cv::Mat img(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  for (std::size_t i = 0; i < panels.size(); ++i) {
    drawPanel(img, panels[i], cv::Rect(int(i) * panel_width, 0, panel_width, panel_height));
  }
  for (std::size_t i = 0; i < legend.size(); ++i) {
    const int row = int(i) / per_row, col = int(i) % per_row;
    const cv::Point c(40 + col * 260, panel_height + 10 + row * 22);
    drawMarker(img, c, *legend[i]);
    cv::putText(img, legend[i]->label, c + cv::Point(12, 5), kFont, 0.42, kText, 1, cv::LINE_AA);
  }
  cv::putText(img, caption, {10, height - 12}, kFont, 0.4, kText, 1, cv::LINE_AA);

  tex::RawImage raw;
  raw.width = img.cols;
  raw.height = img.rows;
  raw.channels = 3;
  raw.bit_depth = 8;
  raw.samples.resize(std::size_t(raw.width) * std::size_t(raw.height) * 3);
  for (int y = 0; y < img.rows; ++y) {
    const cv::Vec3b* row = img.ptr<cv::Vec3b>(y);
    for (int x = 0; x < img.cols; ++x) {
      const std::size_t o = (std::size_t(y) * std::size_t(raw.width) + std::size_t(x)) * 3;
      raw.samples[o + 0] = row[x][2];
      raw.samples[o + 1] = row[x][1];
      raw.samples[o + 2] = row[x][0];
    }
  }
  raw.text["Software"] = "texhaptics tools/report/plot.cpp";
  tex::writePng(path, raw);
}

}  // namespace thx::bench
