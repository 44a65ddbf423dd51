#pragma once
// Meso-level excitation from a normal map (docs/design.md §1 Eq. 5): a contact moving with
// tangential velocity v_t over a texel with sampled normal n_s, on a surface of geometric normal
// n_g, carries the normal momentum
//   p_n = m (-(v_t . n_s) / (n_g . n_s)) n_g,
// and every texel it enters applies the change of p_n from the texel it left as an impulse.
// Both momenta are taken at the current velocity, so the impulse is the texture's relief and not
// the hand's acceleration; a uniformly tilted region gives none, a flat map exactly none.
//
// Texels are walked with the textures library's texel walk (textures/sampling.hpp), so a fast
// contact skips none, and each texel's own (nearest) normal is used, as the paper does, never the
// bilinear one. n_g . n_s is floored at min_normal_dot, so |p_n| <= m |v_t| / min_normal_dot
// stays bounded as the normals approach perpendicular.
// Vectors are in the texture's tangent frame (+x = image right, +y = image up, +z out of it).
#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <vector>

#include "textures/sampling.hpp"
#include "textures/texture_map.hpp"

namespace thx::audio {

struct MesoSurface {
  const tex::TextureMap* map = nullptr;
  tex::Address address = tex::Address::Wrap;
  Eigen::Vector3d geometric_normal{0.0, 0.0, 1.0};  // n_g, unit
  double mass_kg = 0.0;                             // the moving object's (the pen's effective) mass
  double min_normal_dot = 0.05;                     // floor of n_g . n_s
};

struct MesoImpulse {
  tex::TexelIndex texel;   // the texel entered
  Eigen::Vector3d impulse; // N s, along n_g
};

// A contact's walk so far: the texel it is in.
struct MesoState {
  bool started = false;
  tex::TexelIndex texel;
};

// Eq. 5's normal momentum over a texel of normal n_s.
Eigen::Vector3d mesoMomentum(const MesoSurface& surface, const Eigen::Vector3f& sampled_normal,
                             const Eigen::Vector3d& velocity);

// The impulses of the segment a -> b, at velocity `velocity` (its normal component is removed).
// The texel the contact is already in (state) gives none; each texel entered after it gives one.
// Allocation-free; `emit(const MesoImpulse&)`. Returns the number of impulses.
template <class Emit>
std::size_t mesoImpulsesAlong(const MesoSurface& surface, MesoState& state, tex::TexCoord a, tex::TexCoord b,
                              const Eigen::Vector3d& velocity, Emit&& emit) {
  const tex::TextureMap& map = *surface.map;
  std::size_t count = 0;
  tex::walkTexels(map, a, b, surface.address, [&](tex::TexelIndex t) {
    if (state.started && !(t == state.texel)) {
      const Eigen::Vector3d impulse = mesoMomentum(surface, map.normal(t.i, t.j), velocity) -
                                      mesoMomentum(surface, map.normal(state.texel.i, state.texel.j), velocity);
      emit(MesoImpulse{t, impulse});
      ++count;
    }
    state.started = true;
    state.texel = t;
    return true;
  });
  return count;
}

struct PathPoint {
  tex::TexCoord uv;
  Eigen::Vector3d velocity{0.0, 0.0, 0.0};  // m/s; the segment ending here moves at this velocity
};

// Every impulse of a contact's path, in order (a pure function of the path).
std::vector<MesoImpulse> mesoImpulses(const MesoSurface& surface, std::span<const PathPoint> path);

}  // namespace thx::audio
