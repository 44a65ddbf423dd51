#include "clients/physics/pair_contact_normal.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "clients/physics/crease_contact.hpp"
#include "textures/sampling.hpp"

namespace thx::phys {

void smootherSurfaceNormals(const tex::TexturedSurface& surface, const GroundBend* bend, const TexturedObjectSurface& object,
                            std::span<ReliefCandidate> contacts) {
  const tex::TextureMap& map = surface.map();
  const tex::Address address = surface.sampling().address;
  // Signed as the rasteriser steps (+i is +x, +j is -y, relief_raster.cpp).
  const Eigen::Vector2d texel = surface.mapping().texelSize(map);
  for (ReliefCandidate& c : contacts) {
    // The object over the contact's texel (absent only where it does not cover it: nothing to
    // measure there).
    const std::optional<ObjectSurfacePoint> centre = object.at(c.p_surface.x(), c.p_surface.y());
    if (!centre) continue;
    // The texel d texels along a row (axis 0) or a column (axis 1) from the contact's.
    auto planeHeight = [&](int axis, int d) {
      const long long i = c.i + (axis == 0 ? d : 0), j = c.j + (axis == 1 ? d : 0);
      const double x = c.p_surface.x() + double(i - c.i) * texel.x(), y = c.p_surface.y() - double(j - c.j) * texel.y();
      return -double(map.depth(tex::resolveIndex(i, map.width(), address), tex::resolveIndex(j, map.height(), address))) +
             (bend ? bend->height(x, y) : 0.0);
    };
    auto objectHeight = [&](int axis, int d) -> std::optional<double> {
      if (d == 0) return centre->z;
      const double x = c.p_surface.x() + (axis == 0 ? d * texel.x() : 0.0), y = c.p_surface.y() - (axis == 1 ? d * texel.y() : 0.0);
      const std::optional<ObjectSurfacePoint> b = object.at(x, y);
      return b ? std::optional<double>(b->z) : std::nullopt;
    };
    // Along a row and along a column, the larger. The plane lies under the contact's neighbours
    // everywhere; the object, on the footprint's rim, covers one of the two only: its second
    // difference is then taken one texel in.
    const double plane_centre = planeHeight(0, 0);
    double plane_jump = 0.0, object_jump = -1.0;
    for (int axis = 0; axis < 2; ++axis) {
      const double size = std::fabs(axis == 0 ? texel.x() : texel.y());
      plane_jump = std::max(plane_jump, std::fabs(planeHeight(axis, -1) + planeHeight(axis, 1) - 2.0 * plane_centre) / size);
      std::optional<double> h[5];
      for (int d = -2; d <= 2; ++d) h[d + 2] = objectHeight(axis, d);
      int mid = 2;
      if (!h[1] || !h[3]) mid = h[1] ? 1 : 3;
      if (h[mid - 1] && h[mid] && h[mid + 1])
        object_jump = std::max(object_jump, std::fabs(*h[mid - 1] + *h[mid + 1] - 2.0 * *h[mid]) / size);
    }
    if (object_jump < 0.0) continue;  // an object less than three texels across
    // Neither has a crease, or both have (an edge on the other's ridge: neither is the face).
    if ((plane_jump > kCreaseSlopeJump) == (object_jump > kCreaseSlopeJump)) continue;
    if (plane_jump > kCreaseSlopeJump) {
      if (centre->n_up) c.n_local = *centre->n_up;
    } else {
      const Eigen::Vector3d n = surface.texelNormal(c.i, c.j, tex::resolveIndex(c.i, map.width(), address),
                                                    tex::resolveIndex(c.j, map.height(), address));
      c.n_local = bend ? bend->tilt(n, c.p_surface.x(), c.p_surface.y()) : n;
    }
  }
}

}  // namespace thx::phys
