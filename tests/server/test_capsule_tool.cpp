// The pen with extent (issue 30): a capsule's contacts with a textured plane, the coupling's solver,
// and the tool against analytic answers: a shaft lying across two parallel ridges carries each
// ridge's share of the force by the lever rule, and the torque about its centre is that lever's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>

#include "device/device_specs.hpp"
#include "server/capsule_tool.hpp"
#include "textures/generators.hpp"
#include "textures/height_normals.hpp"

namespace test_capsule_tool {

using namespace thx;
using srv::CapsuleTool;
using srv::CapsuleToolConfig;

namespace {

constexpr int kTexels = 512;
constexpr double kTexel = 0.25e-3;  // 128 mm square
constexpr double kRidgeHeight = 2e-3;

double texelCentreX(int i) { return (i + 0.5) * kTexel - 0.5 * kTexels * kTexel; }

// Two ridges along y, 45 degree walls, crests on texel centres (their x: texelCentreX(i1), (i2)).
tex::TextureMap twoRidges(int i1, int i2) {
  tex::HeightField h(kTexels, kTexels, 0.0);
  for (int j = 0; j < kTexels; ++j)
    for (int i = 0; i < kTexels; ++i) {
      const double x = texelCentreX(i);
      const double d = std::min(std::abs(x - texelCentreX(i1)), std::abs(x - texelCentreX(i2)));
      h.at(i, j) = std::max(0.0, kRidgeHeight - d);
    }
  tex::ReliefFromHeightOptions o;
  o.texel_m = {kTexel, kTexel};
  return tex::reliefFromHeight(h, o);
}

tex::PlaneMapping squareMapping() {
  tex::PlaneMapping m;
  m.size_m = {kTexels * kTexel, kTexels * kTexel};
  return m;
}

// The pen lying along -x from its tip (the identity holds it upright along +z).
Eigen::Quaterniond lyingAlongMinusX() { return Eigen::Quaterniond(Eigen::AngleAxisd(-std::numbers::pi / 2, Eigen::Vector3d::UnitY())); }

dev::DeviceState deviceAt(const Eigen::Vector3d& centre, const Eigen::Quaterniond& q, double length) {
  dev::DeviceState s;
  s.q_world = q;
  s.p_world = centre - 0.5 * length * (q * Eigen::Vector3d::UnitZ());
  return s;
}

CapsuleToolConfig toolConfig() {
  CapsuleToolConfig c;
  c.length_m = 0.10;
  c.radius_m = 0.002;
  c.stiffness_n_per_m = 600.0;
  c.rot_stiffness_nm_per_rad = 0.5;
  c.ramp_ticks = 10;
  return c;
}

}  // namespace

TEST(CapsuleContacts, AShaftAboveAFlatReliefTouchesOnlyWithinItsRadius) {
  tex::HeightField flat(64, 64, 0.0);
  tex::ReliefFromHeightOptions o;
  o.texel_m = {1e-3, 1e-3};
  const tex::TextureMap map = tex::reliefFromHeight(flat, o);
  tex::PlaneMapping m;
  m.size_m = {0.064, 0.064};
  const tex::TexturedSurface surface(map, m, {}, true);
  srv::ToolContacts contacts;
  srv::CapsuleShape cap{{-0.0105, 0.0005, 0.0015}, {0.0095, 0.0005, 0.0015}, 0.002};  // 0.5 mm into z = 0
  srv::findCapsuleContacts(surface, cap, 0.0, contacts);
  ASSERT_GT(contacts.count, 0);
  double deepest = 0.0;
  for (int k = 0; k < contacts.count; ++k) {
    const srv::ToolContact& c = contacts.c[std::size_t(k)];
    EXPECT_LT(c.gap_m, 0.0);
    EXPECT_NEAR(c.point.z(), 0.0, 1e-12);
    deepest = std::min(deepest, c.gap_m);
  }
  EXPECT_NEAR(deepest, -0.0005, 1e-12);  // the texel row right under the axis
  cap.a.z() = cap.b.z() = 0.0025;        // 0.5 mm clear
  srv::findCapsuleContacts(surface, cap, 0.0, contacts);
  EXPECT_EQ(contacts.count, 0);
  srv::findCapsuleContacts(surface, cap, 0.001, contacts);  // within a margin of 1 mm: the near rows
  EXPECT_GT(contacts.count, 0);
  for (int k = 0; k < contacts.count; ++k) EXPECT_GE(contacts.c[std::size_t(k)].gap_m, 0.0005 - 1e-12);
}

TEST(CapsuleContacts, ANormalMapIsTheFlatPlaneWithItsSampledNormals) {
  const tex::TextureMap map(16, 16, tex::Representation::Normal);
  tex::PlaneMapping m;
  m.size_m = {0.016, 0.016};
  const tex::TexturedSurface surface(map, m, {}, false);
  srv::ToolContacts contacts;
  const srv::CapsuleShape upright{{0.001, 0.002, 0.0015}, {0.001, 0.002, 0.1015}, 0.002};
  srv::findCapsuleContacts(surface, upright, 0.0, contacts);
  ASSERT_EQ(contacts.count, 1);  // only the tip's ball reaches the plane
  EXPECT_NEAR(contacts.c[0].gap_m, -0.0005, 1e-12);
  EXPECT_TRUE(contacts.c[0].point.isApprox(Eigen::Vector3d(0.001, 0.002, 0.0), 1e-12));
}

// The block heights only skip texels that cannot be within reach: the same contacts (and the same
// nearest distance) with and without them, for capsules in random poses over bricks and valleys.
TEST(CapsuleContacts, SkippingBlocksOutOfReachFindsTheSameContacts) {
  for (const char* kind : {"bricks", "vvalley"}) {
    tex::GenerateRequest req;
    req.kind = kind;
    req.size = 256;
    req.params = {{"extent", 0.05}};
    const tex::TextureMap map = tex::generate(req);
    tex::PlaneMapping m;
    m.size_m = {0.05, 0.05};
    const tex::TexturedSurface surface(map, m, {}, true);
    const srv::ReliefBlockHeights blocks(surface);
    ASSERT_FALSE(blocks.empty());
    std::uint64_t state = 12345;
    auto uniform = [&](double lo, double hi) {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      return lo + (hi - lo) * double(state >> 11) / double(1ULL << 53);
    };
    int with_contacts = 0, skipped = 0;
    for (int k = 0; k < 300; ++k) {
      const Eigen::Vector3d a(uniform(-0.03, 0.03), uniform(-0.03, 0.03), uniform(-0.004, 0.003));
      const Eigen::Vector3d dir = Eigen::Vector3d(uniform(-1, 1), uniform(-1, 1), uniform(-0.3, 1)).normalized();
      const srv::CapsuleShape cap{a, a + uniform(0.0, 0.04) * dir, uniform(0.0005, 0.003)};
      const double margin = uniform(0.0, 0.002);
      srv::ToolContacts plain, fast;
      srv::findCapsuleContacts(surface, cap, margin, plain);
      srv::findCapsuleContacts(surface, cap, margin, fast, &blocks);
      ASSERT_EQ(plain.count, fast.count) << kind << " pose " << k;
      EXPECT_EQ(plain.nearest_gap_m >= margin, fast.nearest_gap_m >= margin) << kind << " pose " << k;
      if (plain.nearest_gap_m < margin) {
        EXPECT_EQ(plain.nearest_gap_m, fast.nearest_gap_m) << kind << " pose " << k;
      }
      for (int c = 0; c < plain.count; ++c) {
        EXPECT_EQ(plain.c[std::size_t(c)].point, fast.c[std::size_t(c)].point);
        EXPECT_EQ(plain.c[std::size_t(c)].gap_m, fast.c[std::size_t(c)].gap_m);
      }
      with_contacts += plain.count > 0;
      skipped += fast.texels_examined < plain.texels_examined;
    }
    EXPECT_GT(with_contacts, 30) << kind;  // the poses do touch
    EXPECT_GT(skipped, 30) << kind;        // and the blocks do skip
  }
}

TEST(CouplingProjection, OneContactStopsTheMotionAtTheSurfaceAndCarriesTheSpringsForce) {
  srv::ToolContacts contacts;
  contacts.count = 1;
  contacts.c[0].point = {0.0, 0.0, 0.0};
  contacts.c[0].normal = Eigen::Vector3d::UnitZ();
  contacts.c[0].gap_m = 0.001;
  const srv::CouplingGains gains{500.0, 0.3};
  const srv::PoseStep s = srv::projectToolMotion({0.0, 0.0, -0.003}, Eigen::Vector3d::Zero(), contacts,
                                                 {0.0, 0.0, 0.0}, gains, {});
  ASSERT_TRUE(s.converged);
  EXPECT_NEAR(s.dx.z(), -0.001, 1e-12);  // down to the surface, no further
  EXPECT_NEAR(s.lambda_n[0], 500.0 * 0.002, 1e-9);  // the spring's 2 mm left over
  // Moving away from the surface leaves it untouched.
  const srv::PoseStep away = srv::projectToolMotion({0.0, 0.0, 0.003}, Eigen::Vector3d::Zero(), contacts,
                                                    {0.0, 0.0, 0.0}, gains, {});
  EXPECT_NEAR(away.dx.z(), 0.003, 1e-15);
  EXPECT_EQ(away.lambda_n[0], 0.0);
}

TEST(CapsuleTool, AnUprightPenPressedIntoAFlatPlaneFeelsTheSpringFromItsBallsSurface) {
  const tex::TextureMap map(16, 16, tex::Representation::Normal);
  tex::PlaneMapping m;
  m.size_m = {0.016, 0.016};
  const tex::TexturedSurface surface(map, m, {}, false);
  CapsuleTool tool(surface, dev::phantomDesktopSpec(), toolConfig());
  dev::DeviceState s;
  s.p_world = {0.001, 0.001, -0.001};  // the tip ball's centre 1 mm under the plane: 3 mm too deep
  srv::ToolOutput out;
  for (int t = 0; t < 20; ++t) out = tool.step(s);
  EXPECT_TRUE(out.in_contact);
  EXPECT_NEAR(out.force_world.z(), 600.0 * 0.003, 1e-9);
  EXPECT_NEAR(out.force_world.head<2>().norm(), 0.0, 1e-12);
  EXPECT_NEAR(out.tool_tip_world.z(), 0.002, 1e-12);  // resting on its ball
  EXPECT_EQ(out.torque_world, Eigen::Vector3d::Zero());  // a Desktop displays no torque
}

TEST(CapsuleTool, TheForceRampsInAndIsClampedToTheDevicesPeak) {
  const tex::TextureMap map(16, 16, tex::Representation::Normal);
  tex::PlaneMapping m;
  m.size_m = {0.016, 0.016};
  const tex::TexturedSurface surface(map, m, {}, false);
  CapsuleToolConfig c = toolConfig();
  c.ramp_ticks = 100;
  const dev::DeviceSpec spec = dev::phantomDesktopSpec();
  CapsuleTool tool(surface, spec, c);
  dev::DeviceState s;
  s.p_world = {0.0, 0.0, 0.002 - 0.003};
  EXPECT_NEAR(tool.step(s).force_world.z(), 0.01 * 600.0 * 0.003, 1e-9);  // 1 / 100 of it
  for (int t = 1; t < 49; ++t) tool.step(s);
  EXPECT_NEAR(tool.step(s).force_world.z(), 0.5 * 600.0 * 0.003, 1e-9);
  s.p_world.z() = 0.002 - 0.5;  // half a metre under: the spring asks for 300 N
  srv::ToolOutput out;
  for (int t = 0; t < 60; ++t) out = tool.step(s);
  EXPECT_NEAR(out.force_world.norm(), spec.peak_force_n, 1e-9);
}

TEST(CapsuleTool, GainsAreCappedByTheDeviceAndTheDampingIsCritical) {
  const tex::TextureMap map(16, 16, tex::Representation::Normal);
  const tex::TexturedSurface surface(map, squareMapping(), {}, false);
  CapsuleToolConfig c = toolConfig();
  c.stiffness_n_per_m = 5000.0;
  c.rot_stiffness_nm_per_rad = 10.0;
  c.device_mass_kg = 0.001;  // critical damping 2 sqrt(1000 x 0.001) = 2 N s/m, under the Desktop's 5
  const CapsuleTool six(surface, dev::simulated6DofSpec(), c);
  EXPECT_EQ(six.stiffness(), dev::simulated6DofSpec().max_stiffness_n_per_m);
  EXPECT_EQ(six.rotStiffness(), dev::simulated6DofSpec().max_rot_stiffness_nm_per_rad);
  EXPECT_NEAR(six.damping(), 2.0, 1e-12);
  EXPECT_NEAR(six.rotDamping(), 2.0 * std::sqrt(2.0 * c.device_inertia_kgm2), 1e-15);
  c.device_mass_kg = 1.0;  // critical would be 63 N s/m: held at the device's limit
  const CapsuleTool heavy(surface, dev::phantomDesktopSpec(), c);
  EXPECT_EQ(heavy.damping(), dev::phantomDesktopSpec().max_damping_ns_per_m);
}

TEST(CapsuleTool, AFreePenFeelsNothingWhileItMoves) {
  const tex::TextureMap map(16, 16, tex::Representation::Normal);
  const tex::TexturedSurface surface(map, squareMapping(), {}, false);
  CapsuleTool tool(surface, dev::simulated6DofSpec(), toolConfig());
  for (int t = 0; t < 200; ++t) {
    const double a = 0.01 * t;
    dev::DeviceState s;
    s.p_world = {0.02 * std::sin(a), 0.01 * t * 1e-3, 0.03};
    s.q_world = Eigen::Quaterniond(Eigen::AngleAxisd(0.3 * std::sin(a), Eigen::Vector3d::UnitX()));
    s.v_world = {0.02 * std::cos(a) * 10.0, 0.01, 0.0};
    s.w_world = {0.3 * std::cos(a) * 10.0, 0.0, 0.0};
    const srv::ToolOutput out = tool.step(s);
    // The tool follows exactly; only the damping of the finite-difference against the device's own
    // velocity remains, and that is what the device reports: the same motion.
    EXPECT_FALSE(out.in_contact);
    EXPECT_LT((out.tool_tip_world - s.p_world).norm(), 1e-12);
  }
}

// A shaft 100 mm long, radius 2 mm, lying across two ridges (crests 55 mm apart, under its back
// and near its tip); the device is pushed 2 mm down and turned nose-down by 0.1 rad. The ridges
// hold the tool where it lies, so the coupling is stretched by exactly that: the device is given
// F = k x 2 mm up and the torque k_rot x 0.1 rad; the ridges share F so that their forces'
// torque about the centre is that torque (a lever: f1 + f2 = F, x1 f1 + x2 f2 = tau).
TEST(CapsuleTool, AShaftAcrossTwoRidgesSharesTheForceByTheLeverAndGivesItsTorque) {
  const int i_back = 100, i_front = 320;
  const tex::TextureMap map = twoRidges(i_back, i_front);
  const tex::TexturedSurface surface(map, squareMapping(), {}, true);
  const CapsuleToolConfig c = toolConfig();
  CapsuleTool tool(surface, dev::simulated6DofSpec(), c);
  const double r = c.radius_m;
  const Eigen::Vector3d centre_rest(-0.005, 0.003125, r);  // axis resting on both crests (z = 0), over a row of texel centres
  const double push = 0.002, tilt = 0.02;
  const Eigen::Quaterniond q_rest = lyingAlongMinusX();
  // Nose down: the tip (at +x) goes down, a turn about +y.
  const Eigen::Quaterniond q_device = Eigen::Quaterniond(Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitY())) * q_rest;
  const dev::DeviceState s = deviceAt(centre_rest - push * Eigen::Vector3d::UnitZ(), q_device, c.length_m);
  srv::ToolOutput out;
  for (int t = 0; t < 40; ++t) out = tool.step(s);

