#pragma once
// A texture's slopes averaged over ever larger squares of texels: level 0 holds each texel's
// slopes (the height's gradient in the texture's tangent space, dh/du and dh/dv per texel side:
// -nx/nz, -ny/nz of its normal), level k their mean over 2^k x 2^k texels. Averaging the gradient
// is box-filtering the height it comes from, so level k is the relief as a body sees it that
// cannot follow features smaller than 2^k texels: a ball resting on a relief bridges what is
// narrower than its contact patch (clients/physics/mesh_contact.hpp). Over a whole tile of a
// texture that wraps the mean slope is 0 (the height comes back to where it started); the 16-bit
// normals leave a small mean, which a wrapped pyramid removes from every texel: where a mesh
// squeezes the texture (a lathe's pole) that mean would otherwise be read over many tiles and
// scaled up with the squeeze, a slope the relief does not have.
// Built once (allocates, a third more than level 0); sampling is real-time safe.
#include <Eigen/Core>
#include <vector>

#include "textures/sampling.hpp"
#include "textures/texture_map.hpp"

namespace thx::tex {

class SlopePyramid {
 public:
  // `address`: how the texture continues beyond its tile (Wrap: periodic, its mean slope removed).
  SlopePyramid(const TextureMap& map, Address address);

  int levels() const { return int(levels_.size()); }
  // The slopes at uv box-filtered over 2^lod texels: bilinear within a level, linear between the
  // two levels around a fractional lod (clamped to [0, levels() - 1]), texels wrapped or clamped
  // by `address`.
  Eigen::Vector2d slopes(TexCoord uv, double lod, Address address) const;
  // The same as a unit normal in tangent space: (-dh/du, -dh/dv, 1), normalised.
  Eigen::Vector3d normal(TexCoord uv, double lod, Address address) const;

 private:
  struct Level {
    int width = 0, height = 0;
    std::vector<Eigen::Vector2f> slopes;  // row-major, row 0 = v = 1 (the map's rows)
    Eigen::Vector2f at(int i, int j) const { return slopes[std::size_t(j) * std::size_t(width) + std::size_t(i)]; }
  };
  Eigen::Vector2d bilinear(const Level& level, TexCoord uv, Address address) const;
  std::vector<Level> levels_;
};

}  // namespace thx::tex
