#include "clients/physics/ball_texel_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "clients/physics/textured_ball.hpp"
#include "textures/sampling.hpp"

namespace thx::phys {

namespace {
// The first and last texel index whose centre, (index + 1/2) texel, lies on a face (within a
// quarter turn's arc of its centre either way).
void texelsOnFace(double half_arc_m, double texel_m, int& first, int& last) {
  first = int(std::ceil(-half_arc_m / texel_m - 0.5));
  last = int(std::floor(half_arc_m / texel_m - 0.5));
}
}  // namespace

void BallTexelGrid::pointAtOffset(int face, int k, int l, double du, double dv, Eigen::Vector3d& w,
                                  double& recess) const {
  const double tu = tan_offset_u_[std::size_t(std::lround(du * kOffsetSteps) + kOffsetSteps)];
  const double tv = tan_offset_v_[std::size_t(std::lround(dv * kOffsetSteps) + kOffsetSteps)];
  const double a = tan_u_[std::size_t(k)], b = tan_v_[std::size_t(l)];
  // tan(x + y) = (tan x + tan y) / (1 - tan x tan y); the angles stay within a texel of 45 degrees.
  w = unit(face, (a + tu) / (1.0 - a * tu), (b + tv) / (1.0 - b * tv));
  const double u_m = (k + k_first_ + 0.5 + du) * texel_u_m_, v_m = (l + l_first_ + 0.5 + dv) * texel_v_m_;
  if (std::fabs(u_m) <= half_arc_m_ && std::fabs(v_m) <= half_arc_m_)
    recess = double(tex::sampleDepth(*texture_.map, {u_m / texture_.tile_m, v_m / texture_.tile_m}, texture_.sampling));
  else
    recess = ballRecessAtUnit(texture_, radius_m_, w);
}

Eigen::Vector3d BallTexelGrid::directionAt(int face, double k, double l) const {
  return unit(face, std::tan((k + k_first_ + 0.5) * texel_u_m_ / radius_m_),
              std::tan((l + l_first_ + 0.5) * texel_v_m_ / radius_m_));
}

void BallTexelGrid::texelNearest(const Eigen::Vector3d& w, int& face, int& k, int& l) const {
  int a = 0;
  for (int i = 1; i < 3; ++i)
    if (std::fabs(w[i]) > std::fabs(w[a])) a = i;
  face = 2 * a + (w[a] < 0.0 ? 1 : 0);
  const double wa = std::fabs(w[a]);
  const double u = radius_m_ * std::atan(w[(a + 1) % 3] / wa), v = radius_m_ * std::atan(w[(a + 2) % 3] / wa);
  k = std::clamp(int(std::floor(u / texel_u_m_)) - k_first_, 0, columns() - 1);
  l = std::clamp(int(std::floor(v / texel_v_m_)) - l_first_, 0, rows() - 1);
}

std::unique_ptr<const BallTexelGrid> BallTexelGrid::build(const FaceTexture& texture, double radius_m) {
  if (!texture.map || !(radius_m > 0.0) || !(texture.tile_m > 0.0)) return nullptr;
  const tex::TextureMap& map = *texture.map;
  std::unique_ptr<BallTexelGrid> g(new BallTexelGrid);
  g->texture_ = texture;
  g->radius_m_ = radius_m;
  g->texel_u_m_ = texture.tile_m / double(map.width());
  g->texel_v_m_ = texture.tile_m / double(map.height());
  const double half_arc = 0.25 * std::numbers::pi * radius_m;
  g->half_arc_m_ = half_arc;
  for (int i = -kOffsetSteps; i <= kOffsetSteps; ++i) {
    g->tan_offset_u_.push_back(std::tan(double(i) / kOffsetSteps * g->texel_u_m_ / radius_m));
    g->tan_offset_v_.push_back(std::tan(double(i) / kOffsetSteps * g->texel_v_m_ / radius_m));
  }
  int k_last = 0, l_last = 0;
  texelsOnFace(half_arc, g->texel_u_m_, g->k_first_, k_last);
  texelsOnFace(half_arc, g->texel_v_m_, g->l_first_, l_last);
  if (k_last < g->k_first_ || l_last < g->l_first_) return nullptr;
  // Each column's and row's tangent, and the map's texel there as the contacts' reading finds it
  // (textured_ball.cpp: uv = uv_m / tile; a texel centre is where its bilinear weight is whole).
  std::vector<int> map_i, map_j;
  for (int k = g->k_first_; k <= k_last; ++k) {
    const double u_m = (k + 0.5) * g->texel_u_m_;
    g->tan_u_.push_back(std::tan(u_m / radius_m));
    map_i.push_back(tex::texelOf(map, {u_m / texture.tile_m, 0.5}, texture.sampling.address).i);
  }
  for (int l = g->l_first_; l <= l_last; ++l) {
    const double v_m = (l + 0.5) * g->texel_v_m_;
    g->tan_v_.push_back(std::tan(v_m / radius_m));
    map_j.push_back(tex::texelOf(map, {0.5, v_m / texture.tile_m}, texture.sampling.address).j);
  }
  g->recess_.resize(map_i.size() * map_j.size(), 0.0f);
  if (map.isRelief())
    for (std::size_t l = 0; l < map_j.size(); ++l)
      for (std::size_t k = 0; k < map_i.size(); ++k) g->recess_[g->at(int(k), int(l))] = map.depth(map_i[k], map_j[l]);
  for (const float recess : g->recess_) g->deepest_recess_m_ = std::max(g->deepest_recess_m_, double(recess));
  for (int f = 0; f < 6; ++f)
    for (int l0 = 0; l0 < g->rows(); l0 += kBlock)
      for (int k0 = 0; k0 < g->columns(); k0 += kBlock) {
        Block b;
        b.k0 = k0, b.l0 = l0;
        b.k1 = std::min(k0 + kBlock, g->columns()), b.l1 = std::min(l0 + kBlock, g->rows());
        b.centre = g->direction(f, (b.k0 + b.k1 - 1) / 2, (b.l0 + b.l1 - 1) / 2);
        double cos_spread = 1.0;
        for (const int k : {b.k0, b.k1 - 1})
          for (const int l : {b.l0, b.l1 - 1}) cos_spread = std::min(cos_spread, b.centre.dot(g->direction(f, k, l)));
        b.cos_spread = std::clamp(cos_spread, -1.0, 1.0);
        b.sin_spread = std::sqrt(1.0 - b.cos_spread * b.cos_spread);
        b.spread = std::acos(b.cos_spread);
        g->blocks_[std::size_t(f)].push_back(b);
      }
  return g;
}

}  // namespace thx::phys
