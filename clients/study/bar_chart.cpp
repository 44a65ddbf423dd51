#include "clients/study/bar_chart.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "textures/png_io.hpp"

namespace thx::study {

namespace {

constexpr int kFace = cv::FONT_HERSHEY_SIMPLEX;
const cv::Scalar kInk(30, 30, 30), kRule(215, 215, 215);

void text(cv::Mat& img, const std::string& s, cv::Point at, double scale, bool centred = false) {
  int base = 0;
  const cv::Size size = cv::getTextSize(s, kFace, scale, 1, &base);
  if (centred) at.x -= size.width / 2;
  cv::putText(img, s, at, kFace, scale, kInk, 1, cv::LINE_AA);
}

// A tick step of 1, 2 or 5 times a power of ten giving at most eight intervals.
double tickStep(double top) {
  const double unit = std::pow(10.0, std::floor(std::log10(top)));
  for (double m : {0.1, 0.2, 0.5, 1.0, 2.0, 5.0}) {
    if (top / (m * unit) <= 8) return m * unit;
  }
  return 10 * unit;
}

void drawPanel(cv::Mat& img, const BarPanel& p, int x0, int w, int h) {
  const int left = x0 + 80, right = x0 + w - 20, top = 50, bottom = h - 110;
  text(img, p.title, {x0 + w / 2, 28}, 0.55, true);
  const auto y = [&](double v) { return bottom - int(std::lround(v / p.y_max * (bottom - top))); };
  // The y label, rotated: drawn on its own strip, then turned a quarter.
  cv::Mat strip(24, bottom - top, CV_8UC3, cv::Scalar(255, 255, 255));
  text(strip, p.y_label, {strip.cols / 2, 17}, 0.45, true);
  cv::Mat turned;
  cv::rotate(strip, turned, cv::ROTATE_90_COUNTERCLOCKWISE);
  turned.copyTo(img(cv::Rect(x0 + 4, top, turned.cols, turned.rows)));
  const double step = tickStep(p.y_max);
  for (double v = 0; v <= p.y_max * (1 + 1e-9); v += step) {
    cv::line(img, {left, y(v)}, {right, y(v)}, kRule, 1);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", std::fabs(v) < 1e-12 ? 0.0 : v);
    int base = 0;
    const int width = cv::getTextSize(buf, kFace, 0.42, 1, &base).width;
    text(img, buf, {left - 8 - width, y(v) + 5}, 0.42);  // right-aligned against the axis
  }

  const std::size_t nc = p.categories.size(), ns = p.series.size();
  const double slot = double(right - left) / double(std::max<std::size_t>(nc, 1));
  const double bar = slot * 0.8 / double(std::max<std::size_t>(ns, 1));
  for (std::size_t c = 0; c < nc; ++c) {
    const double slot_x = left + slot * double(c);
    text(img, p.categories[c], {int(slot_x + slot / 2), bottom + 20}, 0.42, true);
    for (std::size_t s = 0; s < ns; ++s) {
      const BarSeries& bs = p.series[s];
      const int bx = int(slot_x + slot * 0.1 + bar * double(s));
      const int cx = bx + int(bar / 2);
      const double v = bs.values[c];
      if (std::isnan(v)) {
        text(img, "n/a", {cx, bottom - 6}, 0.35, true);
        continue;
      }
      cv::rectangle(img, cv::Point(bx, y(std::min(v, p.y_max))), cv::Point(int(bx + bar) - 2, bottom),
                    cv::Scalar(bs.b, bs.g, bs.r), cv::FILLED);
      if (!bs.errors.empty() && !std::isnan(bs.errors[c])) {
        const int lo = y(std::max(0.0, v - bs.errors[c])), hi = y(std::min(p.y_max, v + bs.errors[c]));
        cv::line(img, {cx, lo}, {cx, hi}, kInk, 1, cv::LINE_AA);
        cv::line(img, {cx - 5, lo}, {cx + 5, lo}, kInk, 1, cv::LINE_AA);
        cv::line(img, {cx - 5, hi}, {cx + 5, hi}, kInk, 1, cv::LINE_AA);
      }
    }
  }
  cv::line(img, {left, bottom}, {right, bottom}, kInk, 1);
  cv::line(img, {left, top}, {left, bottom}, kInk, 1);
  // Legend under the category names, one swatch per series.
  int lx = left;
  for (const BarSeries& bs : p.series) {
    cv::rectangle(img, cv::Point(lx, bottom + 45), cv::Point(lx + 14, bottom + 59), cv::Scalar(bs.b, bs.g, bs.r),
                  cv::FILLED);
    text(img, bs.label, {lx + 20, bottom + 57}, 0.42);
    int base = 0;
    lx += 40 + cv::getTextSize(bs.label, kFace, 0.42, 1, &base).width;
  }
}

}  // namespace

void writeBarChartPng(const std::string& path, const std::vector<BarPanel>& panels, const std::string& caption,
                      int panel_width, int panel_height) {
  for (const BarPanel& p : panels) {
    if (!(p.y_max > 0)) throw std::logic_error("writeBarChartPng: panel '" + p.title + "': y_max must be > 0");
    for (const BarSeries& s : p.series) {
      if (s.values.size() != p.categories.size() || (!s.errors.empty() && s.errors.size() != p.categories.size())) {
        throw std::logic_error("writeBarChartPng: series '" + s.label + "' does not have one value per category");
      }
    }
  }
  const int width = panel_width * int(std::max<std::size_t>(panels.size(), 1));
  cv::Mat img(panel_height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  for (std::size_t i = 0; i < panels.size(); ++i) drawPanel(img, panels[i], int(i) * panel_width, panel_width, panel_height);
  text(img, caption, {10, panel_height - 14}, 0.4);
  tex::RawImage out;
  out.width = img.cols;
  out.height = img.rows;
  out.channels = 3;
  out.samples.resize(std::size_t(img.cols) * std::size_t(img.rows) * 3);
  for (int r = 0; r < img.rows; ++r) {
    for (int c = 0; c < img.cols; ++c) {
      const cv::Vec3b px = img.at<cv::Vec3b>(r, c);
      const std::size_t at = (std::size_t(r) * std::size_t(img.cols) + std::size_t(c)) * 3;
      out.samples[at] = px[2];
      out.samples[at + 1] = px[1];
      out.samples[at + 2] = px[0];
    }
  }
  tex::writePng(path, out);
}

}  // namespace thx::study
