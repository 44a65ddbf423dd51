#include "clients/audio/spectrogram/spectrogram_image.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "textures/png_io.hpp"

namespace thx::audio {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
const cv::Scalar kBlack(0, 0, 0), kGrey(90, 90, 90);

// The smallest of the usual steps that gives at most `max_ticks` ticks over `span`.
double tickStep(double span, int max_ticks) {
  for (double decade = 1e-3; decade < 1e7; decade *= 10)
    for (double m : {1.0, 2.0, 5.0})
      if (span / (m * decade) <= max_ticks) return m * decade;
  return span;
}

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", std::fabs(v) < 1e-9 ? 0.0 : v);
  return b;
}

void centredText(cv::Mat& img, const std::string& s, cv::Point at, double scale, const cv::Scalar& colour) {
  int base = 0;
  const cv::Size ts = cv::getTextSize(s, kFont, scale, 1, &base);
  cv::putText(img, s, {at.x - ts.width / 2, at.y}, kFont, scale, colour, 1, cv::LINE_AA);
}

}  // namespace

void writeSpectrogramPng(const std::string& path, const Spectrogram& s, const SpectrogramImageOptions& o) {
  const int left = 70, right = 110, top = o.title.empty() ? 20 : 40, bottom = 55;
  const int w = std::max(50, o.width), h = std::max(50, o.height);
  cv::Mat img(top + h + bottom, left + w + right, CV_8UC3, cv::Scalar(255, 255, 255));
  const double nyquist = 0.5 * s.sample_rate_hz;
  const double max_hz = o.max_hz > 0 ? std::min(o.max_hz, nyquist) : nyquist;
  const float peak = s.db.empty() ? 0.0f : *std::max_element(s.db.begin(), s.db.end());
  const double floor_db = double(peak) - o.range_db;

  // Each pixel shows the loudest STFT cell it covers, so no click narrower than a pixel is lost.
  cv::Mat level(h, w, CV_8UC1);
  const double seconds = double(s.frames) * double(s.hop) / s.sample_rate_hz;
  for (int x = 0; x < w; ++x) {
    const std::size_t f0 = std::min(s.frames - 1, std::size_t(double(x) / w * double(s.frames)));
    const std::size_t f1 = std::max(f0 + 1, std::min(s.frames, std::size_t(double(x + 1) / w * double(s.frames))));
    for (int y = 0; y < h; ++y) {
      const double hz_hi = max_hz * (1.0 - double(y) / h), hz_lo = max_hz * (1.0 - double(y + 1) / h);
      const std::size_t b0 = std::min(s.bins - 1, std::size_t(std::lround(hz_lo / s.sample_rate_hz * double(s.window))));
      const std::size_t b1 = std::min(s.bins - 1, std::size_t(std::lround(hz_hi / s.sample_rate_hz * double(s.window))));
      float v = -1e30f;
      for (std::size_t f = f0; f < f1; ++f)
        for (std::size_t b = b0; b <= b1; ++b) v = std::max(v, s.at(f, b));
      const double t = std::clamp((double(v) - floor_db) / o.range_db, 0.0, 1.0);
      level.at<std::uint8_t>(y, x) = std::uint8_t(std::lround(255 * t));
    }
  }
  cv::Mat coloured;
  cv::applyColorMap(level, coloured, cv::COLORMAP_INFERNO);
  coloured.copyTo(img(cv::Rect(left, top, w, h)));
  cv::rectangle(img, cv::Rect(left - 1, top - 1, w + 2, h + 2), kBlack, 1);

  // Frequency axis (kHz), time axis (s).
  const double f_step = tickStep(max_hz, 10);
  for (double f = 0; f <= max_hz + 1e-9; f += f_step) {
    const int y = top + int(std::lround(h * (1.0 - f / max_hz)));
    cv::line(img, {left - 5, y}, {left - 1, y}, kBlack, 1);
    int base = 0;
    const std::string label = number(f / 1000.0);
    const cv::Size ts = cv::getTextSize(label, kFont, 0.4, 1, &base);
    cv::putText(img, label, {left - 8 - ts.width, y + 4}, kFont, 0.4, kBlack, 1, cv::LINE_AA);
  }
  const double t_step = tickStep(std::max(seconds, 1e-3), 12);
  for (double t = 0; t <= seconds + 1e-9; t += t_step) {
    const int x = left + int(std::lround(w * t / seconds));
    cv::line(img, {x, top + h + 1}, {x, top + h + 5}, kBlack, 1);
    centredText(img, number(t), {x, top + h + 20}, 0.4, kBlack);
  }
  centredText(img, "time, s", {left + w / 2, top + h + 42}, 0.45, kBlack);
  {
    // The vertical frequency label, drawn into a strip and rotated.
    const std::string label = "frequency, kHz";
    int base = 0;
    const cv::Size ts = cv::getTextSize(label, kFont, 0.45, 1, &base);
    cv::Mat strip(ts.height + 8, ts.width + 8, img.type(), cv::Scalar(255, 255, 255));
    cv::putText(strip, label, {4, ts.height + 2}, kFont, 0.45, kBlack, 1, cv::LINE_AA);
    cv::Mat rotated;
    cv::rotate(strip, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
    const int y0 = std::max(0, top + (h - rotated.rows) / 2);
    if (y0 + rotated.rows <= img.rows) rotated.copyTo(img(cv::Rect(4, y0, rotated.cols, rotated.rows)));
  }
  if (!o.title.empty()) cv::putText(img, o.title, {left, top - 14}, kFont, 0.5, kBlack, 1, cv::LINE_AA);

  // The colour scale: dB relative to a full-scale amplitude of 1.
  const int bar_x = left + w + 20, bar_w = 16;
  cv::Mat ramp(h, 1, CV_8UC1);
  for (int y = 0; y < h; ++y) ramp.at<std::uint8_t>(y, 0) = std::uint8_t(std::lround(255.0 * (1.0 - double(y) / (h - 1))));
  cv::Mat ramp_c, ramp_wide;
  cv::applyColorMap(ramp, ramp_c, cv::COLORMAP_INFERNO);
  cv::resize(ramp_c, ramp_wide, {bar_w, h}, 0, 0, cv::INTER_NEAREST);
  ramp_wide.copyTo(img(cv::Rect(bar_x, top, bar_w, h)));
  cv::rectangle(img, cv::Rect(bar_x - 1, top - 1, bar_w + 2, h + 2), kBlack, 1);
  const double db_step = tickStep(o.range_db, 8);
  for (double d = std::ceil(floor_db / db_step) * db_step; d <= double(peak) + 1e-9; d += db_step) {
    const int y = top + int(std::lround(h * (double(peak) - d) / o.range_db));
    cv::line(img, {bar_x + bar_w, y}, {bar_x + bar_w + 4, y}, kBlack, 1);
    cv::putText(img, number(d), {bar_x + bar_w + 7, y + 4}, kFont, 0.38, kBlack, 1, cv::LINE_AA);
  }
  centredText(img, "dB", {bar_x + bar_w / 2, top + h + 20}, 0.4, kGrey);

  tex::RawImage raw;
  raw.width = img.cols;
  raw.height = img.rows;
  raw.channels = 3;
  raw.bit_depth = 8;
  cv::Mat rgb;
  cv::cvtColor(img, rgb, cv::COLOR_BGR2RGB);
  raw.samples.assign(rgb.datastart, rgb.dataend);  // a new Mat is continuous
  raw.text["Software"] = "texhaptics wav-spectrogram";
  tex::writePng(path, raw);
}

}  // namespace thx::audio
