#pragma once
// A textured box's surface over the texels of a raster row (relief_raster.cpp): what lowestZ and
// TexturedObjectSurface::zOver and over give there (to rounding: the slabs' sines are taken as
// reciprocals), with what the box and a row share worked out once. A point's object coordinates
// are its slab coordinates, which the vertical line's slabs already take, not the pose applied
// again; the surface there is TexturedObjectSurface::boxAt's, its face's texture read once for
// its depth and, where the texel is a candidate, its normal. The raster reads a grooved 2 cm
// block at 4,200 texels a step, and those reads were half of its step (docs/physics.md, "What it
// costs").
#include <Eigen/Core>
#include <array>
#include <optional>

#include "clients/physics/textured_object_surface.hpp"
#include "clients/physics/underside.hpp"

namespace thx::phys {

class TexturedBoxRows {
 public:
  // The box (plane frame) and its textured surface; both must outlive this.
  TexturedBoxRows(const Underside& box, const TexturedObjectSurface& surface);

  // Over a texel: the box's lowest point and its textured surface there.
  struct Point {
    double lowest_z = 0.0;
    TexturedObjectSurface::BoxPoint surface;
  };
  // The row at plane height y; then at(x) reads its texels.
  void startRow(double y);
  // Over (x, the row's y); false where the vertical line misses the box.
  bool at(double x, Point& out) const;
  // The relief's normal at `p`, unit, turned to the plane's +z side; absent on a steep face.
  std::optional<Eigen::Vector3d> nUp(const Point& p) const { return surface_.boxNormalUp(p.surface); }

 private:
  const TexturedObjectSurface& surface_;
  Eigen::Vector3d centre_;
  std::array<Eigen::Vector3d, 3> axes_;   // the box's axes in the plane frame
  std::array<double, 3> half_{}, inv_sine_{};
  std::array<bool, 3> parallel_{};        // an axis the vertical crosses at |sin| < kParallelSine
  std::array<double, 3> row_part_{};      // a slab coordinate's part from the row's y
};

}  // namespace thx::phys
