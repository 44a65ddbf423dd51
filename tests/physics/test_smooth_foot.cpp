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

// A point 10 mm off a 1 mm rod (a tube mesh of 128 segments and 64 rows over 10 cm: slivers
// 0.05 x 1.6 mm), at five angles round it and two heights along it, the walk started a facet and
// more round from the foot and 0.3 mm along the rod. Round it h / R is 10, along it 0: the damped
// walk's one part alpha settled neither (at 0.125, 0.875 of the way a round along the rod, 40
// rounds short), and the foot was left at an edge, "not over the surface"; a plain ball pressed on
// the rod was thrown off along two of five lines (docs/physics.md, "Small triangles"). Newton's
// method on the foot's two coordinates settles it.
TEST(SmoothFoot, OnARodCurvedTightlyRoundItAndNotAlongItIsWhereTheNormalPointsAtThePoint) {
  thx::mesh::GeneratedMesh rod = thx::mesh::cylinder(0.001, 0.1, 128, 64, 0.02);
  for (Eigen::Vector3d& p : rod.mesh.positions) p.z() -= 0.05;
  const ContactMesh contact(rod.mesh);
  for (const double angle : {0.0, 0.3, 0.7, 1.1, 2.0}) {
    for (const double z : {0.0, 0.0004}) {
      const Eigen::Vector3d c(0.011 * std::cos(angle), 0.011 * std::sin(angle), z);
      for (const double start_rad : {0.05, 0.5}) {
        const Eigen::Vector3d start(0.001 * std::cos(angle + start_rad), 0.001 * std::sin(angle + start_rad), z + 0.0003);
        std::uint32_t triangle = thx::mesh::nearestTriangle(rod.mesh, start);
        Eigen::Vector3d b = thx::mesh::closestBarycentric(rod.mesh, triangle, start);
        const bool over = smoothFoot(contact, c, 1.0, triangle, b);
        const double off = offNormal(rod.mesh, triangle, b, c);
        std::printf("[measured] foot on the 1 mm rod at %.1f rad, %.1f mm along, from %.2f rad round: normal %.2g rad off "
                    "the line to the point\n",
                    angle, z * 1e3, start_rad, off);
        EXPECT_TRUE(over) << angle << " rad, " << z << " m along";
        EXPECT_LT(off, 1e-8) << angle << " rad, " << z << " m along";
      }
    }
  }
}

}  // namespace
