// The textured mesh renderer (server/textured_mesh_renderer.hpp): the exact force of a smooth
// sphere, the texture's normal and depth turned by the interpolated frame, a thin plate that
// cannot be pushed through, an inside corner held by three textured faces, and a force whose
// direction turns smoothly across edges where a face's own frame jumps.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <string>

#include "meshes/mesh_generators.hpp"
#include "textures/generators.hpp"
#include "server/textured_mesh_renderer.hpp"
#include "tests/support/same_render_output.hpp"

namespace test_textured_mesh_renderer {

using namespace thx;

constexpr double kK = 600.0;
constexpr double kStep = 2e-5;  // m per tick: 20 mm/s at 1 kHz

srv::RendererConfig config() {
  srv::RendererConfig c;
  c.stiffness_n_per_m = kK;
  return c;
}

// A mesh with its hierarchy and a renderer on it (the pieces must outlive the renderer).
struct Rig {
  mesh::TexturedMesh mesh;
  std::unique_ptr<srv::TriangleBvh> bvh;
  std::unique_ptr<srv::TexturedMeshRenderer> renderer;
  Rig(mesh::TexturedMesh m, const srv::MeshTexture& texture, mesh::FrameMode frames = mesh::FrameMode::InterpolatedPhong,
      const Eigen::Isometry3d& place = Eigen::Isometry3d::Identity())
      : mesh(std::move(m)), bvh(std::make_unique<srv::TriangleBvh>(mesh.positions, mesh.triangles)) {
    renderer = std::make_unique<srv::TexturedMeshRenderer>(mesh, *bvh, texture, place, config(), frames);
  }
};

// Moves the tip from `from` to `to` in steps of kStep, then holds it; the last output.
srv::RenderOutput press(srv::TexturedMeshRenderer& r, const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                        int hold = 5) {
  r.reset();
  const int n = int(std::ceil((to - from).norm() / kStep));
  for (int k = 0; k < n; ++k) r.render(from + (to - from) * (double(k) / n), Eigen::Vector3d::Zero());
  srv::RenderOutput out;
  for (int k = 0; k < hold; ++k) out = r.render(to, Eigen::Vector3d::Zero());
  return out;
}

// A map of one normal everywhere (tangent frame), and optionally one depth.
tex::TextureMap uniformMap(const Eigen::Vector3f& n, double depth_m = 0.0) {
  tex::TextureMap map(8, 8, depth_m > 0 ? tex::Representation::Relief : tex::Representation::Normal, depth_m);
  for (int j = 0; j < 8; ++j) {
    for (int i = 0; i < 8; ++i) {
      map.setNormal(i, j, n);
      if (depth_m > 0) map.setDepth(i, j, depth_m);
    }
  }
  return map;
}

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

TEST(TexturedMeshRenderer, SmoothSphereGivesTheRadialForce) {
  const double r = 0.05;
  Rig rig(mesh::sphere(r, 64, 32, 0.01).mesh, {});
  for (const Eigen::Vector3d& dir : {Eigen::Vector3d(1, 0.3, 0.2), Eigen::Vector3d(-0.2, 0.9, -0.5),
                                    Eigen::Vector3d(0.1, -0.2, -1.0), Eigen::Vector3d(0.01, 0.02, 1.0)}) {
    const Eigen::Vector3d u = dir.normalized();
    for (double depth : {0.5e-3, 2e-3}) {
      const srv::RenderOutput out = press(*rig.renderer, u * (r + 1e-3), u * (r - depth));
      ASSERT_TRUE(out.in_contact);
      EXPECT_LT(angleDeg(out.force_world, u), 0.1);
      // Phong's surface at 64 x 32 lies within 1e-6 m of the sphere: 0.3 % of k x 0.5 mm.
      EXPECT_NEAR(out.force_world.norm(), kK * depth, kK * 1.5e-6);
    }
  }
}

TEST(TexturedMeshRenderer, NormalMapTurnsWithTheFrame) {
  // A normal tilted toward +u everywhere, on a cylinder (u around z): the force leans along the
  // circumference by the same angle wherever the pen presses, as on the plane. It leans in the
  // frame of the contact (the proxy, a depth x tilt around from the tip), where the surface that
  // normal stands for is closest to the tip.
  const tex::TextureMap map = uniformMap(Eigen::Vector3f(0.3f, 0.0f, 1.0f).normalized());
  const double r = 0.03;
  Rig rig(mesh::cylinder(r, 0.05, 96, 8, 0.01).mesh, {&map, {}, false});
  for (double phi : {0.3, 2.0, 4.4}) {
    const Eigen::Vector3d radial(std::cos(phi), std::sin(phi), 0.0), east(-std::sin(phi), std::cos(phi), 0.0);
    const Eigen::Vector3d at = Eigen::Vector3d(0, 0, 0.025);
    const srv::RenderOutput out = press(*rig.renderer, at + radial * (r + 1e-3), at + radial * (r - 1e-3));
    ASSERT_TRUE(out.in_contact);
    const Eigen::Vector3d c = rig.renderer->lastContact().frame.point;
    const double phi_c = phi + std::remainder(std::atan2(c.y(), c.x()) - phi, 2 * M_PI);
    EXPECT_GT(phi_c - phi, 0.0);  // the proxy leans toward +u, and the contact with it
    EXPECT_LT(phi_c - phi, 1.1 * 1e-3 * 0.3 / r);
    const Eigen::Vector3d want =
        (0.3 * Eigen::Vector3d(-std::sin(phi_c), std::cos(phi_c), 0) + Eigen::Vector3d(std::cos(phi_c), std::sin(phi_c), 0)).normalized();
    EXPECT_LT(angleDeg(out.force_world, want), 0.02) << "phi " << phi;
    EXPECT_LT(angleDeg(out.n_sampled_world, want), 0.02);
    (void)east;
  }
}

TEST(TexturedMeshRenderer, ReliefDepthMovesTheSurfaceIn) {
  const tex::TextureMap map = uniformMap(Eigen::Vector3f(0, 0, 1), 0.4e-3);
  const double r = 0.05;
  Rig rig(mesh::sphere(r, 64, 32, 0.01).mesh, {&map, {}, true});
  const Eigen::Vector3d u = Eigen::Vector3d(0.3, -0.4, 0.5).normalized();
  // Inside the mesh but above the relief: no force.
  EXPECT_FALSE(press(*rig.renderer, u * (r + 1e-3), u * (r - 0.3e-3)).in_contact);
  const srv::RenderOutput out = press(*rig.renderer, u * (r + 1e-3), u * (r - 1.4e-3));
  ASSERT_TRUE(out.in_contact);
  EXPECT_NEAR(out.force_world.norm(), kK * 1.0e-3, kK * 2e-6);
  EXPECT_NEAR(out.relief_depth_m, 0.4e-3, 1e-8);
}

TEST(TexturedMeshRenderer, ThinPlateIsNotPushedThrough) {
  // A 1 mm plate: the tip pressed 3 mm down from above ends below the plate, and the force still
  // pushes it up to the top face (the god object stays on the side it came from).
  Rig rig(mesh::box({0.04, 0.04, 0.001}, 0.005, 0.01).mesh, {});
  const Eigen::Vector3d xy(0.0031, -0.0047, 0.0);
  const srv::RenderOutput out = press(*rig.renderer, xy + Eigen::Vector3d(0, 0, 0.002), xy + Eigen::Vector3d(0, 0, -0.0025));
  ASSERT_TRUE(out.in_contact);
  EXPECT_NEAR(out.force_world.z(), kK * 0.003, 1e-6);
  EXPECT_NEAR(out.force_world.head<2>().norm(), 0.0, 1e-9);
}

TEST(TexturedMeshRenderer, InsideCornerHoldsThreeTexturedFaces) {
  // The inside of a 4 cm room; the pen pushed into the corner (+x, +y, +z) from the centre. With
  // a flat normal map every face's plane is its wall, so the force is k x (corner - tip) per axis.
  const tex::TextureMap map = uniformMap(Eigen::Vector3f(0, 0, 1));
  Rig rig(mesh::box({0.04, 0.04, 0.04}, 0.01, 0.01, true).mesh, {&map, {}, false});
  const Eigen::Vector3d tip(0.0205, 0.021, 0.0215);
  const srv::RenderOutput out = press(*rig.renderer, Eigen::Vector3d(0.015, 0.015, 0.015), tip);
  ASSERT_TRUE(out.in_contact);
  EXPECT_EQ(out.num_planes, 3);
  EXPECT_LT((out.force_world - kK * (Eigen::Vector3d(0.02, 0.02, 0.02) - tip)).norm(), 1e-6);
}

TEST(TexturedMeshRenderer, InterpolatedFramesTurnTheForceSmoothlyAcrossEdges) {
  // A stroke around a coarse smooth cylinder at a constant depth: the face's own frame (CHAI3D's)
  // turns the force by a whole face angle (7.5 degrees at 48 segments) at each edge; the
  // interpolated frame by a small fraction of it per tick.
  const double r = 0.03;
  auto largestStep = [&](mesh::FrameMode mode) {
    Rig rig(mesh::cylinder(r, 0.05, 48, 4, 0.01).mesh, {}, mode);
    rig.renderer->reset();
    Eigen::Vector3d last = Eigen::Vector3d::Zero();
    double worst = 0.0;
    const double rho = r - 1e-3;
    rig.renderer->render({rho + 2e-3, 0.0, 0.025}, Eigen::Vector3d::Zero());
    for (int k = 0; k <= 50; ++k) rig.renderer->render({rho + 2e-3 * (1 - k / 50.0), 0.0, 0.025}, Eigen::Vector3d::Zero());
    for (double phi = 0.0; phi < 0.8; phi += kStep / rho) {
      const srv::RenderOutput out =
          rig.renderer->render({rho * std::cos(phi), rho * std::sin(phi), 0.025}, Eigen::Vector3d::Zero());
      EXPECT_TRUE(out.in_contact);
      if (!last.isZero()) worst = std::max(worst, angleDeg(out.force_world, last));
      last = out.force_world;
    }
    return worst;
  };
  const double per_triangle = largestStep(mesh::FrameMode::PerTriangle);
  const double interpolated = largestStep(mesh::FrameMode::InterpolatedPhong);
  EXPECT_GT(per_triangle, 5.0);
  EXPECT_LT(interpolated, 0.1);
}

TEST(TexturedMeshRenderer, SeamIsFeltNowhere) {
  // A bumpy relief wrapped round a cylinder in whole tiles: a stroke at a constant depth across
  // the seam (u = 0 meets u = 10 at phi = 0) turns the force no more there than anywhere else.
  tex::TextureMap map(64, 64, tex::Representation::Relief, 3e-4);
  for (int j = 0; j < 64; ++j) {
    for (int i = 0; i < 64; ++i) {
      // Height h = -a (1 + sin x cos y) over one tile of 20 mm (x = 2 pi u, y = 2 pi v; row 0 is
      // v = 1): the normal (-dh/dX, -dh/dY, 1) with X, Y in metres.
      const double x = 2 * M_PI * (i + 0.5) / 64, y = 2 * M_PI * (1.0 - (j + 0.5) / 64);
      const double a = 1.5e-4, k = 2 * M_PI / 0.02;
      map.setDepth(i, j, a + a * std::sin(x) * std::cos(y));
      map.setNormal(i, j, Eigen::Vector3f(float(a * k * std::cos(x) * std::cos(y)), float(-a * k * std::sin(x) * std::sin(y)), 1.0f));
    }
  }
  const double r = 0.2 / (2 * M_PI);  // a circumference of 0.2 m: 10 tiles of 20 mm
  Rig rig(mesh::cylinder(r, 0.05, 240, 8, 0.02).mesh, {&map, {}, true});
  rig.renderer->reset();
  const double rho = r - 0.6e-3, z = 0.0255;
  for (int k = 0; k <= 60; ++k) rig.renderer->render({(r + 1e-3) - (1e-3 + 0.6e-3) * k / 60.0, 0.0, z}, Eigen::Vector3d::Zero());
  // From phi = -0.05 to +0.05 through the seam at 0, then the same length elsewhere.
  auto largestStep = [&](double from) {
    double worst = 0.0;
    Eigen::Vector3d last = Eigen::Vector3d::Zero();
    for (double phi = from; phi < from + 0.1; phi += kStep / rho) {
      const srv::RenderOutput out = rig.renderer->render({rho * std::cos(phi), rho * std::sin(phi), z}, Eigen::Vector3d::Zero());
      EXPECT_TRUE(out.in_contact);
      if (!last.isZero()) worst = std::max(worst, (out.force_world - last).norm());
      last = out.force_world;
    }
    return worst;
  };
  for (double phi = 0; phi > -0.05; phi -= kStep / rho) rig.renderer->render({rho * std::cos(phi), rho * std::sin(phi), z}, Eigen::Vector3d::Zero());
  const double across = largestStep(-0.05);
  const double elsewhere = largestStep(0.05);
  EXPECT_GT(elsewhere, 0.0);
  EXPECT_LT(across, 1.5 * elsewhere);
}

TEST(TexturedMeshRenderer, MirroredChartLeansTowardItsOwnU) {
  // The same normal map tilted toward +u on a flat quad whose u runs along -x (a mirrored chart):
  // the force leans toward -x, as the texture says, not toward +x.
  const tex::TextureMap map = uniformMap(Eigen::Vector3f(0.3f, 0.0f, 1.0f).normalized());
  mesh::TexturedMesh m;
  m.source = "mirrored quad";
  m.positions = {{-0.02, -0.02, 0}, {0.02, -0.02, 0}, {0.02, 0.02, 0}, {-0.02, 0.02, 0}};
  m.uvs = {{4, 0}, {0, 0}, {0, 4}, {4, 4}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh::buildVertexFrames(m);
  Rig rig(std::move(m), {&map, {}, false});
  const srv::RenderOutput out = press(*rig.renderer, {0.001, 0.002, 1e-3}, {0.001, 0.002, -1e-3});
  ASSERT_TRUE(out.in_contact);
  EXPECT_LT(angleDeg(out.force_world, Eigen::Vector3d(-0.3, 0.0, 1.0)), 0.01);
}

TEST(TexturedMeshRenderer, PlacedInTheWorld) {
  // The same press on a sphere moved and turned: the force is turned with it.
  const double r = 0.05;
  Eigen::Isometry3d place = Eigen::Isometry3d::Identity();
  place.translate(Eigen::Vector3d(0.1, -0.2, 0.05));
  place.rotate(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  const tex::TextureMap map = uniformMap(Eigen::Vector3f(0.2f, -0.1f, 1.0f).normalized());
  Rig local(mesh::sphere(r, 48, 24, 0.01).mesh, {&map, {}, false});
  Rig placed(mesh::sphere(r, 48, 24, 0.01).mesh, {&map, {}, false}, mesh::FrameMode::InterpolatedPhong, place);
  const Eigen::Vector3d u = Eigen::Vector3d(0.2, 0.5, -0.3).normalized();
  const srv::RenderOutput a = press(*local.renderer, u * (r + 1e-3), u * (r - 1e-3));
  const srv::RenderOutput b = press(*placed.renderer, place * (u * (r + 1e-3)), place * (u * (r - 1e-3)));
  ASSERT_TRUE(a.in_contact && b.in_contact);
  EXPECT_LT((place.linear() * a.force_world - b.force_world).norm(), 1e-9);
  EXPECT_LT((place * a.proxy_world - b.proxy_world).norm(), 1e-12);
}

// The inside of a pipe is concave at every edge, so the god object holds two faces wherever the
// pen runs along one. They continue each other smoothly: one surface, its texture rendered on
// the chart. (Rendered as two separate textured planes, the anchor flipped between the faces
// every tick on a textured relief and the force with it, by up to 1 N in the bowl of
// scenes/brick_bowl.yaml: energy the passivity controller had to take out.)
TEST(TexturedMeshRenderer, AlongAConcaveEdgeTheTextureIsRenderedAsOneSurface) {
  tex::GenerateRequest g;
  g.kind = "sine";
  g.size = 256;
  g.params = {{"amplitude", 0.3e-3}, {"period", 0.01}, {"extent", 0.02}};
  const tex::TextureMap map = tex::generate(g);
  const double r = 0.03;
  // 32 segments: an edge every 11.25 degrees, each a concave crease of the pipe's inside.
  Rig rig(mesh::cylinder(r, 0.1, 32, 8, 0.02, /*inward=*/true).mesh, {&map, {}, true});
  // Along the edge at angle 0 (x = r + depth: into the pipe's wall from its hollow, y = 0), from
  // z = 0.03 to 0.07 at 20 mm/s, wobbling across it.
  const double depth = 1.0e-3;
  rig.renderer->reset();
  for (int k = 0; k < 150; ++k)
    rig.renderer->render(Eigen::Vector3d(r - 0.002 + (0.002 + depth) * k / 149.0, 0.0, 0.03), Eigen::Vector3d::Zero());
  double max_step = 0.0, max_force = 0.0;
  int multi_face_ticks = 0;
  Eigen::Vector3d prev = rig.renderer->render(Eigen::Vector3d(r + depth, 0.0, 0.03), Eigen::Vector3d::Zero()).force_world;
  for (int k = 1; k <= 2000; ++k) {
    // A hand's wobble across the edge: 20 um either side.
    const double y = 2e-5 * std::sin(0.3 * k);
    const srv::RenderOutput out = rig.renderer->render(Eigen::Vector3d(r + depth, y, 0.03 + k * kStep), Eigen::Vector3d::Zero());
    ASSERT_TRUE(out.in_contact) << k;
    max_step = std::max(max_step, (out.force_world - prev).norm());
    max_force = std::max(max_force, out.force_world.norm());
    if (out.num_planes > 1) ++multi_face_ticks;  // the smooth bumps need one plane; two: a plane per face
    prev = out.force_world;
  }
  // The texture's bumps (0.3 mm, 10 mm period) move the force by about k x amplitude x 2 pi x
  // step / period per tick: 0.5 mN. A flip between two faces' planes is 100 times that.
  EXPECT_LT(max_step, 0.01);
  EXPECT_GT(max_force, kK * depth * 0.5);
  EXPECT_EQ(multi_face_ticks, 0);
}

// The mesh's uv lays the texture at another scale than the one its normals were made for (here
// twice as many tiles along u): with normals_made_for_m the felt slope is the slope of the relief
// as laid, twice the map's; without, the map's as it stands.
TEST(TexturedMeshRenderer, ATextureSqueezedByTheUvIsFeltAtTheSlopeItIsLaidAt) {
  const double slope = 0.1;
  const tex::TextureMap map = uniformMap(Eigen::Vector3f(float(-slope), 0.0f, 1.0f).normalized());
  mesh::TexturedMesh squeezed = mesh::box({0.04, 0.04, 0.04}, 0.01, 0.02).mesh;
  for (Eigen::Vector2d& uv : squeezed.uvs) uv.x() *= 2.0;  // 0.01 m per uv along u
  squeezed.normals.clear();
  squeezed.tangents.clear();
  squeezed.handedness.clear();
  mesh::buildVertexFrames(squeezed);
  srv::MeshTexture as_made{&map, {}, false};
  srv::MeshTexture as_laid = as_made;
  as_laid.normals_made_for_m = {0.02, 0.02};
  Rig made(squeezed, as_made), laid(squeezed, as_laid);
  const Eigen::Vector3d above(0.003, -0.002, 0.021), below(0.003, -0.002, 0.019);
  const srv::RenderOutput a = press(*made.renderer, above, below);
  const srv::RenderOutput b = press(*laid.renderer, above, below);
  ASSERT_TRUE(a.in_contact && b.in_contact);
  // The top face's u runs along +x or -x (the box's own layout): the lean is along x either way.
  // (The map stores its normal in float: the slope to 1e-4.)
  EXPECT_NEAR(std::fabs(a.n_sampled_world.x() / a.n_sampled_world.z()), slope, 1e-4);
  EXPECT_NEAR(std::fabs(b.n_sampled_world.x() / b.n_sampled_world.z()), 2 * slope, 2e-4);
  EXPECT_NEAR(b.n_sampled_world.y(), 0.0, 1e-9);
}

// As the plane renderer's (test_proxy_renderer.cpp): renderForce() then describeContact() say
// what render() says, to the bit, on a relief-textured sphere placed in the world (the chart:
// entering, a wavy stroke over the bricks, leaving, a non-finite tip) and in a room's inside
// corner (several textured planes); renderForce()'s fields are final before describeContact(); and
// the description is in the world's frame (against the same sphere at the origin).
TEST(TexturedMeshRenderer, RendersInTwoHalvesWhatRenderDoes) {
  tex::GenerateRequest request;
  request.kind = "bricks";
  request.size = 128;
  const tex::TextureMap map = tex::generate(request);
  const srv::MeshTexture texture{&map, {tex::Filter::Bilinear, tex::Address::Wrap}, map.isRelief()};
  Eigen::Isometry3d place = Eigen::Isometry3d::Identity();
  place.translate(Eigen::Vector3d(0.1, -0.2, 0.05));
  place.rotate(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  const double radius = 0.03;
  Rig whole(mesh::sphere(radius, 96, 48, 0.01).mesh, texture, mesh::FrameMode::InterpolatedPhong, place);
  Rig halves(mesh::sphere(radius, 96, 48, 0.01).mesh, texture, mesh::FrameMode::InterpolatedPhong, place);
  Rig at_origin(mesh::sphere(radius, 96, 48, 0.01).mesh, texture);
  int contact = 0;
  for (int k = 0; k < 3000; ++k) {
    const double a = 5e-5 * k / radius, b = 0.3 * std::sin(a * 3.0);
    const double depth = k % 1000 < 800 ? 1e-3 : -2e-3;  // out of contact 200 ticks in 1000
    const Eigen::Vector3d n(std::cos(a) * std::cos(b), std::sin(a) * std::cos(b), std::sin(b));
    Eigen::Vector3d local_tip = n * (radius - depth);
    const Eigen::Vector3d local_v = Eigen::Vector3d(-std::sin(a), std::cos(a), 0.0) * 0.05;
    if (k == 1500) local_tip.y() = std::numeric_limits<double>::infinity();
    const Eigen::Vector3d tip = place * local_tip;
    const Eigen::Vector3d v = place.linear() * local_v;
    const std::string where = "sphere, tick " + std::to_string(k);
    const srv::RenderOutput x = whole.renderer->render(tip, v);
    srv::RenderOutput y = halves.renderer->renderForce(tip, v);
    test::expectSameForce(x, y, where);
    halves.renderer->describeContact(y);
    halves.renderer->prepareNextTick();  // the servo's order
    test::expectSameOutput(x, y, where);
    const srv::RenderOutput z = at_origin.renderer->render(local_tip, local_v);
    if (k != 1500 && z.in_contact == y.in_contact) test::expectDescribedAt(place, z, y, 1e-9, where);
    contact += x.in_contact ? 1 : 0;
  }
  EXPECT_GT(contact, 1200);

  // The room's inside corner: three faces held, each its own textured plane.
  const tex::TextureMap flat = uniformMap(Eigen::Vector3f(0.1f, 0.05f, 1.0f).normalized());
  Rig room_whole(mesh::box({0.04, 0.04, 0.04}, 0.01, 0.01, true).mesh, {&flat, {}, false});
  Rig room_halves(mesh::box({0.04, 0.04, 0.04}, 0.01, 0.01, true).mesh, {&flat, {}, false});
  int three = 0;
  const Eigen::Vector3d from(0.015, 0.015, 0.015), to(0.0205, 0.021, 0.0215);
  for (int k = 0; k <= 400; ++k) {
    const Eigen::Vector3d tip = from + (to - from) * (double(k) / 400);
    const srv::RenderOutput a = room_whole.renderer->render(tip, Eigen::Vector3d::Zero());
    srv::RenderOutput b = room_halves.renderer->renderForce(tip, Eigen::Vector3d::Zero());
    room_halves.renderer->describeContact(b);
    test::expectSameOutput(a, b, "corner, tick " + std::to_string(k));
    three += a.num_planes == 3 ? 1 : 0;
  }
  EXPECT_GT(three, 0) << "the stroke reaches the corner";
}

}  // namespace test_textured_mesh_renderer
