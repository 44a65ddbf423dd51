// What a simulated participant hears and sees (docs/study.md §6.1): the sound features of known
// samples, the audio client's synthesis against what the physics predicts (pitch goes as √E,
// mass-proportional damping rings for 3 ln 10 / (α/2) whatever the stiffness), a muted scene
// silent; the ball's slip telling a sliding launch from a rolling one, and no ball nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <vector>

#include "clients/study/ball_percept.hpp"
#include "clients/study/sound_percept.hpp"
#include "scenes/scene_loader.hpp"
#include "tests/support/temp_dir.hpp"

namespace thx::study::test_percepts {
namespace {

const std::string kBricks = THX_TEST_DATA_DIR "/study/identification/bricks_small.yaml";

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void writeText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(SoundFeatures, OneModeGivesItsFrequencyAndItsT60) {
  const double fs = 44100.0, f = 1000.0, d = 20.0;
  std::vector<double> x(std::size_t(2.0 * fs));
  for (std::size_t n = 0; n < x.size(); ++n) {
    const double t = double(n) / fs;
    x[n] = std::exp(-d * t) * std::sin(2.0 * std::numbers::pi * f * t);
  }
  const auto p = soundFeatures(x, fs);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->pitch_log10_hz, 3.0, 1e-3);
  EXPECT_NEAR(p->ring_log10_s, std::log10(3.0 * std::log(10.0) / d), 0.01);
  EXPECT_FALSE(soundFeatures(std::vector<double>(100, 0.0), fs));
}

TEST(SoundPercept, FourTimesTheStiffnessSoundsAnOctaveUpAndRingsAsLong) {
  test::TempDir dir("study_sound");
  // Mass-proportional damping only (β = 0): every mode decays at d = α / 2, so the ring is
  // 3 ln 10 / d whatever E is, and the modes' weights do not change with E: the pitch goes as √E.
  // Soft enough that all 12 modes stay in the audible band at both stiffnesses (a mode pushed
  // above 20 kHz is dropped, and the pitch with it).
  const std::string materials =
      "materials:\n"
      "  - {name: tile_a, density: 1900, youngs_modulus: 1.0e9, poisson_ratio: 0.18, rayleigh_alpha: 30}\n"
      "  - {name: tile_b, density: 1900, youngs_modulus: 4.0e9, poisson_ratio: 0.18, rayleigh_alpha: 30}\n";
  const std::string text = readText(kBricks);
  writeText(dir.file("a.yaml"), replaced(text, "material: brick", "material: tile_a") + materials);
  writeText(dir.file("b.yaml"), replaced(text, "material: brick", "material: tile_b") + materials);
  const auto a = hearSurface(dir.file("a.yaml"));
  const auto b = hearSurface(dir.file("b.yaml"));
  ASSERT_TRUE(a && b);
  std::printf("pitch %.4f -> %.4f, ring %.4f and %.4f (log10)\n", a->pitch_log10_hz, b->pitch_log10_hz, a->ring_log10_s,
              b->ring_log10_s);
  // Measured 0.2976: the damped frequencies √(ω² − d²) and the RMS frequency's weighting of the
  // decay keep it a little below log10 2.
  EXPECT_NEAR(b->pitch_log10_hz - a->pitch_log10_hz, std::log10(2.0), 0.01);
  const double t60 = std::log10(3.0 * std::log(10.0) / 15.0);
  EXPECT_NEAR(a->ring_log10_s, t60, 0.02);
  EXPECT_NEAR(b->ring_log10_s, t60, 0.02);
}

TEST(SoundPercept, AMutedSceneIsHeardAsNothing) {
  test::TempDir dir("study_sound");
  ASSERT_TRUE(hearSurface(kBricks));
  writeText(dir.file("muted.yaml"), readText(kBricks) + "audio: {mute: true}\n");
  EXPECT_FALSE(hearSurface(dir.file("muted.yaml")));
}

TEST(BallPercept, ASlidingLaunchSlipsARollingOneDoesNot) {
  // On a flat, nearly frictionless surface (μ 0.005 against the glass's) a ball set down without
  // spin slides for about a quarter of a second before friction has it rolling
  // (t = 2 v / (7 μ g)); one set down already rolling (ω = n × v / r) never slides. (On the
  // bricks it would: every joint it drops into costs it its rolling, and so little friction
  // takes long to restore it.)
  test::TempDir dir("study_ball");
  std::string text = replaced(readText(kBricks), "material: brick", "material: slippery");
  text = replaced(text, "generator: bricks", "generator: tilted");
  text = replaced(text, "    seed: 5\n", "");
  text = replaced(text,
                  "params: {extent: 0.1, brick_length: 0.025, brick_height: 0.0125, mortar: 0.003, mortar_depth: 0.001, "
                  "jitter: 0}",
                  "params: {extent: 0.1, angle_deg: 0}");
  writeText(dir.file("slippery.yaml"), text + "materials:\n  - {name: slippery, density: 1900, youngs_modulus: 1.5e10, "
                                              "poisson_ratio: 0.18, friction: 0.005}\n");
  scene::Scene sliding = scene::loadScene(dir.file("slippery.yaml"));
  ASSERT_FALSE(sliding.objects.empty());
  scene::Scene rolling = sliding;
  for (scene::Scene* s : {&sliding, &rolling}) {
    scene::SceneObject& ball = s->objects[0];
    ball.pose.position_m.z() = ball.radius_m + 1e-4;
    ball.velocity_m_per_s = {-0.04, 0.0, 0.0};
  }
  rolling.objects[0].angular_velocity_rad_per_s = {0.0, -0.04 / rolling.objects[0].radius_m, 0.0};
  const auto s = watchBall(sliding);
  const auto r = watchBall(rolling);
  ASSERT_TRUE(s && r);
  std::printf("slip: sliding launch %.4f, rolling launch %.4f\n", s->slip, r->slip);
  EXPECT_GT(s->slip, 0.05);
  EXPECT_GT(s->slip, 5.0 * r->slip);
  EXPECT_NEAR(s->watched_s, kBallWatchS, 1e-9);
}

TEST(BallPercept, NoBallNothingToWatch) {
  scene::Scene sc = scene::loadScene(kBricks);
  sc.objects.clear();
  EXPECT_FALSE(watchBall(sc));
}

}  // namespace
}  // namespace thx::study::test_percepts
