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

void flatterReliefNormals(const tex::TexturedSurface& surface, const GroundBend* bend, const TexturedObjectSurface& object,
                          std::span<ReliefCandidate> contacts) {
  const tex::TextureMap& map = surface.map();
  const tex::Address address = surface.sampling().address;
  const Eigen::Vector2d texel = surface.mapping().texelSize(map);  // signed: +i is +x, +j is -y
  const double dx = texel.x(), dy = -texel.y();                     // metres per +i, per +j
  for (ReliefCandidate& c : contacts) {
    const double x0 = c.p_surface.x(), y0 = c.p_surface.y();
    // Each surface's heights over the 3 x 3 texels round the contact's (the relief's at its texel
    // centres, as rasterised; the object's at the same offsets from the contact's point).
    double plane[3][3], lower[3][3];
    bool inside = true;
    for (int a = -1; a <= 1 && inside; ++a)
      for (int b = -1; b <= 1 && inside; ++b) {
        const double x = x0 + a * dx, y = y0 + b * dy;
        plane[a + 1][b + 1] = -double(map.depth(tex::resolveIndex(c.i + a, map.width(), address),
                                                tex::resolveIndex(c.j + b, map.height(), address))) +
                              (bend ? bend->height(x, y) : 0.0);
        const std::optional<ObjectSurfacePoint> o = object.at(x, y);
        inside = o.has_value();
        if (o) lower[a + 1][b + 1] = o->z;
      }
    if (!inside) continue;
    auto hessian = [&](const double (&f)[3][3]) {
      Eigen::Matrix2d h;
      h(0, 0) = (f[2][1] + f[0][1] - 2.0 * f[1][1]) / (dx * dx);
      h(1, 1) = (f[1][2] + f[1][0] - 2.0 * f[1][1]) / (dy * dy);
      h(0, 1) = h(1, 0) = (f[2][2] - f[2][0] - f[0][2] + f[0][0]) / (4.0 * dx * dy);
      return h;
    };
    const Eigen::Matrix2d h_plane = hessian(plane), h_object = hessian(lower);
    // The pair's minimum's slope is g_plane + H_plane d, d its offset (pair_contact_normal.hpp): the
    // relief's own where it curves much less than the object.
    if (!(h_plane.norm() <= kFlatterRelief * h_object.norm())) continue;
    const tex::SurfacePoint at = surface.at(x0, y0);  // bilinear, as the refined contact reads it
    c.n_local = bend ? bend->tilt(at.n_local, x0, y0) : at.n_local;
  }
}

}  // namespace thx::phys
