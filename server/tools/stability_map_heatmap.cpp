#include "server/tools/stability_map_heatmap.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <tuple>

#include "textures/png_io.hpp"

namespace thx::srv::stab {

namespace {

// Layout, pixels.
constexpr int kSquareW = 44, kSquareH = 24;  // one (angle, stiffness) square
constexpr int kPanelLeft = 44;               // stiffness labels
constexpr int kPanelTop = 18;                // panel title
constexpr int kPanelBottom = 30;             // angle labels + axis name
constexpr int kGapX = 24, kGapY = 10;
constexpr int kMargin = 16;
constexpr int kHeader = 58, kFooter = 84;
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

const cv::Scalar kInk(30, 30, 30);
const cv::Scalar kGrey(120, 120, 120);
const cv::Scalar kWhite(255, 255, 255);
const cv::Scalar kEmpty(225, 225, 225);

// BGR: teal, amber, dark red; told apart by lightness too, and every square is lettered.
cv::Scalar verdictColour(Verdict v) {
  switch (v) {
    case Verdict::Stable: return cv::Scalar(115, 150, 0);
    case Verdict::LimitCycle: return cv::Scalar(0, 165, 235);
    case Verdict::Unstable: return cv::Scalar(40, 30, 180);
    case Verdict::CannotHold: return cv::Scalar(170, 170, 170);
  }
  return kEmpty;
}

char verdictLetter(Verdict v) {
  switch (v) {
    case Verdict::Stable: return 'S';
    case Verdict::LimitCycle: return 'L';
    case Verdict::Unstable: return 'U';
    case Verdict::CannotHold: return 'H';
  }
  return '?';
}

void text(cv::Mat& img, const std::string& s, cv::Point at, double scale, const cv::Scalar& colour, int thickness = 1) {
  cv::putText(img, s, at, kFont, scale, colour, thickness, cv::LINE_AA);
}

void centredText(cv::Mat& img, const std::string& s, cv::Point centre, double scale, const cv::Scalar& colour) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(s, kFont, scale, 1, &baseline);
  text(img, s, cv::Point(centre.x - size.width / 2, centre.y + size.height / 2), scale, colour);
}

std::string fmt(const char* f, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

using Key = std::tuple<int, bool, double, double>;  // mitigations, relief, angle, stiffness

}  // namespace

void writeHeatmap(const std::string& path, const SweepAxes& axes, const std::vector<CellResult>& results,
                  const std::string& subtitle) {
  // Letters per square, in push-force order.
  std::vector<double> forces = axes.push_forces_n;
  std::sort(forces.begin(), forces.end());
  std::map<Key, std::string> letters;
  std::map<Key, Verdict> worst;
  for (const CellResult& r : results) {
    const Key key{r.params.mitigations.index(), r.params.relief, r.params.angle_deg, r.params.stiffness_fraction};
    std::string& l = letters[key];
    if (l.empty()) l.assign(forces.size(), '.');
    const auto at = std::find(forces.begin(), forces.end(), r.params.push_force_n);
    // Lower case: the thermal (continuous-force) limit acted in the window, yet the cell still
    // tests the valley (not cannot-hold); the verdict is about oscillation only.
    const char letter = verdictLetter(r.metrics.verdict);
    const bool limited = r.metrics.continuous_limit_fraction > 0.0 && r.metrics.verdict != Verdict::CannotHold;
    if (at != forces.end()) l[std::size_t(at - forces.begin())] = limited ? char(letter - 'A' + 'a') : letter;
    const auto w = worst.find(key);
    if (w == worst.end() || severity(r.metrics.verdict) > severity(w->second)) worst[key] = r.metrics.verdict;
  }

  std::vector<double> stiffness = axes.stiffness_fractions;
  std::sort(stiffness.begin(), stiffness.end());
  const int cols = int(axes.angles_deg.size()), rows = int(stiffness.size());
  const int panel_w = kPanelLeft + cols * kSquareW, panel_h = kPanelTop + rows * kSquareH + kPanelBottom;
  const int n_repr = int(axes.relief.size()), n_mit = int(axes.mitigations.size());
  const int width = std::max(2 * kMargin + n_repr * panel_w + (n_repr - 1) * kGapX, 640);
  const int height = kHeader + n_mit * panel_h + (n_mit - 1) * kGapY + kFooter;
  cv::Mat img(height, width, CV_8UC3, kWhite);

  text(img, "Stability map: V-valley press, simulated PHANToM Desktop (1 kHz servo, lock-step)", {kMargin, 22}, 0.55,
       kInk, 1);
  text(img, subtitle, {kMargin, 44}, 0.4, kGrey);

  const double letter_scale = forces.size() > 6 ? 0.25 : (forces.size() > 4 ? 0.3 : 0.38);
  for (int mi = 0; mi < n_mit; ++mi) {
    for (int ri = 0; ri < n_repr; ++ri) {
      const Mitigations& m = axes.mitigations[std::size_t(mi)];
      const bool relief = axes.relief[std::size_t(ri)];
      const int x0 = kMargin + ri * (panel_w + kGapX), y0 = kHeader + mi * (panel_h + kGapY);
      text(img, std::string(relief ? "relief" : "normal map") + "  |  mitigations: " + m.name(),
           {x0, y0 + kPanelTop - 5}, 0.42, kInk);
      const int gx = x0 + kPanelLeft, gy = y0 + kPanelTop;
      for (int r = 0; r < rows; ++r) {
        const double k = stiffness[std::size_t(rows - 1 - r)];  // stiffest at the top
        text(img, fmt("%.2g", k), {x0 + 4, gy + r * kSquareH + kSquareH / 2 + 4}, 0.35, kInk);
        for (int c = 0; c < cols; ++c) {
          const Key key{m.index(), relief, axes.angles_deg[std::size_t(c)], k};
          const cv::Rect square(gx + c * kSquareW, gy + r * kSquareH, kSquareW, kSquareH);
          const auto w = worst.find(key);
          cv::rectangle(img, square, w == worst.end() ? kEmpty : verdictColour(w->second), cv::FILLED);
          cv::rectangle(img, square, kWhite, 1);
          if (w != worst.end())
            centredText(img, letters[key], {square.x + kSquareW / 2, square.y + kSquareH / 2}, letter_scale, kWhite);
        }
      }
      const int label_y = gy + rows * kSquareH + 12;
      for (int c = 0; c < cols; ++c)
        centredText(img, fmt("%g", axes.angles_deg[std::size_t(c)]), {gx + c * kSquareW + kSquareW / 2, label_y}, 0.35,
                    kInk);
      centredText(img, "opening angle, deg", {gx + cols * kSquareW / 2, label_y + 13}, 0.33, kGrey);
      text(img, "K/Kmax", {x0, label_y + 4}, 0.3, kGrey);
    }
  }

  // Legend.
  const int ly = height - kFooter + 14;
  const Verdict verdicts[] = {Verdict::Stable, Verdict::LimitCycle, Verdict::Unstable, Verdict::CannotHold};
  int lx = kMargin;
  for (const Verdict v : verdicts) {
    cv::rectangle(img, cv::Rect(lx, ly, 18, 12), verdictColour(v), cv::FILLED);
    text(img, verdictName(v), {lx + 24, ly + 11}, 0.4, kInk);
    lx += 130;
  }
  std::string forces_text = "letters: verdict at push force ";
  for (std::size_t i = 0; i < forces.size(); ++i) forces_text += (i ? ", " : "") + fmt("%g", forces[i]);
  forces_text += " N (S stable, L limit-cycle, U unstable, H cannot hold); colour: the worst.";
  text(img, forces_text, {kMargin, ly + 30}, 0.38, kInk);
  text(img, "H: the continuous-force limit held the force below the push and the pen sank; lower case: it acted, the cell still counts.",
       {kMargin, ly + 46}, 0.38, kInk);
  text(img, "rows: stiffness as a fraction of the device maximum (1000 N/m); docs/stability.md explains the verdicts.",
       {kMargin, ly + 62}, 0.38, kInk);

  // BGR cv::Mat -> RGB RawImage.
  tex::RawImage out;
  out.width = img.cols;
  out.height = img.rows;
  out.channels = 3;
  out.bit_depth = 8;
  out.samples.resize(std::size_t(img.cols) * std::size_t(img.rows) * 3);
  std::size_t k = 0;
  for (int y = 0; y < img.rows; ++y) {
    const cv::Vec3b* row = img.ptr<cv::Vec3b>(y);
    for (int x = 0; x < img.cols; ++x) {
      out.samples[k++] = row[x][2];
      out.samples[k++] = row[x][1];
      out.samples[k++] = row[x][0];
    }
  }
  out.text["Software"] = "stability-map";
  tex::writePng(path, out);
}

}  // namespace thx::srv::stab