  EXPECT_LT((tool.centreLocal() - centre_rest).norm(), 1e-7);
  EXPECT_LT(out.penetration_m, 1e-7);
  const double F = tool.stiffness() * push;
  const double tau = tool.rotStiffness() * tilt;
  EXPECT_NEAR(out.force_world.z(), F, 0.01 * F);
  EXPECT_NEAR(out.torque_world.y(), -tau, 0.01 * tau);  // the device is turned back nose-up
  // Each ridge's share: x_i are the crests' arms along x from the centre; the torque of an upward
  // force f at arm x about the centre is -x f about y.
  const double x1 = texelCentreX(i_back) - centre_rest.x();
  const double x2 = texelCentreX(i_front) - centre_rest.x();
  // f1 + f2 = F; -(x1 f1 + x2 f2) = torque on the device about y = -tau.
  const double f2 = (tau - x1 * F) / (x2 - x1);
  const double f1 = F - f2;
  double got1 = 0.0, got2 = 0.0;
  const srv::ToolContacts& contacts = tool.solvedContacts();
  for (int k = 0; k < contacts.count; ++k) {
    const double f = tool.lastSolve().lambda_n[std::size_t(k)] * contacts.c[std::size_t(k)].normal.z();
    (contacts.c[std::size_t(k)].point.x() < 0.0 ? got1 : got2) += f;
  }
  EXPECT_NEAR(got1, f1, 0.01 * std::abs(f1)) << "back ridge";
  EXPECT_NEAR(got2, f2, 0.01 * std::abs(f2)) << "front ridge";
  // The torque the device is given is that of the ridges' forces about the centre.
  EXPECT_NEAR(out.contact_torque_world.y(), out.coupling_torque_world.y(), 0.01 * tau);
  EXPECT_NEAR(-(x1 * got1 + x2 * got2), out.torque_world.y(), 0.01 * tau);
}

