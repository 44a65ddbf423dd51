// HandScript over a curved surface (device/surface_height.hpp): a flat source reproduces the
// plane, the contact follows an analytic dome's height with its rate of change, hovering stays
// above the top, off the footprint the contact is at z = 0, and the simulated PHANToM samples its
// script on the configured surface.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "device/hand_script.hpp"
#include "device/sim_phantom.hpp"
#include "device/surface_height.hpp"

namespace test_hand_script_height {

using namespace thx::dev;

namespace {

// h = 0 everywhere, top 0: the plane as a height source.
class FlatHeight final : public SurfaceHeight {
 public:
  bool heightAt(const Eigen::Vector2d&, double& z_m) const override {
    z_m = 0.0;
    return true;
  }
  double top() const override { return 0.0; }
};

// A dome: the part above z = 0 of a sphere of radius R about (0, 0, -depth); nothing under a
// point off its footprint (radius sqrt(R^2 - depth^2)).
class DomeHeight final : public SurfaceHeight {
 public:
  static constexpr double kR = 0.04, kDepth = 0.02;
  bool heightAt(const Eigen::Vector2d& xy, double& z_m) const override {
    const double z = std::sqrt(std::max(0.0, kR * kR - xy.squaredNorm())) - kDepth;
    if (!(z >= 0.0)) return false;
    z_m = z;
    return true;
  }
  double top() const override { return kR - kDepth; }
  static double height(const Eigen::Vector2d& xy) { return std::sqrt(kR * kR - xy.squaredNorm()) - kDepth; }
  // dh/dt along the horizontal velocity v: grad h . v, grad h = -xy / sqrt(R^2 - |xy|^2).
  static double rate(const Eigen::Vector2d& xy, const Eigen::Vector2d& v) {
    return -xy.dot(v) / std::sqrt(kR * kR - xy.squaredNorm());
  }
};

// h = a + g . xy everywhere; a declared top.
class TiltedHeight final : public SurfaceHeight {
 public:
  static constexpr double kA = 0.01, kGx = 0.3, kGy = -0.2, kTop = 0.03;
  bool heightAt(const Eigen::Vector2d& xy, double& z_m) const override {
    z_m = kA + kGx * xy.x() + kGy * xy.y();
    return true;
  }
  double top() const override { return kTop; }
};

class NanTop final : public SurfaceHeight {
 public:
  bool heightAt(const Eigen::Vector2d&, double&) const override { return false; }
  double top() const override { return std::nan(""); }
};

HandScript exampleScript() {
  HandPath path;
  path.samples = {{0.0, {0.0, 0.0}, 1.0}, {0.5, {0.01, 0.0}, 2.0}, {1.0, {0.01, 0.01}, 2.0}};
  return HandScript({HandHold{0.5}, HandStroke{{-0.02, 0.0}, {0.02, 0.0}, 0.05, 1.0}, HandPress{{0.0, 0.01}, 1.5, 1.0},
                     path});
}

// The velocity equals the derivative of the position everywhere on the timeline (central
// difference over dt), and the position never jumps.
void expectVelocityIsTheDerivative(const HandScript& s, const SurfaceHeight& height) {
  const double dt = 1e-4;
  double max_vz = 0.0;
  for (double t = 0.0; t < s.duration() + 0.1; t += 7 * dt) {
    const HandTarget h = s.sampleLocal(t, &height);
    const HandTarget before = s.sampleLocal(t - dt, &height), after = s.sampleLocal(t + dt, &height);
    const Eigen::Vector3d numeric = (after.p_m - before.p_m) / (2 * dt);
    ASSERT_LT(std::abs(numeric.z() - h.v_m_per_s.z()), 2e-4) << "z velocity at t = " << t;
    ASSERT_LT((numeric - h.v_m_per_s).norm(), 2e-3) << "velocity at t = " << t;
    max_vz = std::max(max_vz, std::abs(h.v_m_per_s.z()));
  }
  EXPECT_GT(max_vz, 0.01);  // the grid did see height changes
}

}  // namespace

TEST(HandScriptHeight, NullSourceIsThePlaneAndAFlatSourceMatchesIt) {
  const HandScript s = exampleScript();
  const FlatHeight flat;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(0.01, -0.02, 0.03);
  for (double t = -0.01; t < s.duration() + 0.2; t += 1.3e-3) {
    const HandTarget plane = s.sampleLocal(t), none = s.sampleLocal(t, nullptr), on_flat = s.sampleLocal(t, &flat);
    // nullptr: the very same numbers.
    ASSERT_EQ(none.p_m, plane.p_m) << t;
    ASSERT_EQ(none.v_m_per_s, plane.v_m_per_s) << t;
    ASSERT_EQ(none.push_n, plane.push_n) << t;
    ASSERT_EQ(none.pressing, plane.pressing) << t;
    const HandTarget world = s.sample(t, pose), world_none = s.sample(t, pose, nullptr);
    ASSERT_EQ(world_none.p_m, world.p_m) << t;
    ASSERT_EQ(world_none.v_m_per_s, world.v_m_per_s) << t;
    // A flat source: the plane to rounding; x, y, the push and the button untouched.
    ASSERT_LT((on_flat.p_m - plane.p_m).norm(), 1e-15) << t;
    ASSERT_LT((on_flat.v_m_per_s - plane.v_m_per_s).norm(), 1e-13) << t;
    ASSERT_EQ(Eigen::Vector2d(on_flat.p_m.head<2>()), Eigen::Vector2d(plane.p_m.head<2>())) << t;
    ASSERT_EQ(on_flat.push_n, plane.push_n) << t;
    ASSERT_EQ(on_flat.pressing, plane.pressing) << t;
  }
}

TEST(HandScriptHeight, StrokeFollowsADomeWithItsHeightRate) {
  const HandScriptOptions o;
  const DomeHeight dome;
  const Eigen::Vector2d from(-0.02, 0.004), to(0.02, 0.004);  // inside the footprint (radius 0.0346)
  const HandScript s({HandStroke{from, to, 0.04, 1.0}});
  const double hover_z = o.hover_height_m + dome.top();
  // Starts and ends hovering above the dome's top, not above z = 0.
  EXPECT_NEAR(s.sampleLocal(0.0, &dome).p_m.z(), hover_z, 1e-15);
  EXPECT_EQ(s.sampleLocal(0.0, &dome).v_m_per_s.z(), 0.0);
  EXPECT_NEAR(s.sampleLocal(s.duration() + 1.0, &dome).p_m.z(), hover_z, 1e-15);
  // Descending: the min-jerk blend from the hover to h at the start point (half way at half time).
  const double h_from = DomeHeight::height(from);
  EXPECT_NEAR(s.sampleLocal(0.5 * o.approach_s, &dome).p_m.z(), 0.5 * (hover_z + h_from), 1e-15);
  EXPECT_NEAR(s.sampleLocal(o.approach_s, &dome).p_m.z(), h_from, 1e-15);

  // The stroke's body: on the dome, the velocity's z its height's rate along the motion.
  const double body_start = o.approach_s + o.force_ramp_s;
  const double body_s = (to - from).norm() / 0.04 + o.stroke_ramp_s;
  double max_rate = 0.0;
  int samples = 0;
  for (double t = body_start; t <= body_start + body_s; t += 2.5e-3, ++samples) {
    const HandTarget h = s.sampleLocal(t, &dome);
    const HandTarget plane = s.sampleLocal(t);
    ASSERT_EQ(Eigen::Vector2d(h.p_m.head<2>()), Eigen::Vector2d(plane.p_m.head<2>())) << t;
    ASSERT_EQ(Eigen::Vector2d(h.v_m_per_s.head<2>()), Eigen::Vector2d(plane.v_m_per_s.head<2>())) << t;
    ASSERT_EQ(h.push_n, plane.push_n) << t;
    ASSERT_NEAR(h.p_m.z(), DomeHeight::height(h.p_m.head<2>()), 1e-15) << t;
    const double rate = DomeHeight::rate(h.p_m.head<2>(), h.v_m_per_s.head<2>());
    ASSERT_NEAR(h.v_m_per_s.z(), rate, 1e-5) << t;  // the central difference's error: ~1e-6 m/s here
    max_rate = std::max(max_rate, std::abs(rate));
  }
  EXPECT_GT(samples, 400);
  EXPECT_GT(max_rate, 0.02);  // the dome's slope mattered
  expectVelocityIsTheDerivative(s, dome);
}

TEST(HandScriptHeight, HoldsAndTransitsHoverAboveTheTop) {
  const HandScriptOptions o;
  const TiltedHeight tilted;
  const HandScript s({HandPress{{0.01, 0.0}, 1.0, 0.3}, HandHold{0.4}, HandPress{{-0.03, 0.02}, 1.0, 0.3}});
  const double hover_z = o.hover_height_m + TiltedHeight::kTop;
  const double first_end = 2 * o.approach_s + 2 * o.force_ramp_s + 0.3;
  // The hold and the transit after it: hovering at the top's hover height, no vertical motion.
  int hovering = 0;
  for (double t = first_end + 1e-6; t < first_end + 0.4 + o.min_transit_s; t += 1e-3, ++hovering) {
    const HandTarget h = s.sampleLocal(t, &tilted);
    ASSERT_EQ(h.p_m.z(), hover_z) << t;
    ASSERT_EQ(h.v_m_per_s.z(), 0.0) << t;
    ASSERT_FALSE(h.pressing) << t;
  }
  EXPECT_GT(hovering, 400);
  // Pressing: on the tilted plane at each press point.
  const HandTarget first = s.sampleLocal(o.approach_s + o.force_ramp_s + 0.15, &tilted);
  EXPECT_NEAR(first.p_m.z(), TiltedHeight::kA + TiltedHeight::kGx * 0.01, 1e-15);
  EXPECT_EQ(first.v_m_per_s.z(), 0.0);
  EXPECT_TRUE(first.pressing);
  const HandTarget last = s.sampleLocal(s.duration() - o.approach_s - o.force_ramp_s - 0.15, &tilted);
  EXPECT_NEAR(last.p_m.z(), TiltedHeight::kA - TiltedHeight::kGx * 0.03 + TiltedHeight::kGy * 0.02, 1e-15);
  expectVelocityIsTheDerivative(s, tilted);
}

TEST(HandScriptHeight, PathOnATiltedPlaneHasTheExactHeightRate) {
  const HandScriptOptions o;
  const TiltedHeight tilted;
  HandPath path;
  path.samples = {{0.0, {0.0, 0.0}, 1.0}, {0.5, {0.01, 0.0}, 2.0}, {1.0, {0.01, 0.01}, 2.0}};
  const HandScript s({path});
  const double body_start = o.approach_s + o.force_ramp_s;
  for (double tau : {0.1, 0.25, 0.6, 0.9}) {
    const HandTarget h = s.sampleLocal(body_start + tau, &tilted);
    const Eigen::Vector2d v = h.v_m_per_s.head<2>();
    EXPECT_NEAR(h.p_m.z(), TiltedHeight::kA + TiltedHeight::kGx * h.p_m.x() + TiltedHeight::kGy * h.p_m.y(), 1e-15);
    EXPECT_NEAR(h.v_m_per_s.z(), TiltedHeight::kGx * v.x() + TiltedHeight::kGy * v.y(), 1e-12) << tau;
    EXPECT_GT(v.norm(), 0.019);
  }
  // (Its velocity steps at the samples, as on the plane: no derivative check on a grid.)
}

TEST(HandScriptHeight, OffTheFootprintTheContactIsAtZero) {
  const HandScriptOptions o;
  const DomeHeight dome;  // footprint radius sqrt(0.04^2 - 0.02^2) = 0.0346
  const HandScript s({HandStroke{{0.02, 0.0}, {0.05, 0.0}, 0.05, 1.0}});
  const double body_start = o.approach_s + o.force_ramp_s;
  int on = 0, off = 0;
  for (double t = body_start; t <= body_start + 0.03 / 0.05 + o.stroke_ramp_s; t += 1e-3) {
    const HandTarget h = s.sampleLocal(t, &dome);
    double z = 0.0;
    if (dome.heightAt(h.p_m.head<2>(), z)) {
      ++on;
      ASSERT_EQ(h.p_m.z(), z) << t;
    } else {
      ++off;
      ASSERT_EQ(h.p_m.z(), 0.0) << t;
      // Clear of the rim by more than the slope step: flat ground.
      if (h.p_m.x() > 0.035 + HandScript::kHeightSlopeStepM) {
        ASSERT_EQ(h.v_m_per_s.z(), 0.0) << t;
      }
    }
  }
  EXPECT_GT(on, 100);
  EXPECT_GT(off, 100);
  // The press ends on the ground, then ascends to the hover above the top.
  EXPECT_EQ(s.sampleLocal(s.duration() - o.approach_s, &dome).p_m.z(), 0.0);
  EXPECT_NEAR(s.sampleLocal(s.duration(), &dome).p_m.z(), o.hover_height_m + dome.top(), 1e-15);
}

TEST(HandScriptHeight, SimPhantomSamplesItsScriptOnTheConfiguredSurface) {
  const DomeHeight dome;
  const HandScript script({HandStroke{{-0.01, 0.0}, {0.01, 0.005}, 0.05, 0.5}});
  SimPhantomConfig c;
  c.plane_to_world.linear() = Eigen::AngleAxisd(std::numbers::pi / 5, Eigen::Vector3d::UnitY()).toRotationMatrix();
  c.plane_to_world.translation() = Eigen::Vector3d(0.0, 0.01, -0.02);
  c.surface_height = &dome;
  SimPhantom sim(c, script);
  sim.open();
  // At rest under the hand hovering above the dome's top.
  EXPECT_TRUE(sim.truth().p_world_m.isApprox(c.plane_to_world * Eigen::Vector3d(-0.01, 0.0, 0.005 + dome.top())));
  double lowest_local_z = 1.0;
  while (sim.truth().t_s < 1.0) {  // to the ascent after the stroke
    sim.read();
    sim.write(DeviceCommand{});
    const HandTarget expected = script.sample(sim.truth().t_s, c.plane_to_world, &dome);
    ASSERT_EQ(sim.truth().hand_target_world.p_m, expected.p_m);
    ASSERT_EQ(sim.truth().hand_target_world.v_m_per_s, expected.v_m_per_s);
    lowest_local_z = std::min(lowest_local_z, (c.plane_to_world.inverse() * expected.p_m).z());
  }
  EXPECT_NEAR(lowest_local_z, DomeHeight::height({0.01, 0.005}), 1e-12);  // the stroke ends lowest
}

TEST(HandScriptHeight, SimConfigRejectsANonFiniteTop) {
  const NanTop nan_top;
  SimPhantomConfig c;
  c.surface_height = &nan_top;
  try {
    validate(c);
    ADD_FAILURE() << "no error";
  } catch (const DeviceError& e) {
    EXPECT_EQ(std::string(e.what()),
              "SimPhantomConfig.surface_height: top not finite; expected a surface whose highest point is finite, got "
              "'nan'");
  }
}

}  // namespace test_hand_script_height
