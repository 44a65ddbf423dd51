#include "clients/physics/textured_box.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thx::phys {

namespace {
// The face faceTextureAt reads (its axis and sign; recess and normal left to the caller).
FacePoint faceOf(const Eigen::Vector3d& half, const Eigen::Vector3d& p, const Eigen::Vector3d& toward) {
  FacePoint f;
  double best = -1.0;
  for (int a = 0; a < 3; ++a) best = std::max(best, std::fabs(p[a]) / half[a]);
  double along = -std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (std::fabs(p[a]) / half[a] < best * (1.0 - 1e-9)) continue;  // not on this face
    const double sign = p[a] < 0.0 ? -1.0 : 1.0;
    if (sign * toward[a] > along) along = sign * toward[a], f.axis = a, f.sign = sign;
  }
  // A point on a face standing over the plane (a side, near the bottom's edge) takes the texture
  // of the face turned most towards it, read at the point's place over that face: the bottom's
  // grooves cut through its edge.
  if (along <= kSteepestTexturedFaceCos && toward.squaredNorm() > 0.0) {
    int a_best = 0;
    for (int a = 1; a < 3; ++a)
      if (std::fabs(toward[a]) > std::fabs(toward[a_best])) a_best = a;
    f.axis = a_best;
    f.sign = toward[a_best] < 0.0 ? -1.0 : 1.0;
  }
  return f;
}

// Where on the texture the face `f` holds the object's point p.
tex::TexCoord faceUv(const FaceTexture& texture, const FacePoint& f, const Eigen::Vector3d& p) {
  const int b = (f.axis + 1) % 3, c = (f.axis + 2) % 3;
  return {p[b] / texture.tile_m, p[c] / texture.tile_m};
}
}  // namespace

FaceSample faceSampleAt(const FaceTexture& texture, const Eigen::Vector3d& half, const Eigen::Vector3d& p,
                        const Eigen::Vector3d& toward) {
  const FacePoint f = faceOf(half, p, toward);
  FaceSample s{f, tex::SamplePlace(*texture.map, faceUv(texture, f, p), texture.sampling)};
  s.face.recess_m = double(s.place.depth());
  return s;
}

Eigen::Vector3d faceNormal(const FaceSample& sample) {
  const FacePoint& f = sample.face;
  const int a = f.axis, b = (a + 1) % 3, c = (a + 2) % 3;
  const Eigen::Vector3f m = sample.place.normal();
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  n[b] = double(m.x());
  n[c] = double(m.y());
  n[a] = f.sign * double(m.z());
  return n.normalized();
}

FacePoint faceTextureAt(const FaceTexture& texture, const Eigen::Vector3d& half, const Eigen::Vector3d& p,
                        const Eigen::Vector3d& toward) {
  FaceSample s = faceSampleAt(texture, half, p, toward);
  s.face.normal_object = faceNormal(s);
  return s.face;
}

namespace {
// Marks a shape whose user pointer is a FaceTexture ("TBOX").
constexpr int kFaceTextureTag = 0x54424f58;
}  // namespace

void attachObjectTexture(btCollisionShape& shape, const FaceTexture& texture, int tag) {
  shape.setUserPointer(const_cast<FaceTexture*>(&texture));
  shape.setUserIndex(tag);
}

const FaceTexture* objectTextureOf(const btCollisionShape& shape, int shape_type, int tag) {
  if (shape.getShapeType() != shape_type || shape.getUserIndex() != tag) return nullptr;
  return static_cast<const FaceTexture*>(shape.getUserPointer());
}

void attachFaceTexture(btCollisionShape& box, const FaceTexture& texture) {
  attachObjectTexture(box, texture, kFaceTextureTag);
}

const FaceTexture* faceTextureOf(const btCollisionShape& shape) {
  return objectTextureOf(shape, BOX_SHAPE_PROXYTYPE, kFaceTextureTag);
}

}  // namespace thx::phys