TEST(CapsuleTool, AForceOnlyDeviceGetsTheForceAndNoTorque) {
  const tex::TextureMap map = twoRidges(100, 320);
  const tex::TexturedSurface surface(map, squareMapping(), {}, true);
  const CapsuleToolConfig c = toolConfig();
  CapsuleTool six(surface, dev::simulated6DofSpec(), c);
  CapsuleTool three(surface, dev::phantomDesktopSpec(), c);
  const Eigen::Quaterniond q = Eigen::Quaterniond(Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitY())) * lyingAlongMinusX();
  const dev::DeviceState s = deviceAt({-0.005, 0.003125, c.radius_m - 0.002}, q, c.length_m);
  srv::ToolOutput a, b;
  for (int t = 0; t < 40; ++t) {
    a = six.step(s);
    b = three.step(s);
  }
  EXPECT_TRUE(a.force_world.isApprox(b.force_world, 1e-9));
  EXPECT_GT(a.torque_world.norm(), 0.009);
  EXPECT_EQ(b.torque_world, Eigen::Vector3d::Zero());
  EXPECT_TRUE(a.coupling_torque_world.isApprox(b.coupling_torque_world, 1e-9));  // reported all the same
}

// The tip's ball pressed hard into a steep V-valley (60 degree opening, 3.46 mm deep) and dragged
// across three of them, the pen held at 45 degrees: the tool never enters the relief (beyond the
// solver's tolerance), rests on both walls of each valley and pops over each crest into the next
// (a tool without mass leaves a crest at once: a tick or three in the air).
TEST(CapsuleTool, TheToolNeverEntersASteepValley) {
  tex::GenerateRequest req;
  req.kind = "vvalley";
  req.size = 512;
  req.params = {{"extent", 0.1}, {"angle_deg", 60.0}, {"period", 0.004}};
  const tex::TextureMap map = tex::generate(req);
  tex::PlaneMapping m;
  m.size_m = {0.1, 0.1};
  const tex::TexturedSurface surface(map, m, {}, true);
  CapsuleToolConfig c = toolConfig();
  c.radius_m = 0.001;
  CapsuleTool tool(surface, dev::simulated6DofSpec(), c);
  const Eigen::Quaterniond pen(Eigen::AngleAxisd(std::numbers::pi / 4, Eigen::Vector3d::UnitY()));
  constexpr int kTicks = 1500;
  double worst = 0.0;
  int touching = 0, crests = 0;
  bool was_touching = false;
  for (int t = 0; t < kTicks; ++t) {
    dev::DeviceState s;
    s.q_world = pen;
    s.p_world = {-0.012 + 8e-6 * t, 0.0, -0.006};  // 6 mm under the top
    const srv::ToolOutput out = tool.step(s);
    worst = std::max(worst, out.penetration_m);
    touching += out.in_contact;
    crests += was_touching && !out.in_contact;
    was_touching = out.in_contact;
    EXPECT_NEAR(out.tool_tip_world.y(), 0.0, 1e-5) << "tick " << t;  // nothing pushes it along the valleys
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_GE(touching, kTicks - 20);
  EXPECT_GE(crests, 2);
}

}  // namespace test_capsule_tool
