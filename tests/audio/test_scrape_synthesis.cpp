// The pen's scrape rendered offline (clients/audio/offline/scrape_synthesis.hpp) on a small slab.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "clients/audio/analysis/scene_bodies.hpp"
#include "clients/audio/offline/scrape_synthesis.hpp"
#include "tests/audio/live_fixtures.hpp"

namespace thx::audio::test_scrape_synthesis {
namespace {

using test::steel;

// The small steel slab the live tests use too.
const test::LiveSlab& slab() { return test::liveSlab(); }

// The steel pen the live tests use too, as the offline render takes it.
struct Pen {
  PenModes view{&test::livePen().mesh, &test::livePen().modes, test::livePen().tip, 30.0};
  const AudibleModes& modes = test::livePen().modes;
};

const Pen& pen() {
  static const Pen p;
  return p;
}

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
  EXPECT_EQ(r.nonzero_impulses, 0u);
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

// The pen pressing with 1 N along the straight scrape.
std::vector<ScrapeSample> pressedScrape(double force_n) {
  std::vector<ScrapeSample> path = straightScrape();
  for (ScrapeSample& p : path) p.f_normal_n = force_n;
  return path;
}

TEST(ScrapeSynthesis, FlatMapStillSoundsItsFineRoughness) {
  const tex::TextureMap flat(64, 64, tex::Representation::Normal);
  const ScrapeRender r = renderScrape(flat, slab().mesh, slab().modes, pressedScrape(1.0), ScrapeOptions{});
  EXPECT_GT(r.raw_peak, 0.0);
  EXPECT_NEAR(r.micro_rms_n, 0.03, 0.015);  // amplitude 0.03 x 1 N x a unit-RMS profile
  // The first segment's force acts from the sample after its first tick's (sample 1) and sounds
  // from the next one.
  EXPECT_EQ(r.samples[1], 0.0f);
  EXPECT_NE(r.samples[2], 0.0f);
  // No roughness amplitude: silent again.
  ScrapeOptions quiet;
  quiet.roughness.amplitude = 0.0;
  const ScrapeRender q = renderScrape(flat, slab().mesh, slab().modes, pressedScrape(1.0), quiet);
  for (float x : q.samples) ASSERT_EQ(x, 0.0f);
}

TEST(ScrapeSynthesis, MicroForceFollowsTheNormalForce) {
  const tex::TextureMap flat(64, 64, tex::Representation::Normal);
  const ScrapeExcitation one = scrapeExcitation(flat, slab().mesh, pressedScrape(1.0), ScrapeOptions{});
  const ScrapeExcitation three = scrapeExcitation(flat, slab().mesh, pressedScrape(3.0), ScrapeOptions{});
  ASSERT_EQ(one.impulse_ns.size(), three.impulse_ns.size());
  for (std::size_t n = 0; n < one.impulse_ns.size(); ++n) ASSERT_NEAR(three.impulse_ns[n], 3 * one.impulse_ns[n], 1e-18);
  EXPECT_NEAR(three.micro_rms_n, 3 * one.micro_rms_n, 1e-12);
  // Nothing after the last tick in contact (0.5 s).
  for (std::size_t n = 22051; n < one.impulse_ns.size(); ++n) ASSERT_EQ(one.impulse_ns[n], 0.0);
}

TEST(ScrapeSynthesis, BothSidesSoundAndTheRenderIsTheSameEveryTime) {
  const tex::TextureMap map = grooves();
  const ScrapeRender slab_only = renderScrape(map, slab().mesh, slab().modes, pressedScrape(1.0), ScrapeOptions{});
  const ScrapeRender a = renderScrape(map, slab().mesh, slab().modes, pressedScrape(1.0), ScrapeOptions{}, &pen().view);
  const ScrapeRender b = renderScrape(map, slab().mesh, slab().modes, pressedScrape(1.0), ScrapeOptions{}, &pen().view);
  ASSERT_GT(pen().modes.size(), 0u);
  EXPECT_EQ(a.impulses, 16u);
  EXPECT_GT(a.pen_peak, 0.0);
  EXPECT_GT(a.slab_peak, 0.0);
  EXPECT_EQ(a.slab_peak, slab_only.slab_peak);  // the pen's modes add to the slab's, change nothing there
  EXPECT_NE(a.samples, slab_only.samples);
  EXPECT_EQ(a.samples, b.samples);
  // With no roughness the pen still rings at the grooves: the meso impulses excite both sides.
  ScrapeOptions meso_only;
  meso_only.roughness.amplitude = 0.0;
  const ScrapeRender m = renderScrape(map, slab().mesh, slab().modes, straightScrape(), meso_only, &pen().view);
  EXPECT_GT(m.pen_peak, 0.0);
  EXPECT_GT(m.slab_peak, 0.0);
}

TEST(ScrapeSynthesis, ReliefImpulsesFromTheContactNormal) {
  // A relief scrape: the map is not read; the contact normal steps onto a 20-degree facet at
  // tick 100 and back at tick 200 (0.1 m/s along x).
  const double a = 20.0 * std::numbers::pi / 180.0;
  std::vector<ScrapeSample> path = straightScrape();
  for (ScrapeSample& p : path) {
    p.v_tangent = {0.1, 0.0, 0.0};
    if (p.tick >= 1100 && p.tick < 1200) p.n_contact = {std::sin(a), 0.0, std::cos(a)};
  }
  ScrapeOptions o;
  o.meso = MesoSource::ContactNormals;
  o.roughness.amplitude = 0.0;
  const tex::TextureMap flat(64, 64, tex::Representation::Normal);
  const ScrapeExcitation e = scrapeExcitation(flat, slab().mesh, path, o);
  EXPECT_EQ(e.impulses, 500u);  // one per tick in contact after the first
  EXPECT_EQ(e.nonzero_impulses, 2u);
  std::vector<std::size_t> at;
  for (std::size_t n = 0; n < e.impulse_ns.size(); ++n)
    if (e.impulse_ns[n] != 0.0) at.push_back(n);
  ASSERT_EQ(at.size(), 2u);
  EXPECT_EQ(at[0], 4410u);  // tick 100 after the first: 0.1 s
  EXPECT_EQ(at[1], 8820u);
  EXPECT_NEAR(e.impulse_ns[at[0]], -0.045 * 0.1 * std::tan(a), 1e-12);
  EXPECT_NEAR(e.impulse_ns[at[1]], 0.045 * 0.1 * std::tan(a), 1e-12);
  // A flat relief: exactly silent.
  for (ScrapeSample& p : path) p.n_contact = {0, 0, 1};
  const ScrapeRender r = renderScrape(flat, slab().mesh, slab().modes, path, o, &pen().view);
  for (float x : r.samples) ASSERT_EQ(x, 0.0f);
}

}  // namespace
}  // namespace thx::audio::test_scrape_synthesis
