#pragma once
// A textured object's surface seen from a relief plane under it (plane frame): a box whose faces
// carry a relief (textured_box.hpp) or a ball with a bump map (textured_ball.hpp). Over a point
// of the plane, the object's lowest surface pushed inwards by its relief there (along the
// vertical: the recess divided by the cosine between the smooth surface's outward normal and the
// plane's downward), and that relief's normal turned to face the plane's way. The rasteriser
// reads the pair's depth through it (relief_raster.hpp), the pair's normal rule its neighbours
// (pair_contact_normal.hpp).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>

#include "clients/physics/textured_box.hpp"
#include "clients/physics/underside.hpp"

namespace thx::phys {

struct ObjectSurfacePoint {
  double z = 0.0;                         // the surface's height in the plane frame
  std::optional<Eigen::Vector3d> n_up;    // the relief's normal, unit, +z side; absent where the
                                          // surface is steeper than kSteepestTexturedFaceCos (not
                                          // read there)
};

class TexturedObjectSurface {
 public:
  // `object`: a box (its faces' layout) or a sphere (the ball's); both must outlive this.
  TexturedObjectSurface(const Underside& object, const FaceTexture& texture);
  // Over (x, y), whose vertical line first meets the object at height `lowest_z` (lowestZ).
  ObjectSurfacePoint over(double x, double y, double lowest_z) const;
  // Its z alone, as over() reads it to the bit (the texture read for its depth only).
  double zOver(double x, double y, double lowest_z) const;
  // Over (x, y); nullopt where the vertical line misses the object.
  std::optional<ObjectSurfacePoint> at(double x, double y) const;

  // A box's surface where the vertical line enters it at p_object (object frame) at height
  // lowest_z, read in two parts: its z, and its relief's normal (boxNormalUp) only where wanted.
  // over() and zOver() read a box through it, and so does the raster's row reader
  // (textured_box_rows.hpp), which knows p_object without the pose applied again.
  struct BoxPoint {
    double z = 0.0;
    bool steep = false;  // a face beyond kSteepestTexturedFaceCos: its z is lowest_z, no normal
    FaceSample sample;
  };
  BoxPoint boxAt(const Eigen::Vector3d& p_object, double lowest_z) const;
  // As over() gives it: unit, turned to the plane's +z side; absent on a steep face.
  std::optional<Eigen::Vector3d> boxNormalUp(const BoxPoint& p) const;

 private:
  // A box's face's outward normal against the plane's -z.
  double faceDown(const FacePoint& face) const;
  const Underside& object_;
  const FaceTexture& texture_;
  Eigen::Isometry3d object_from_plane_;
  Eigen::Vector3d down_object_;  // the plane's -z in the object frame
};

}  // namespace thx::phys
