// Every pen of a recorded session, mixed (issue 30; clients/audio/offline/pen_mix.hpp, docs/audio.md
// §5 "Several pens"): hapticd records scenes/two_pens.yaml in lock-step (two simulated pens on the
// bricks, 2 s); audio-client renders the mix and each pen alone (--device 0, --device 1), all at one
// gain (--gain: neither normalised nor clamped, so the three compare sample for sample; the default
// normalisation to a peak of 0.5 would scale each render by its own peak). Modal synthesis is
// linear: the mix must equal the sum of the two pens alone to float rounding, and each pen alone
// must differ from the mix (both pens are heard).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "tests/audio/replay_render.hpp"
#include "tests/support/rendered_sound.hpp"

namespace test_pen_mix {

namespace {

const std::string kScene = std::string(THX_SOURCE_DIR) + "/scenes/two_pens.yaml";

class PenMix : public thx::test::SessionTest {
 protected:
  // audio-client on the session at gain 1e6 (the mix's raw peak, 3.5e-8 m^3, becomes 0.035: float
  // keeps 2^-24 of any magnitude), a small slab for speed.
  std::vector<float> render(const std::string& name, const std::string& options) {
    return thx::audio::test::replayRender("--scene " + kScene + " --replay-log " + path("session.lcm") +
                                              " --slab-cells 4 --modes 12 --gain 1e6 --cache-dir " + path("cache") + " " +
                                              options,
                                          path(name + ".wav"));
  }
};

double peakOf(const std::vector<double>& x) {
  double p = 0.0;
  for (double v : x) p = std::max(p, std::fabs(v));
  return p;
}

// a - b sample by sample, the shorter zero-padded (a pen alone ends with its own last tick).
std::vector<double> difference(const std::vector<float>& a, const std::vector<double>& b) {
  std::vector<double> d(std::max(a.size(), b.size()), 0.0);
  for (std::size_t n = 0; n < d.size(); ++n) d[n] = (n < a.size() ? double(a[n]) : 0.0) - (n < b.size() ? b[n] : 0.0);
  return d;
}

std::vector<double> widened(const std::vector<float>& x) { return std::vector<double>(x.begin(), x.end()); }

TEST_F(PenMix, TheMixIsTheSumOfEachPenAloneAndBothAreHeard) {
  ASSERT_EQ(recordSession(kScene, "--duration 2"), 0) << fileBytes(path("hapticd.out"));
  const std::vector<float> mix = render("mix", "");
  EXPECT_NE(fileBytes(path("mix.wav.out")).find("every pen, mixed: device 0 ("), std::string::npos);
  EXPECT_NE(fileBytes(path("mix.wav.out")).find(" device 1 ("), std::string::npos);
  const std::vector<float> left = render("left", "--device 0");
  const std::vector<float> right = render("right", "--device 1");
  ASSERT_GT(mix.size(), std::size_t(2 * 44100));

  std::vector<double> sum = widened(left);
  sum.resize(std::max(left.size(), right.size()), 0.0);
  for (std::size_t n = 0; n < right.size(); ++n) sum[n] += double(right[n]);
  const double peak = peakOf(widened(mix));
  ASSERT_GT(peak, 0.0);
  // Each render rounds G x to float (half an ulp, 2^-24 relative): the sum of three such errors
  // stays below 1e-6 of the mix's peak.
  const double superposition = peakOf(difference(mix, sum));
  const double left_gap = peakOf(difference(mix, widened(left))), right_gap = peakOf(difference(mix, widened(right)));
  std::printf("[measured] mix peak %.6g; max |mix - (left + right)| %.3g (%.3g of the peak); max |mix - left| %.3g, "
              "|mix - right| %.3g\n",
              peak, superposition, superposition / peak, left_gap, right_gap);
  EXPECT_LE(superposition, 1e-6 * peak);
  EXPECT_EQ(mix.size(), sum.size());
  // Both pens are heard: leaving either out changes the sound by a good part of its peak.
  EXPECT_GT(left_gap, 0.1 * peak);
  EXPECT_GT(right_gap, 0.1 * peak);
}

}  // namespace

}  // namespace test_pen_mix
