// physics-client on a mesh scene (surface.mesh, issue 29): a marble dropped into a bowl of bricks
// rolls inside it, never through it, with texel paths that follow the foot of its centre through
// the bowl's uv; the pen pushes it; the scene is named by hapticd's mesh fingerprint.
#include <gtest/gtest.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "clients/physics/bullet_convert.hpp"
#include "clients/physics_client/physics_scene.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_mesh.hpp"
#include "clients/physics/mesh_contact.hpp"
#include "scenes/scene_surface.hpp"
#include "textures/ball_on_relief.hpp"
#include "tests/support/bowl_scene.hpp"
#include "textures/smoothing.hpp"

namespace test_mesh_scene {

namespace {

using namespace thx::physclient;

// The shipped bowl of bricks at a coarser tessellation and texture, with a steel marble held above
// its wall.
const std::string kScene = thx::test::bowlOfBricksScene("marble in a bowl", 64, 128, R"(objects:
  - name: marble
    shape: sphere
    radius: 0.006
    mass: 0.007
    material: steel
    position: [0.02, 0.005, -0.012]
rates: {physics_hz: 1000}
)");

constexpr double kInsideA = 0.0552, kInsideB = 0.0432, kRimZ = 0.048, kFloorZ = 0.0048, kBowlZ = -0.04;
constexpr double kRadius = 0.006;

// Where a ball's centre is against the bowl's inside: < 1 within the ellipsoid shrunk by the ball
// (a ball resting on the inside has about 1), > 1 beyond it (through the wall).
double insideMeasure(const Eigen::Vector3d& c) {
  const double a = kInsideA - kRadius, b = kInsideB - kRadius;
  const double z = c.z() - kBowlZ;
  const double r2 = c.x() * c.x() + c.y() * c.y();
  const double below_rim = std::max(0.0, kRimZ - z);
  return r2 / (a * a) + below_rim * below_rim / (b * b);
}

// The triangle nearest p_world, by looking at every one (slow and sure).
std::uint32_t nearestTriangle(const thx::scene::SceneMesh& m, const Eigen::Vector3d& p_world) {
  return thx::mesh::nearestTriangle(m.mesh, m.mesh_to_world.inverse() * p_world);
}

bool fourNeighbours(const Texel& a, const Texel& b) { return std::llabs(a.i - b.i) + std::llabs(a.j - b.j) == 1; }

PhysicsScene makeScene(PenShape pen = PenShape::None) {
  SimOptions options;
  options.pen.shape = pen;
  return PhysicsScene(thx::scene::parseScene(kScene, "marble_in_a_bowl.yaml", "."), options);
}

TEST(MeshScene, AMarbleDroppedInABowlRollsInsideItAndNeverThroughIt) {
  PhysicsScene sim = makeScene();
  ASSERT_NE(sim.meshGround(), nullptr);
  double lowest = 1.0, highest_after_landing = -1.0, worst_inside = 0.0;
  int touching_steps = 0;
  bool landed = false;
  for (int k = 0; k < 2000; ++k) {
    sim.step(1e-3);
    const BodyState b = sim.body(0);
    bool touching = false;
    for (const LastingContact& c : sim.takeContacts()) touching = touching || (c.body_a == 0 && c.body_b == kBodySurface);
    touching_steps += touching;
    landed = landed || touching;
    lowest = std::min(lowest, b.p_world.z());
    if (landed) {
      highest_after_landing = std::max(highest_after_landing, b.p_world.z());
      worst_inside = std::max(worst_inside, insideMeasure(b.p_world));
    }
  }
  ASSERT_TRUE(landed);
  EXPECT_GT(touching_steps, 1500);  // it rolls: on the surface nearly all the time
  // Down through the floor's middle region: the centre comes within 3 mm of resting on the floor.
  EXPECT_LT(lowest, kBowlZ + kFloorZ + kRadius + 0.003);
  EXPECT_GT(lowest, kBowlZ + kFloorZ + kRadius - 0.0005);  // and never sinks into it
  // Inside the wall at every step (a measure of 1 is the wall itself; 1.02 allows the facets).
  EXPECT_LT(worst_inside, 1.02);
  // No energy from the contacts: it climbs no higher than it landed from.
  EXPECT_LT(highest_after_landing, -0.012 + 0.001);
}

TEST(MeshScene, TexelPathsFollowTheFootOfTheMarblesCentreThroughTheBowlsUv) {
  PhysicsScene sim = makeScene();
  const MeshGround& ground = *sim.meshGround();
  std::size_t texels = 0, restarts = 0, steps_with_path = 0;
  std::optional<std::uint32_t> near;
  for (int k = 0; k < 1500; ++k) {
    sim.step(1e-3);
    for (const LastingContact& c : sim.takeContacts()) {
      if (c.body_a != 0 || c.body_b != kBodySurface || c.path.empty()) continue;
      ++steps_with_path;
      // From the last foot's triangle (the marble moves about a triangle a step at most); the
      // first from the triangle nearest the contact.
      if (!near) near = nearestTriangle(ground.sceneMesh(), c.p_world);
      const MeshGround::Place foot = ground.footOf(sim.body(0).p_world, *near);
      near = foot.triangle;
      const thx::scene::SceneMesh& m = ground.sceneMesh();
      Eigen::Vector3d smooth = m.mesh_to_world.linear() *
                               thx::mesh::frameAt(m.mesh, foot.triangle, foot.barycentric, thx::mesh::FrameMode::Interpolated).normal;
      if (smooth.dot(sim.body(0).p_world - foot.p_world) < 0.0) smooth = -smooth;  // the inside is behind the winding
      EXPECT_EQ(c.path_dropped, 0);
      EXPECT_DOUBLE_EQ(c.mass_a_kg, 0.007);
      for (std::size_t q = 0; q < c.path.size(); ++q) {
        const Texel& t = c.path[q];
        ++texels;
        EXPECT_NEAR(t.n_world.norm(), 1.0, 1e-9);
        // The texel's normal leans from the smooth surface's at the marble by the bricks' slopes,
        // clamped at 75° (the contacts' rule), and towards the marble's side of the wall.
        EXPECT_GT(t.n_world.dot(smooth), std::cos(76.0 * M_PI / 180.0)) << "step " << k;
        if (q > 0) {
          if (!fourNeighbours(c.path[q - 1], t)) ++restarts;  // a seam of the lathe's u
          EXPECT_GE(t.t_s, c.path[q - 1].t_s);
        }
      }
      // The last texel is the one under the foot of the centre now.
      long long i = 0, j = 0;
      ground.texelOf(foot.uv, i, j);
      EXPECT_LE(std::llabs(c.path.back().i - i) + std::llabs(c.path.back().j - j), 1) << "step " << k;
    }
  }
  EXPECT_GT(steps_with_path, 200u);
  EXPECT_GT(texels, 500u);   // the bricks' 0.3 mm texels: many per centimetre rolled
  EXPECT_LE(restarts, 4u);  // only where the path crossed the u seam
}

TEST(MeshScene, ThePenPushesTheMarbleAndFeelsIt) {
  PhysicsScene sim = makeScene(PenShape::Sphere);
  for (int k = 0; k < 1000; ++k) sim.step(1e-3);  // it rolls about the floor (nothing damps it)
  // The pen (a 4 mm sphere) comes at the rolling marble from -x at its height, 0.1 mm closer
  // every step, from 2 mm apart: it touches within 20 steps and goes on pushing.
  bool felt = false;
  double push_x = 0.0;
  for (int k = 0; k <= 60; ++k) {
    const BodyState m = sim.body(0);
    const double gap = 0.002 - 1e-4 * k;
    sim.setPenTip(m.p_world - Eigen::Vector3d(kRadius + 0.004 + gap, 0.0, 0.004));
    sim.step(1e-3);
    if (sim.penForce().in_contact) {
      felt = felt || sim.penForce().raw_world.norm() > 1e-3;
      push_x = std::min(push_x, sim.penForce().raw_world.x());  // the marble pushes the pen back (-x)
    }
  }
  EXPECT_TRUE(felt);
  EXPECT_LT(push_x, -1e-3);
}

TEST(MeshScene, TheSceneIsNamedByHapticdsMeshFingerprint) {
  const thx::scene::Scene scene = thx::scene::parseScene(kScene, "marble_in_a_bowl.yaml", ".");
  SimOptions options;
  options.pen.shape = PenShape::None;
  const PhysicsScene sim(scene, options);
  thx::scene::SurfaceTextureOptions texture;
  texture.smooth = thx::tex::smoothTexture;
  const std::uint64_t plane_fingerprint = thx::scene::buildSceneSurface(scene, texture).fingerprint;
  EXPECT_EQ(sim.sceneSurface().fingerprint,
            thx::scene::meshSceneFingerprint(plane_fingerprint, thx::scene::buildSceneMesh(scene)));
  EXPECT_NE(sim.sceneSurface().fingerprint, plane_fingerprint);
}

// A ball on a relief mesh meets the relief as its sphere does (mesh_contact.hpp, ballOnReliefNormal):
// the bowl of bricks' 0.8 mm joints under a 12 mm marble swinging across the floor, through the
// lathe's pole where the texture's u closes to a point. Read at one point, the bricks squeezed
// there steered the marble into ever larger swings (1.5 mm more height in 4 s). Met as a sphere
// meets them, the push is the gradient of one scalar, the ball's lift over the relief, so the
// relief adds no energy: the marble loses some where it crosses the bricks' edges, as a real one
// does (the 1 ms step meets each edge as a small collision, which also moves the energy by a few
// hundredths of a millimetre either way from one window to the next).
// The swing's energy as a height: the centre's height plus its kinetic energy over m g, its peak
// over each 2 s window of `seconds`.
std::vector<double> swingEnergyPeaks(const thx::scene::Scene& scene, int variant, double seconds) {
  thx::scene::SurfaceTextureOptions texture;
  texture.smooth = thx::tex::smoothTexture;
  const thx::scene::SceneSurface surface = thx::scene::buildSceneSurface(scene, texture);
  const thx::scene::SceneMesh bowl = thx::scene::buildSceneMesh(scene);
  const thx::tex::BallOnRelief ball_relief(surface.surface.map(), surface.surface.sampling().address);
  thx::phys::MeshContactOptions o;
  o.texture = variant == 2 ? nullptr : &surface.surface.map();
  o.sampling = surface.surface.sampling();
  o.normals_made_for_m = surface.surface.mapping().size_m;
  o.ball_relief = variant == 0 ? &ball_relief : nullptr;
  thx::phys::WorldOptions wo;
  wo.rest.enabled = false;
  thx::phys::PhysicsWorld world(wo);
  world.addTexturedMesh(bowl.mesh, bowl.mesh_to_world, {1.0, 0.0, 0.0}, o);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0.01, 0.0, kBowlZ + kFloorZ + kRadius + 0.0005);
  btRigidBody& ball = world.addSphere(kRadius, 0.007, pose, {0.5, 0.0, 0.0});
  // Met as the ball meets it, the relief is the ball's potential too: its centre's lift over the
  // relief there (BallOnRelief::Touch::lift_m, along the surface's normal) is added.
  const thx::phys::ContactMesh contact_mesh(bowl.mesh);
  std::uint32_t foot_triangle = nearestTriangle(bowl, pose.translation());  // where the walk starts
  Eigen::Vector3d foot_b = Eigen::Vector3d::Constant(1.0 / 3.0);
  auto reliefLift = [&](const Eigen::Vector3d& c_world) {
    if (variant != 0) return 0.0;
    thx::phys::smoothFoot(contact_mesh, bowl.mesh_to_world.inverse() * c_world, -1.0, foot_triangle, foot_b);
    const thx::mesh::SurfaceFrame f = thx::mesh::frameAt(bowl.mesh, foot_triangle, foot_b, thx::mesh::FrameMode::Interpolated);
    const double lift = ball_relief.touch({f.uv.x(), f.uv.y()}, thx::phys::metresPerUvAt(contact_mesh, foot_triangle, foot_b), kRadius, true).lift_m;
    return lift * std::fabs((bowl.mesh_to_world.linear() * f.normal).z());
  };
  std::vector<double> peaks;
  double peak = -1.0;
  for (int k = 1; k <= int(std::lround(seconds * 1000.0)); ++k) {
    world.step(1e-3);
    const Eigen::Vector3d v = thx::phys::velocityOf(ball), c = thx::phys::positionOf(ball);
    const Eigen::Vector3d w = thx::phys::toEigen(ball.getAngularVelocity());
    peak = std::max(peak, c.z() + reliefLift(c) + (v.squaredNorm() + 0.4 * kRadius * kRadius * w.squaredNorm()) / (2.0 * 9.81));
    if (k % 2000 == 0) peaks.push_back(peak), peak = -1.0;
  }
  return peaks;
}

TEST(MeshScene, ABallMeetsAReliefAsItsSphereDoesAndGainsNoEnergy) {
  const thx::scene::Scene scene = thx::scene::parseScene(kScene, "marble_in_a_bowl.yaml", ".");
  // From the window after the first (the drop settled): the most the energy rose above it, and
  // where it ended.
  auto rise = [](const std::vector<double>& peaks) {
    double most = 0.0;
    for (std::size_t k = 2; k < peaks.size(); ++k) most = std::max(most, peaks[k] - peaks[1]);
    return most;
  };
  const std::vector<double> met = swingEnergyPeaks(scene, 0, 16.0), point = swingEnergyPeaks(scene, 1, 8.0),
                            smooth = swingEnergyPeaks(scene, 2, 8.0);
  std::printf("[measured] energy over the swing as height (with the lift over the relief), from the second 2 s window: "
              "met as a sphere rose at most %.4f mm and ended %+.4f mm 12 s later; read at one point %+.3f mm 4 s later; "
              "untextured %+.5f mm\n",
              rise(met) * 1e3, (met.back() - met[1]) * 1e3, (point.back() - point[1]) * 1e3, (smooth.back() - smooth[1]) * 1e3);
  EXPECT_LT(std::fabs(smooth.back() - smooth[1]), 2e-6);
  EXPECT_LT(rise(met), 5e-5);             // no more than the edges' collisions move it (measured 0.02 mm)
  EXPECT_LT(met.back() - met[1], 0.0);    // and 12 s later it has lost some
  EXPECT_GT(point.back() - point[1], 1e-4);  // read at one point: a tenth of a millimetre and more
}

}  // namespace

}  // namespace test_mesh_scene
