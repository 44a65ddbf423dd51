// The foot of a point on a mesh's smooth surface (clients/physics/mesh_contact.hpp, smoothFoot):
// where the interpolated normal points at it. A ball's chart is laid there, and its contacts on a
// smooth mesh are moved there.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "clients/physics/mesh_contact.hpp"
#include "meshes/mesh_generators.hpp"

namespace {

using thx::phys::ContactMesh;
using thx::phys::smoothFoot;

// How far (radians) the smooth normal at the foot turns from the foot's line to c.
double offNormal(const thx::mesh::TexturedMesh& m, std::uint32_t triangle, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const thx::mesh::SurfaceFrame f = thx::mesh::frameAt(m, triangle, b, thx::mesh::FrameMode::Interpolated);
  const Eigen::Vector3d pointing = (c - f.point).normalized();
  return std::atan2(pointing.cross(f.normal).norm(), pointing.dot(f.normal));
}

// A point 9.5 mm off UV spheres smaller than that (a 1 cm ball recessed 0.5 mm on them, down to a
// sphere of a fortieth of its radius), along lines on and off the world's axes, the walk started
// from the triangle nearest the point (as a chart's first step starts), from one about a facet
// round from it (a last step's foot) and from one 0.5 rad round (where the first rounds swing
// from side to side of the smaller spheres, and their growth no longer reads h / R). Each
// round of the undamped walk swung round the sphere h / R times as far as the one before (h the
// point's height over the surface, R the sphere's radius), and the foot it left lay up to 40
// degrees off: a ball rested there 108-130 um off its touch on the 5 mm sphere (docs/physics.md,
// "A smooth mesh curved more tightly than the object on it").
TEST(SmoothFoot, OnASphereCurvedMoreTightlyThanThePointStandsOffItIsWhereTheNormalPointsAtThePoint) {
  for (const double radius : {0.005, 0.003, 0.002, 0.001, 0.00025}) {
    const thx::mesh::GeneratedMesh sphere = thx::mesh::sphere(radius, 128, 64, 0.02);
    const ContactMesh contact(sphere.mesh);
    for (const Eigen::Vector3d& line : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(1, 1, 1),
                                        Eigen::Vector3d(1, -2, 0.5), Eigen::Vector3d(-0.3, 0.8, 1)}) {
      const Eigen::Vector3d u = line.normalized();
      const Eigen::Vector3d c = (radius + 0.0095) * u;
      for (const double start_rad : {0.0, 0.05, 0.5}) {
        const Eigen::Vector3d start = Eigen::AngleAxisd(start_rad, u.unitOrthogonal()) * u * radius;
        std::uint32_t triangle = thx::mesh::nearestTriangle(sphere.mesh, start);
        Eigen::Vector3d b = thx::mesh::closestBarycentric(sphere.mesh, triangle, start);
        const bool over = smoothFoot(contact, c, 1.0, triangle, b);
        const double off = offNormal(sphere.mesh, triangle, b, c);
        const Eigen::Vector3d foot = thx::mesh::frameAt(sphere.mesh, triangle, b, thx::mesh::FrameMode::Interpolated).point;
        const double round_the_sphere = std::acos(std::clamp(foot.normalized().dot(u), -1.0, 1.0));
        std::printf("[measured] foot on the %g mm sphere along (%.2f, %.2f, %.2f) from %.2f rad round: normal %.2g rad "
                    "off the line to the point, %.2g rad round the sphere from the point's direction\n",
                    radius * 1e3, u.x(), u.y(), u.z(), start_rad, off, round_the_sphere);
        EXPECT_TRUE(over) << radius << " m, along " << u.transpose();
        EXPECT_LT(off, 1e-8) << radius << " m, along " << u.transpose();
        // The interpolated normal is the sphere's own to within a facet's turn (2.8 degrees).
        EXPECT_LT(round_the_sphere, 0.05) << radius << " m, along " << u.transpose();
      }
    }
  }
}

}  // namespace
