// The pen's scrape rendered offline (clients/audio/scrape_synthesis.hpp) on a small slab.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "clients/audio/scrape_synthesis.hpp"
#include "tests/audio/live_fixtures.hpp"

namespace thx::audio {
namespace {

using test::steel;

// The small steel slab the live tests use too.
const test::LiveSlab& slab() { return test::liveSlab(); }

// 0.5 s at 0.1 m/s along u from u = 0.3, v = 0.41: 64 texels over 0.2 m, so one texel per
// 3.125 mm, 16 texels entered.
std::vector<ScrapeSample> straightScrape() {
  std::vector<ScrapeSample> path;
  for (int k = 0; k <= 500; ++k) path.push_back({1000 + k, true, {0.3 + 0.1 / 0.2 * k / 1000.0, 0.41}});
  return path;
}

tex::TextureMap grooves() { return test::grooveMap(); }

TEST(ScrapeSynthesis, FlatMapIsSilent) {
  const tex::TextureMap flat(64, 64, tex::Representation::Normal);
  const ScrapeRender r = renderScrape(flat, slab().mesh, slab().modes, straightScrape(), ScrapeOptions{});
  EXPECT_EQ(r.impulses, 16u);
  EXPECT_GT(r.samples.size(), 44100u / 2);
  for (float x : r.samples) ASSERT_EQ(x, 0.0f);
}

TEST(ScrapeSynthesis, GroovesSoundOncePerTexelAndTheSameEveryTime) {
  const tex::TextureMap map = grooves();
  const ScrapeRender a = renderScrape(map, slab().mesh, slab().modes, straightScrape(), ScrapeOptions{});
  EXPECT_EQ(a.impulses, 16u);
  EXPECT_GT(a.raw_peak, 0.0);
  float peak = 0;
  for (float x : a.samples) peak = std::max(peak, std::fabs(x));
  EXPECT_FLOAT_EQ(peak, 0.5f);
  // Silent until the first column boundary, u = 20/64 = 0.3125, reached at tick 25 (25 ms): the
  // impulse enters at sample round(0.025 x 44100) = 1103 and sounds from the next one.
  const auto first = std::find_if(a.samples.begin(), a.samples.end(), [](float x) { return x != 0.0f; }) - a.samples.begin();
  EXPECT_EQ(first, 1104);
  const ScrapeRender b = renderScrape(map, slab().mesh, slab().modes, straightScrape(), ScrapeOptions{});
  EXPECT_EQ(a.samples, b.samples);
}

TEST(ScrapeSynthesis, LiftingOffStopsTheImpulses) {
  std::vector<ScrapeSample> path = straightScrape();
  for (std::size_t k = 250; k < path.size(); ++k) path[k].in_contact = false;
  const ScrapeRender r = renderScrape(grooves(), slab().mesh, slab().modes, path, ScrapeOptions{});
  EXPECT_EQ(r.impulses, 8u);  // 0.25 s: 8 texels entered
}

}  // namespace
}  // namespace thx::audio
