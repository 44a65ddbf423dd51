#pragma once
// The texel centres of a ball's bump map as points of the ball (its material points): on each
// face of the cube laid on the ball (textured_ball.hpp, meshes/textured_ball_mesh.hpp), the
// direction from the centre to every texel centre of the texture over that face, and the recess
// there. Built once per textured ball (PhysicsWorld::addTexturedSphere; allocates), read every
// step by ball_on_flat_ground.hpp.
//
// A face's texel (k, l) has its centre at u = (k + k_first + 1/2) texel_u, v = (l + l_first + 1/2)
// texel_v (metres of arc from the face's centre, ballChartUvAtUnit's uv_m): its direction has the
// tangents of u / r and v / r along the face's two other axes, which are kept per column and row,
// and its recess is the map's texel there, kept per texel of one face (the same on every face:
// each lays the texture alike).
//
// Why the ball's own texels: on flat ground the pair's depth is the ball's own surface height, so
// its basins are the ball's lowest points, which move with the ball. Sampled at the ground's
// texels instead (the relief's, or a smooth chart's laid under the ball), a dimple's rim, a sharp
// crest, was read wherever a ground sample happened to fall near it, and a dimpled ball left on a
// flat floor rocked on those samples (docs/physics.md, "A ball with a bump map on flat ground").
#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <vector>

#include "clients/physics/textured_box.hpp"

namespace thx::phys {

class BallTexelGrid {
 public:
  // nullptr for a texture without a map or a ball without a radius or a tile.
  static std::unique_ptr<const BallTexelGrid> build(const FaceTexture& texture, double radius_m);

  int columns() const { return int(tan_u_.size()); }
  int rows() const { return int(tan_v_.size()); }
  std::size_t at(int k, int l) const { return std::size_t(l) * tan_u_.size() + std::size_t(k); }

  // The unit direction of texel (k, l)'s centre on face `face` (axis face / 2, its sign - for odd).
  Eigen::Vector3d direction(int face, int k, int l) const {
    return unit(face, tan_u_[std::size_t(k)], tan_v_[std::size_t(l)]);
  }
  // The recess at texel (k, l)'s centre (any face), and by its index at().
  double recess(int k, int l) const { return double(recess_[at(k, l)]); }
  double recess(std::size_t texel) const { return double(recess_[texel]); }
  // The deepest recess of any texel centre: every texel's point lies within r - deepest and r of
  // the centre.
  double deepestRecess() const { return deepest_recess_m_; }
  // The tangents of a column's and a row's angle: a texel's direction is (+-1, tanU, tanV) along
  // the face's axes (a, a + 1, a + 2), divided by its length.
  double tanU(int k) const { return tan_u_[std::size_t(k)]; }
  double tanV(int l) const { return tan_v_[std::size_t(l)]; }
  // The unit direction of the point at (k, l) texels of face `face`, fractions allowed: between
  // the centres, and past the face's edge onto the next face's part of the ball.
  Eigen::Vector3d directionAt(int face, double k, double l) const;

  // The point of face `face` at (k + du, l + dv) texels, du and dv within [-1, 1] in steps of
  // 1 / kOffsetSteps (a search's offsets from a texel centre): its unit direction and its recess,
  // read as the contacts read it (ballRecessAtUnit) from the texture coordinates it has, or past
  // the face's edge from its direction. No trigonometry: the tangents of the offsets are tabled
  // and added to the texel's own.
  static constexpr int kOffsetSteps = 1024;
  void pointAtOffset(int face, int k, int l, double du, double dv, Eigen::Vector3d& w, double& recess) const;

  // The texel whose centre lies nearest unit direction `w` (the one whose square holds it): on the
  // face `w` lies most along.
  void texelNearest(const Eigen::Vector3d& w, int& face, int& k, int& l) const;

  double radius() const { return radius_m_; }
  double texelU() const { return texel_u_m_; }
  double texelV() const { return texel_v_m_; }

  // Square blocks of up to kBlock x kBlock texels of a face, each with the direction of its
  // middle texel and the largest angle from it to a texel of the block (at a corner: the block's
  // sides are arcs of great circles): a search skips a block whose every texel lies too far round.
  static constexpr int kBlock = 16;
  struct Block {
    Eigen::Vector3d centre = Eigen::Vector3d::UnitZ();
    double spread = 0.0;                        // that largest angle (radians)
    double cos_spread = 1.0, sin_spread = 0.0;  // and its cosine and sine
    int k0 = 0, l0 = 0, k1 = 0, l1 = 0;         // texels [k0, k1) x [l0, l1)
  };
  const std::vector<Block>& blocks(int face) const { return blocks_[std::size_t(face)]; }

 private:
  BallTexelGrid() = default;
  static Eigen::Vector3d unit(int face, double tan_u, double tan_v) {
    const int a = face / 2, b = (a + 1) % 3, d = (a + 2) % 3;
    Eigen::Vector3d w;
    w[a] = face % 2 ? -1.0 : 1.0;
    w[b] = tan_u;
    w[d] = tan_v;
    return w / std::sqrt(1.0 + tan_u * tan_u + tan_v * tan_v);
  }

  FaceTexture texture_;  // its map must outlive the grid
  double radius_m_ = 0.0, texel_u_m_ = 0.0, texel_v_m_ = 0.0, half_arc_m_ = 0.0, deepest_recess_m_ = 0.0;
  std::vector<double> tan_offset_u_, tan_offset_v_;  // tan(i texel / kOffsetSteps / r), i in [-kOffsetSteps, kOffsetSteps]
  int k_first_ = 0, l_first_ = 0;
  std::vector<double> tan_u_, tan_v_;  // per column and row
  std::vector<float> recess_;          // per texel (k, l), as the map stores it
  std::array<std::vector<Block>, 6> blocks_;
};

}  // namespace thx::phys
