#pragma once
// Conversions between Bullet's float types and Eigen's doubles. Bullet here is the float build
// (pkg-config `bullet`, sizeof(btScalar) == 4); we do our geometry in double and narrow only at
// the boundary, explicitly, so -Wconversion stays quiet and the narrowing is visible.
#include <LinearMath/btTransform.h>
#include <LinearMath/btVector3.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace thx::phys {

inline btVector3 toBt(const Eigen::Vector3d& v) {
  return {static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()), static_cast<btScalar>(v.z())};
}
inline Eigen::Vector3d toEigen(const btVector3& v) { return {double(v.x()), double(v.y()), double(v.z())}; }

inline btMatrix3x3 toBt(const Eigen::Matrix3d& m) {
  btMatrix3x3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[i][j] = static_cast<btScalar>(m(i, j));
  return r;
}
inline Eigen::Matrix3d toEigen(const btMatrix3x3& m) {
  Eigen::Matrix3d r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = double(m[i][j]);
  return r;
}

inline btTransform toBt(const Eigen::Isometry3d& t) { return btTransform(toBt(Eigen::Matrix3d(t.linear())), toBt(Eigen::Vector3d(t.translation()))); }
inline Eigen::Isometry3d toEigen(const btTransform& t) {
  Eigen::Isometry3d r = Eigen::Isometry3d::Identity();
  r.linear() = toEigen(t.getBasis());
  r.translation() = toEigen(t.getOrigin());
  return r;
}

}  // namespace thx::phys
