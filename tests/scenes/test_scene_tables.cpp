// The data tables (materials, device models) against their references, and the small helpers:
// typo suggestions, VRPN addresses, pose conventions.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scenes/closest_match.hpp"
#include "scenes/device_models.hpp"
#include "scenes/materials.hpp"
#include "scenes/scene_frames.hpp"
#include "scenes/vrpn_address.hpp"

namespace test_scene_tables {

namespace {

using namespace thx::scene;

TEST(Materials, EveryNamedMaterialIsThereWithPlausibleValues) {
  for (const char* name : {"ceramic", "glass", "wood", "plastic", "polycarbonate", "iron", "steel", "tin", "aluminium",
                           "stone", "brick", "concrete", "porcelain", "granite", "marble", "brass", "copper"}) {
    const Material* m = findMaterial(name);
    ASSERT_NE(m, nullptr) << name;
    EXPECT_GT(m->density_kg_per_m3, 500.0) << name;
    EXPECT_GT(m->youngs_modulus_pa, 1e9) << name;
    EXPECT_GT(m->poisson_ratio, 0.0) << name;
    EXPECT_LT(m->poisson_ratio, 0.5) << name;
    EXPECT_GT(m->rayleigh_alpha_per_s, 0.0) << name;
    EXPECT_GT(m->rayleigh_beta_s, 0.0) << name;
    EXPECT_GT(m->friction, 0.0) << name;
    EXPECT_LE(m->friction, 1.0) << name;
    EXPECT_GT(m->restitution, 0.0) << name;
    EXPECT_LT(m->restitution, 1.0) << name;
    EXPECT_FALSE(m->source.empty()) << name;
  }
  EXPECT_EQ(materials().size(), 17u);
  EXPECT_EQ(findMaterial("unobtainium"), nullptr);
}

TEST(Materials, ValuesFromTheReferenceTable) {  // docs/scenes.md "Materials"
  const Material& steel = *findMaterial("steel");
  EXPECT_EQ(steel.density_kg_per_m3, 7850.0);
  EXPECT_EQ(steel.youngs_modulus_pa, 2.0e11);
  EXPECT_EQ(steel.poisson_ratio, 0.29);
  EXPECT_EQ(steel.rayleigh_alpha_per_s, 5.0);
  EXPECT_EQ(steel.rayleigh_beta_s, 3e-8);
  const Material& wood = *findMaterial("wood");
  EXPECT_EQ(wood.rayleigh_alpha_per_s, 60.0);
  EXPECT_EQ(wood.rayleigh_beta_s, 2e-6);
  const Material& porcelain = *findMaterial("porcelain");
  EXPECT_EQ(porcelain.density_kg_per_m3, 2400.0);
  EXPECT_EQ(porcelain.youngs_modulus_pa, 7.0e10);
  EXPECT_EQ(porcelain.poisson_ratio, 0.17);
  EXPECT_EQ(findMaterial("brass")->youngs_modulus_pa, 1.01e11);
  EXPECT_EQ(findMaterial("granite")->poisson_ratio, 0.213);
  // √(E/ρ) of KleinPAT's glass (4883 m/s), within its rounding.
  EXPECT_NEAR(std::sqrt(findMaterial("glass")->youngs_modulus_pa / findMaterial("glass")->density_kg_per_m3), 4883, 1);
}

TEST(DeviceModels, ChaiTableValues) {  // docs/scenes.md "Device models"
  const DeviceModel& desktop = *findDeviceModel("phantom_desktop");
  EXPECT_EQ(desktop.peak_force_n, 7.9);
  EXPECT_EQ(desktop.max_stiffness_n_per_m, 1000.0);
  EXPECT_EQ(desktop.max_damping_ns_per_m, 5.0);
  EXPECT_EQ(desktop.workspace_radius_m, 0.10);
  EXPECT_EQ(findDeviceModel("touch")->max_stiffness_n_per_m, 400.0);
  EXPECT_EQ(findDeviceModel("touch")->workspace_radius_m, 0.075);
  EXPECT_EQ(findDeviceModel("premium_3_0")->peak_force_n, 22.0);
  EXPECT_EQ(findDeviceModel("generic")->max_damping_ns_per_m, 8.0);
  EXPECT_EQ(deviceModels().size(), 6u);
  for (const DeviceModel& m : deviceModels()) {
    EXPECT_DOUBLE_EQ(m.continuous_force_n, kContinuousForceFraction * m.peak_force_n) << m.name;
    EXPECT_LT(m.continuous_force_n, m.peak_force_n) << m.name;
  }
}

TEST(ClosestMatch, TyposAndPrefixes) {
  const std::vector<std::string> keys = {"size", "pose", "texture", "representation", "max_depth"};
  EXPECT_EQ(closestMatch("texure", keys), "texture");
  EXPECT_EQ(closestMatch("Texture", keys), "texture");
  EXPECT_EQ(closestMatch("max_dpeth", keys), "max_depth");  // transposition: one edit
  EXPECT_EQ(closestMatch("colour", keys), "");
  EXPECT_EQ(closestMatch("mortar_width", {"mortar", "mortar_depth"}), "mortar");
  EXPECT_EQ(closestMatch("phantom_desk", {"phantom_desktop", "phantom_omni"}), "phantom_desktop");
  EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(editDistance("", "abc"), 3u);
}

TEST(VrpnAddress, AcceptedForms) {
  auto a = parseVrpnAddress("Phantom0@localhost:3883");
  ASSERT_TRUE(a);
  EXPECT_EQ(a->device, "Phantom0");
  EXPECT_EQ(a->host, "localhost");
  EXPECT_EQ(a->port, 3883);
  a = parseVrpnAddress("Phantom0@tcp://10.0.0.2:4000");
  ASSERT_TRUE(a);
  EXPECT_EQ(a->scheme, "tcp");
  EXPECT_EQ(a->host, "10.0.0.2");
  EXPECT_EQ(a->port, 4000);
  a = parseVrpnAddress("Tracker0@lab");
  ASSERT_TRUE(a);
  EXPECT_EQ(a->port, kVrpnDefaultPort);
}

TEST(VrpnAddress, RejectedForms) {
  for (const char* bad : {"", "localhost:3883", "@localhost", "Phantom0@", "Phantom0@host:0", "Phantom0@host:70000",
                          "Phantom0@host:abc", "Phantom0@udp://host:3883", "Phantom 0@host", "Phantom0@tcp://:3883"}) {
    std::string problem;
    EXPECT_FALSE(parseVrpnAddress(bad, &problem)) << bad;
    EXPECT_FALSE(problem.empty()) << bad;
  }
}

TEST(SceneFrames, RollPitchYawConvention) {
  Pose pose;
  pose.rpy_deg = {0, 0, 90};
  EXPECT_TRUE(toIsometry(pose).linear().isApprox(
      Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix()));
  // R = Rz(yaw) Ry(pitch) Rx(roll): roll acts first on a body vector.
  pose.rpy_deg = {90, 0, 90};
  const Eigen::Vector3d y_body = toIsometry(pose).linear() * Eigen::Vector3d::UnitY();
  EXPECT_TRUE(y_body.isApprox(Eigen::Vector3d::UnitZ(), 1e-12)) << y_body.transpose();
  pose.rpy_deg = {0, 0, 0};
  pose.position_m = {0.1, 0.2, 0.3};
  EXPECT_TRUE((toIsometry(pose) * Eigen::Vector3d::Zero()).isApprox(pose.position_m));
}

TEST(SceneFrames, PlaneMappingFollowsTheSurface) {
  Surface surface;
  surface.size_m = {0.4, 0.2};
  surface.pose.position_m = {0, 0, 0.05};
  const thx::tex::PlaneMapping mapping = planeMapping(surface);
  EXPECT_EQ(mapping.size_m, surface.size_m);
  EXPECT_TRUE(mapping.toWorld(Eigen::Vector3d::Zero()).isApprox(Eigen::Vector3d(0, 0, 0.05)));
  const thx::tex::TexCoord uv = mapping.uvOfLocal({0.2, 0.1});
  EXPECT_DOUBLE_EQ(uv.u, 1.0);
  EXPECT_DOUBLE_EQ(uv.v, 1.0);
}

}  // namespace

}  // namespace test_scene_tables
