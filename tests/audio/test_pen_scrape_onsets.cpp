// The pen scraping the default scene's brick relief (issue 14), as a user runs it: hapticd records
// a straight stroke across the bed joints in lock-step (tests/data/scenes/pen_stroke_bricks.yaml),
// audio-client renders it, and the clicks detected in the WAV (tests/support/onset_detector.hpp)
// come at the rate, and at the times, hapticd's CONTACT stream says the pen tip entered a mortar
// joint (docs/audio.md §12).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <thx_msgs/contact_t.hpp>

#include "tests/support/rendered_sound.hpp"
#include "thx_msgs/log_reader.hpp"

namespace test_pen_scrape_onsets {

namespace {

const std::string kScene = std::string(THX_TEST_DATA_DIR) + "/scenes/pen_stroke_bricks.yaml";

class PenScrapeOnsets : public thx::test::SessionTest {};

TEST_F(PenScrapeOnsets, OnsetsInTheWavComeAtTheMortarCrossingsOfTheStroke) {
  // 1. The session: 7 bed joints down and 7 back up at 0.08 m/s, 1 N (4.1 s).
  ASSERT_EQ(recordSession(kScene), 0);
  // 2. Rendered with a small slab mesh and without the pen's own modes (quick in the sanitizer
  // tree; the pen would ring at the same impulses); the micro level on, as in the demo. The slab
  // is 4 x 4 x 2 cells (the default 2 layers).
  ASSERT_EQ(run(std::string(THX_AUDIO_CLIENT) + " --scene " + kScene + " --replay-log " + path("session.lcm") +
                " --slab-cells 4 --no-pen --cache-dir " + path("cache") + " --wav " + path("scrape.wav") + " > " + path("audio.out") +
                " 2>&1"),
            0)
      << fileBytes(path("audio.out"));
  std::printf("%s", fileBytes(path("audio.out")).c_str());

  // 3. The mortar crossings hapticd reported: ticks in contact whose texel (contact_t.texel_i/j,
  // under the device's tip) is mortar after a tick in contact on a brick. Mortar: relief deeper
  // than halfway between the highest brick face and the joints' floor. The tip, pulled by the
  // hand's grip spring, is caught at a joint's far wall and swings back into the joint when it
  // gets over it (once here, 50 ms after the entry): an entry within 120 ms of the last
  // crossing is the same crossing (entries into the next joint came at least 215 ms later).
  const thx::test::MortarMap mortar(kScene);
  std::int64_t origin = -1;
  std::vector<double> crossings;  // s from the WAV's first sample (the first THX_CONTACT)
  bool in_mortar = false, was_in_contact = false;
  double first_contact = -1, last_contact = 0;
  thx_msgs::forEachLogMessage<thx_msgs::contact_t>(path("session.lcm"), "THX_CONTACT", [&](const auto& c, const auto&) {
    if (origin < 0) origin = c.utime;
    const double t = double(c.utime - origin) * 1e-6;
    if (!c.in_contact) {
      was_in_contact = false;
      return;
    }
    const bool in_joint = mortar.isMortar(c.texel_i, c.texel_j);
    if (in_joint && !in_mortar && was_in_contact && (crossings.empty() || t - crossings.back() > 0.12)) crossings.push_back(t);
    in_mortar = in_joint, was_in_contact = true;
    if (first_contact < 0) first_contact = t;
    last_contact = t;
  });
  ASSERT_GE(first_contact, 0.0) << "the pen never touched the surface";
  ASSERT_GE(crossings.size(), 12u) << "the stroke crosses 7 bed joints each way";

  // 4. The onsets in the WAV. One joint is more than one click: the drop in, and the climb over
  // the far wall 30-190 ms later (the pen caught there until the grip spring pulls it over; the
  // longest at the end of a stroke); the drop-ins come at least 219 ms apart. So onsets closer
  // than 200 ms are one.
  const std::vector<double> onsets = thx::test::wavOnsets(path("scrape.wav"), 0.2);
  ASSERT_FALSE(onsets.empty()) << "no sound in " << path("scrape.wav");
  thx::test::printRates(crossings, onsets, last_contact - first_contact);  // while in contact
  if (std::getenv("THX_DEBUG_ONSETS")) {
    for (double c : crossings) std::printf("crossing %.4f\n", c);
    for (double t : onsets) std::printf("onset %.4f\n", t);
  }
  EXPECT_NEAR(double(onsets.size()) / double(crossings.size()), 1.0, 0.05);
  // Each onset at a crossing: the drop-in click starts as the tip goes over the joint's edge,
  // before it reaches the half-depth texels (5-20 ms before; 40 ms is 3.2 mm at 0.08 m/s, about
  // the joint's width; a frame is 4 ms).
  EXPECT_EQ(thx::test::onsetsAtCrossings(onsets, crossings, 0.040, 0.025), onsets.size());
}

}  // namespace

}  // namespace test_pen_scrape_onsets
