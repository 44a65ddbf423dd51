#pragma once
// Two renderer outputs the same to the bit, field by field (server/proxy_renderer.hpp's
// RenderOutput): the check that a renderer's two halves (renderForce, describeContact) say what
// its render() says. expectSameForce: the fields renderForce() fills, which the servo acts on
// before the force is written; expectSameOutput: every field. expectDescribedAt checks the
// description itself, against a renderer at the world's origin.
#include <gtest/gtest.h>

#include <string>

#include "server/proxy_renderer.hpp"

namespace thx::test {

// NaN equals NaN here: a non-finite tip's proxy, projection and uv are the tip's.
inline bool sameBits(double x, double y) { return x == y || (x != x && y != y); }
inline bool sameBits(const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
  return sameBits(x.x(), y.x()) && sameBits(x.y(), y.y()) && sameBits(x.z(), y.z());
}
inline void expectSameForce(const srv::RenderOutput& a, const srv::RenderOutput& b, const std::string& where) {
  EXPECT_EQ(a.in_contact, b.in_contact) << where;
  EXPECT_EQ(a.recovering, b.recovering) << where;
  EXPECT_EQ(a.proxy_held, b.proxy_held) << where;
  EXPECT_TRUE(sameBits(a.force_world, b.force_world)) << where;
  EXPECT_TRUE(sameBits(a.proxy_world, b.proxy_world)) << where;
  EXPECT_TRUE(sameBits(a.depth_m, b.depth_m)) << where;
  EXPECT_TRUE(sameBits(a.f_normal_n, b.f_normal_n)) << where;
  EXPECT_EQ(a.active_mask, b.active_mask) << where;
  ASSERT_EQ(a.num_planes, b.num_planes) << where;
  for (int i = 0; i < a.num_planes; ++i) {
    const dev::PlaneProxy &p = a.planes[std::size_t(i)], &q = b.planes[std::size_t(i)];
    EXPECT_TRUE(sameBits(p.n_world, q.n_world)) << where << ", plane " << i;
    EXPECT_TRUE(sameBits(p.d_m, q.d_m)) << where << ", plane " << i;
    EXPECT_EQ(p.k_n_per_m, q.k_n_per_m) << where << ", plane " << i;
    EXPECT_EQ(p.b_ns_per_m, q.b_ns_per_m) << where << ", plane " << i;
  }
}

inline void expectSameOutput(const srv::RenderOutput& a, const srv::RenderOutput& b, const std::string& where) {
  expectSameForce(a, b, where);
  EXPECT_TRUE(sameBits(a.p_proj_world, b.p_proj_world)) << where;
  EXPECT_TRUE(sameBits(a.uv.u, b.uv.u) && sameBits(a.uv.v, b.uv.v)) << where;
  EXPECT_EQ(a.texel.i, b.texel.i) << where;
  EXPECT_EQ(a.texel.j, b.texel.j) << where;
  EXPECT_TRUE(sameBits(a.n_geom_world, b.n_geom_world)) << where;
  EXPECT_TRUE(sameBits(a.n_sampled_world, b.n_sampled_world)) << where;
  EXPECT_TRUE(sameBits(a.relief_depth_m, b.relief_depth_m)) << where;
  EXPECT_TRUE(sameBits(a.v_tangent_world, b.v_tangent_world)) << where;
  EXPECT_EQ(a.triangle, b.triangle) << where;
  EXPECT_TRUE(sameBits(a.barycentric, b.barycentric)) << where;
  EXPECT_TRUE(sameBits(a.tangent_world, b.tangent_world)) << where;
  EXPECT_TRUE(sameBits(a.bitangent_world, b.bitangent_world)) << where;
}

// What a renderer placed in the world by `place` says of where the contact is (`placed`), against
// the same renderer at the world's origin given the same tip there (`local`): the same place, moved
// and turned by `place`. Within `tol` (the placed renderer works from a tip moved there and back).
inline void expectDescribedAt(const Eigen::Isometry3d& place, const srv::RenderOutput& local,
                              const srv::RenderOutput& placed, double tol, const std::string& where) {
  const Eigen::Matrix3d r = place.linear();
  EXPECT_LT((place * local.p_proj_world - placed.p_proj_world).norm(), tol) << where;
  EXPECT_LT((r * local.n_geom_world - placed.n_geom_world).norm(), tol) << where;
  EXPECT_LT((r * local.tangent_world - placed.tangent_world).norm(), tol) << where;
  EXPECT_LT((r * local.bitangent_world - placed.bitangent_world).norm(), tol) << where;
  EXPECT_LT((r * local.n_sampled_world - placed.n_sampled_world).norm(), tol) << where;
  EXPECT_LT((r * local.v_tangent_world - placed.v_tangent_world).norm(), tol) << where;
  EXPECT_NEAR(local.uv.u, placed.uv.u, tol) << where;
  EXPECT_NEAR(local.uv.v, placed.uv.v, tol) << where;
  EXPECT_NEAR(local.relief_depth_m, placed.relief_depth_m, tol) << where;
}

}  // namespace thx::test
