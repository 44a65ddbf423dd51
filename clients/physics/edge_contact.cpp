#include "clients/physics/edge_contact.hpp"

#include <algorithm>
#include <cmath>

namespace thx::phys {

namespace {

// How far the rod's normal must lean out over the edge (the sine of 0.57 degrees): a rod lying
// level across the edge (a rail under a block's edge) keeps the relief's normals, which its own
// differ from by the texels' sampling of the walls it lies on.
constexpr double kLeansOverEdge = 0.01;

bool nearConvexEdge(const ChartBoundary& boundary, const Eigen::Vector3d& p, double band_m, Eigen::Vector3d& across) {
  for (std::size_t k = 0; k < boundary.count; ++k) {
    const ChartEdge& e = boundary.edges[k];
    const double inside = e.offset - e.normal.dot(p.head<2>());
    if (e.convex && inside >= 0.0 && inside <= band_m) {
      across = e.across_normal;
      return true;
    }
  }
  return false;
}

}  // namespace

void rodNormalsAtConvexEdges(const Underside& rod, const ChartBoundary& boundary, double band_m,
                             ChosenReliefContacts& chosen) {
  const Eigen::Vector3d c = rod.plane_from_object.translation();
  const Eigen::Vector3d u = rod.plane_from_object.linear().col(rod.axis);
  for (std::size_t k = 0; k < chosen.count; ++k) {
    ReliefCandidate& contact = chosen.contacts[k];
    Eigen::Vector3d across;
    if (!nearConvexEdge(boundary, contact.p_surface, band_m, across)) continue;
    const double along = (contact.p_surface - c).dot(u);
    if (rod.kind == Underside::Kind::Cylinder && std::fabs(along) >= rod.half_length) continue;  // its end face's rim
    const Eigen::Vector3d to_axis = c + std::clamp(along, -rod.half_length, rod.half_length) * u - contact.p_surface;
    const double length = to_axis.norm();
    if (!(length > 0.0)) continue;
    const Eigen::Vector3d n = to_axis / length;
    if (n.z() > 0.0 && n.dot(across) > kLeansOverEdge) contact.n_local = n;
  }
}

}  // namespace thx::phys
