// The shipped marble-on-bricks check (issue 14), as a user runs it: hapticd records a session of
// scenes/marble_rolling_bricks.yaml, physics-client adds its streams to it on the same clock,
// audio-client renders the combined log twice (byte-identical WAVs), and the clicks detected in
// the WAV (tests/support/onset_detector.hpp) come at the rate, and at the times, the marble's
// texel path crossed mortar (docs/audio.md §12).
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include <thx_msgs/contact_t.hpp>
#include <thx_msgs/physics_contacts_t.hpp>
#include <thx_msgs/physics_impact_t.hpp>

#include "tests/support/rendered_sound.hpp"
#include "thx_msgs/log_reader.hpp"

namespace test_marble_onsets {

namespace {

const std::string kScene = std::string(THX_SOURCE_DIR) + "/scenes/marble_rolling_bricks.yaml";

class MarbleOnBricks : public thx::test::SessionTest {};

TEST_F(MarbleOnBricks, OnsetsInTheWavComeAtTheMortarCrossingsOfTheTexelPath) {
  // 1. The combined session: hapticd's (the pen held off the surface) with the physics streams.
  ASSERT_EQ(recordSession(kScene, "--duration 1.5"), 0);
  ASSERT_EQ(run(std::string(THX_PHYSICS_CLIENT) + " --scene " + kScene + " --replay-log " + path("session.lcm") +
                " --record " + path("combined.lcm") + " --no-lcm --quiet > " + path("physics.out")),
            0);
  // 2. Rendered twice (the second from the modal cache): the same bytes. A small slab keeps it fast:
  // 4 x 4 cells, the shipped 2 through the thickness. (Before the listener of docs/audio.md §9a
  // this needed 1 layer: with 2, the basis the solve gave the slab's repeated modes made one of
  // the 30 onsets come 17 ms early in the sanitizer tree.)
  const std::string render = std::string(THX_AUDIO_CLIENT) + " --scene " + kScene + " --replay-log " + path("combined.lcm") +
                             " --slab-cells 4 --object-elements tet4 --cache-dir " + path("cache") + " --wav ";
  ASSERT_EQ(run(render + path("a.wav") + " > " + path("audio.out") + " 2>&1"), 0) << fileBytes(path("audio.out"));
  // In another second of wall-clock time: nothing of the time of rendering may reach the file.
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  ASSERT_EQ(run(render + path("b.wav") + " > /dev/null 2>&1"), 0);
  const std::string a = fileBytes(path("a.wav"));
  ASSERT_GT(a.size(), 1000u);
  EXPECT_TRUE(a == fileBytes(path("b.wav"))) << "two renders of one session differ";
  std::printf("%s", fileBytes(path("audio.out")).c_str());

  // 3. The mortar crossings the physics client reported: entries of the marble's texel path into
  // mortar, a texel whose relief (the same generator as a relief map) lies deeper than halfway
  // between the highest brick face and the joints' floor.
  const thx::test::MortarMap mortar_map(kScene);
  auto isMortar = [&](int i, int j) { return mortar_map.isMortar(i, j); };
  std::int64_t origin = -1;
  thx_msgs::forEachLogMessage<thx_msgs::contact_t>(path("combined.lcm"), "THX_CONTACT", [&](const auto& c, const auto&) {
    if (origin < 0) origin = c.utime;
  });
  ASSERT_GE(origin, 0);
  std::vector<double> crossings;  // s from the WAV's first sample
  bool in_mortar = false, started = false;
  double last_t = 0;
  thx_msgs::forEachLogMessage<thx_msgs::physics_contacts_t>(path("combined.lcm"), "THX_PHYSICS_CONTACTS", [&](const auto& m, const auto&) {
    for (int k = 0; k < m.num_contacts; ++k) {
      if (m.body_a[k] != 0 || m.body_b[k] != thx_msgs::physics_contacts_t::BODY_SURFACE) continue;
      for (int e = m.path_start[k]; e < m.path_start[k] + m.num_texels[k]; ++e) {
        const auto& t = m.path[std::size_t(e)];
        const bool mortar = isMortar(t.i, t.j);
        const double when = double(m.utime - origin) * 1e-6 + (t.t - m.sim_time);
        if (mortar && !in_mortar && started) crossings.push_back(when);
        in_mortar = mortar;
        started = true;
        last_t = when;
      }
    }
  });
  ASSERT_GE(crossings.size(), 20u) << "the marble should cross a bed joint every 67 ms";

  // 4. The onsets in the WAV. One joint is the clicks of its trough (Eq. 5) and, on this normal
  // map, the landing of the hop the far wall gives the marble (physics_impact_t 13-19 ms after the
  // path enters the mortar): all within 40 ms, while joints come at least 67 ms apart. So onsets
  // closer than 40 ms are one.
  const std::vector<double> onsets = thx::test::wavOnsets(path("a.wav"), 0.04);
  ASSERT_FALSE(onsets.empty()) << "no sound in " << path("a.wav");
  thx::test::printRates(crossings, onsets, last_t);  // both rates over the marble's whole path
  EXPECT_NEAR(double(onsets.size()) / double(crossings.size()), 1.0, 0.05);
  if (std::getenv("THX_DEBUG_ONSETS")) {
    for (double c : crossings) std::printf("crossing %.4f\n", c);
    for (double t : onsets) std::printf("onset %.4f\n", t);
    thx_msgs::forEachLogMessage<thx_msgs::physics_impact_t>(path("combined.lcm"), "THX_PHYSICS_IMPACT", [&](const auto& m, const auto&) {
      std::printf("impact %.4f %.3g N s at %.3g m/s\n", double(m.utime - origin) * 1e-6, m.impulse, m.v_approach);
    });
  }
  // Each onset at a crossing: at most 10 ms before the path entered mortar (the trough's slope,
  // which clicks, begins 0.75 mm = 2.5 ms before its half-depth texels; a frame is 4 ms) and 25 ms
  // after (the landing).
  EXPECT_EQ(thx::test::onsetsAtCrossings(onsets, crossings, 0.010, 0.025), onsets.size());
}

// Bad input: a clear error naming the option or file.
TEST_F(MarbleOnBricks, BadOptionsAndLogsAreNamed) {
  const std::string bin = THX_AUDIO_CLIENT;
  EXPECT_EQ(run(bin + " --scene " + kScene + " --replay-log x.lcm --wav x.wav --object-elements tet7 2> " + path("err1")), 2);
  EXPECT_NE(fileBytes(path("err1")).find("--object-elements: expected tet4 or tet10, got 'tet7'"), std::string::npos)
      << fileBytes(path("err1"));
  {  // a log with neither hapticd's nor the physics client's streams
    lcm::LogFile log(path("other.lcm"), "w");
    ASSERT_TRUE(log.good());
    char byte = 0;
    lcm::LogEvent e{};
    e.channel = "SOMETHING_ELSE";
    e.datalen = 1;
    e.data = &byte;
    ASSERT_EQ(log.writeEvent(&e), 0);
  }
  EXPECT_EQ(run(bin + " --scene " + kScene + " --replay-log " + path("other.lcm") + " --wav " + path("x.wav") + " 2> " +
                path("err2")),
            1);
  EXPECT_NE(fileBytes(path("err2")).find("other.lcm: no THX_CONTACT or THX_PHYSICS_* events"), std::string::npos)
      << fileBytes(path("err2"));
}

}  // namespace

}  // namespace test_marble_onsets
