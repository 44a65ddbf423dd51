// The pen's scrape across hapticd's scene switches (clients/audio/offline/scrape_session.hpp): a session
// on a flat scene, then, after a hello naming a grooved one, on that scene's surface and pen.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "clients/audio/offline/scrape_session.hpp"
#include "tests/audio/live_fixtures.hpp"

namespace thx::audio::test_scrape_session {
namespace {

// 1 s at 0.1 m/s along u from u = 0.3, v = 0.41 (ticks 1000-2000, utime = tick ms), no normal
// force: only the meso level sounds, and on a flat map nothing does.
std::vector<TimedScrapeSample> session() {
  std::vector<TimedScrapeSample> s;
  for (int k = 0; k <= 1000; ++k) s.push_back({(1000 + k) * 1000, {1000 + k, true, {0.3 + 0.1 / 0.2 * k / 1000.0, 0.41}}});
  return s;
}

// Two scenes on the small steel slab: "flat" (a flat normal map, the slab alone) and "grooves"
// (a column of tilted texels every other one, with the steel pen).
struct Scenes {
  tex::TextureMap flat_map{64, 64, tex::Representation::Normal};
  tex::TextureMap groove_map = test::grooveMap();
  PenModes pen{&test::livePen().mesh, &test::livePen().modes, test::livePen().tip, 30.0};
  std::map<std::string, ScrapeSurface> surfaces;
  std::vector<std::string> asked;  // the names surface_for was called with
  Scenes() {
    surfaces["flat"] = {&flat_map, &test::liveSlab().mesh, &test::liveSlab().modes, nullptr, {}};
    surfaces["grooves"] = {&groove_map, &test::liveSlab().mesh, &test::liveSlab().modes, &pen, {}};
  }
  ScrapeSessionRender render(const std::vector<SceneStart>& hellos, const std::string& first) {
    return renderScrapeSession(session(), hellos, first, [this](const std::string& name) -> const ScrapeSurface& {
      asked.push_back(name);
      return surfaces.at(name);
    });
  }
};

constexpr std::int64_t kSwitchUtime = 1500 * 1000;  // tick 1500
constexpr std::size_t kSwitchSample = 22050;         // 0.5 s after tick 1000 at 44.1 kHz

TEST(ScrapeSession, AfterASwitchThePenScrapesTheNewScenesSurface) {
  Scenes sc;
  // The first hello names the scene the session starts in, the second a switch.
  const std::vector<SceneStart> hellos{{1000 * 1000, "flat"}, {kSwitchUtime, "grooves"}};
  const ScrapeSessionRender a = sc.render(hellos, "flat");
  ASSERT_EQ(a.scenes, (std::vector<std::string>{"flat", "grooves"}));
  // The flat stretch is exactly silent; the grooved one sounds, on one timeline.
  const std::vector<float>& x = a.render.samples;
  ASSERT_GT(x.size(), kSwitchSample);
  const std::size_t first = std::size_t(std::find_if(x.begin(), x.end(), [](float v) { return v != 0.0f; }) - x.begin());
  EXPECT_GT(first, kSwitchSample);
  // The walk starts afresh at tick 1500 (u = 0.55, texel 35): its first texel boundary, u = 36/64,
  // is reached at tick 1525, which enters the impulse at sample round(0.525 x 44100) = 23153 (or
  // 23152 as the half rounds) and sounds from the next one.
  EXPECT_GE(first, 23153u);
  EXPECT_LE(first, 23154u);
  EXPECT_EQ(a.render.impulses, 32u);  // 16 texels entered on each side of the switch
  EXPECT_GT(a.render.nonzero_impulses, 0u);
  EXPECT_GT(a.render.pen_peak, 0.0);  // the grooved scene's pen sounds
  float peak = 0;
  for (float v : x) peak = std::max(peak, std::fabs(v));
  EXPECT_FLOAT_EQ(peak, 0.5f);

  // Exactly what the grooved surface and its pen give for the samples from the switch on.
  const std::vector<TimedScrapeSample> all = session();
  std::vector<ScrapeSample> after;
  for (const TimedScrapeSample& s : all)
    if (s.utime >= kSwitchUtime) after.push_back(s.sample);
  ScrapeOptions o;
  o.origin_tick = 1000;
  const ScrapeRender alone = scrapeDisplacement(sc.groove_map, test::liveSlab().mesh, test::liveSlab().modes, after, o, &sc.pen);
  EXPECT_EQ(a.render.displacement, alone.displacement);

  // Deterministic.
  const ScrapeSessionRender b = sc.render(hellos, "flat");
  EXPECT_EQ(a.render.samples, b.render.samples);
}

TEST(ScrapeSession, WithoutASwitchItIsTheOneSceneRender) {
  Scenes sc;
  std::vector<ScrapeSample> path;
  for (const TimedScrapeSample& s : session()) path.push_back(s.sample);
  const ScrapeRender one = renderScrape(sc.groove_map, test::liveSlab().mesh, test::liveSlab().modes, path, {}, &sc.pen);
  // Hellos naming the current scene, or none, switch nothing.
  const ScrapeSessionRender r = sc.render({{1000 * 1000, "grooves"}, {kSwitchUtime, ""}}, "grooves");
  EXPECT_EQ(r.scenes, std::vector<std::string>{"grooves"});
  EXPECT_EQ(r.render.samples, one.samples);
  EXPECT_EQ(r.render.impulses, one.impulses);
}

TEST(ScrapeSession, TheOldSurfaceRingsOnAfterASwitchToAFlatOne) {
  Scenes sc;
  const ScrapeSessionRender r = sc.render({{kSwitchUtime, "flat"}}, "grooves");
  ASSERT_EQ(r.scenes, (std::vector<std::string>{"grooves", "flat"}));
  std::vector<ScrapeSample> before;
  for (const TimedScrapeSample& s : session())
    if (s.utime < kSwitchUtime) before.push_back(s.sample);
  // Nothing strikes after the switch; the grooved stretch's slab and pen ring on to the end.
  ScrapeOptions o;
  const ScrapeRender alone = scrapeDisplacement(sc.groove_map, test::liveSlab().mesh, test::liveSlab().modes, before, o, &sc.pen);
  ASSERT_LT(alone.displacement.size(), r.render.displacement.size());
  for (std::size_t n = 0; n < alone.displacement.size(); ++n) ASSERT_EQ(r.render.displacement[n], alone.displacement[n]) << n;
  EXPECT_NE(r.render.displacement[kSwitchSample + 100], 0.0);  // still ringing after the switch
  // And a switch back to grooves restarts the walk on it: a third stretch.
  Scenes sc2;
  const ScrapeSessionRender back = sc2.render({{kSwitchUtime, "flat"}, {1750 * 1000, "grooves"}}, "grooves");
  EXPECT_EQ(back.scenes, (std::vector<std::string>{"grooves", "flat", "grooves"}));
}

}  // namespace
}  // namespace thx::audio::test_scrape_session
