#include "clients/physics/textured_ball.hpp"

#include "meshes/textured_ball_mesh.hpp"

namespace thx::phys {

namespace {
// Where the texture is read for a point of the ball's chart: one tile across tile_m.
tex::TexCoord uvOf(const mesh::BallChartPoint& chart, const FaceTexture& texture) {
  return {chart.uv_m.x() / texture.tile_m, chart.uv_m.y() / texture.tile_m};
}
}  // namespace

FacePoint ballTextureAt(const FaceTexture& texture, double radius_m, const Eigen::Vector3d& p) {
  const mesh::BallChartPoint chart = mesh::ballChartAt(p, radius_m);
  const tex::Sample s = tex::sample(*texture.map, uvOf(chart, texture), texture.sampling);
  FacePoint f;
  f.axis = chart.axis;
  f.sign = chart.sign;
  f.recess_m = double(s.depth);
  // The map's normal is its depth's gradient (x along u, y along v, z out): n = N + d_u du + d_v dv
  // with d_u = n_x / n_z, exact for the chart's non-orthogonal gradients (textured_ball_mesh.hpp).
  f.normal_object = (double(s.normal.z()) * p.normalized() + double(s.normal.x()) * chart.du +
                     double(s.normal.y()) * chart.dv)
                        .normalized();
  return f;
}

double ballRecessAt(const FaceTexture& texture, double radius_m, const Eigen::Vector3d& p) {
  return ballRecessAtUnit(texture, radius_m, p.normalized());
}

double ballRecessAtUnit(const FaceTexture& texture, double radius_m, const Eigen::Vector3d& w) {
  return double(tex::sampleDepth(*texture.map, uvOf(mesh::ballChartUvAtUnit(w, radius_m), texture), texture.sampling));
}

namespace {
// Marks a shape whose user pointer is a FaceTexture laid on a ball ("TBAL").
constexpr int kBallTextureTag = 0x5442414c;
// Marks (in its second user index) such a shape whose FaceTexture is a GriddedBallTexture ("TBGR").
constexpr int kBallGridTag = 0x54424752;
}  // namespace

void attachBallTexture(btCollisionShape& sphere, const FaceTexture& texture) {
  attachObjectTexture(sphere, texture, kBallTextureTag);
  sphere.setUserIndex2(-1);
}

void attachBallTexture(btCollisionShape& sphere, const GriddedBallTexture& texture) {
  attachObjectTexture(sphere, texture, kBallTextureTag);
  sphere.setUserIndex2(kBallGridTag);
}

const BallTexelGrid* ballTexelGridOf(const btCollisionShape& shape) {
  const FaceTexture* texture = ballTextureOf(shape);
  if (!texture || shape.getUserIndex2() != kBallGridTag) return nullptr;
  return static_cast<const GriddedBallTexture*>(texture)->grid;
}

const FaceTexture* ballTextureOf(const btCollisionShape& shape) {
  return objectTextureOf(shape, SPHERE_SHAPE_PROXYTYPE, kBallTextureTag);
}

bool hasObjectTexture(const btCollisionShape& shape) {
  return faceTextureOf(shape) != nullptr || ballTextureOf(shape) != nullptr;
}

}  // namespace thx::phys
