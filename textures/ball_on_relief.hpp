#pragma once
// A relief as a ball meets it. A ball of radius r resting over the height field h (h = -depth)
// has its centre at c(x) = max over t of [h(t) + sqrt(r^2 - |x - t|^2)]: the relief dilated by
// the ball. The point t* it touches gives the normal that pushes it, (x - t*, c - h(t*)) / r, the
// gradient of that surface. So a ball rides the crests of features narrower than it can enter
// (it bridges a brick joint, and the bumps a mesh's pole squeezes to a fraction of a millimetre)
// yet meets a wide bump's full slope, which a box filter of the slopes over its contact patch
// erased (docs/physics.md, "Textured meshes").
//
// The search is a branch and bound over a max-pyramid of the heights: a block of texels is
// skipped when its highest texel, at the block's nearest distance, cannot lift the ball above
// the best touch found so far. The touching texel is then refined on the bilinear height (a few
// fixed-point steps of t = x + sqrt(r^2 - |x - t|^2) grad h(t), each kept only if it lifts the
// ball), so that a flat top pushes straight up and a smooth crest from where it is touched, not
// from the nearest texel centre. Across a sharp crest the step is refused; then the step along
// each axis alone is tried, so that the touch slides along a crest line (a V-groove's rim, a
// brick's edge) to the centre's row and the lift does not ripple a texel along it. At a corner
// the touch stays at a texel centre: the normal leans by at most half a texel over r.
//
// Distances are in metres: the caller gives the metres per uv unit along u and v where the
// texture is laid (a mesh's pole squeezes u), so the same texture is read as the ball meets it
// wherever it lies. Built once (allocates); touch() is real-time safe (no allocation, bounded
// work: at most the texels within r of the centre).
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "textures/sampling.hpp"
#include "textures/texture_map.hpp"

namespace thx::tex {

class BallOnRelief {
 public:
  // `map` must be a relief (maxDepth() > 0); its heights are copied.
  BallOnRelief(const TextureMap& map, Address address);

  // A texel by its unwrapped indices (column i along u, row j against v).
  struct Texel {
    long long i = 0, j = 0;
  };
  struct Touch {
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // tangent space (x along u, y along v, metres), unit
    double lift_m = 0.0;                                // c - r: the centre's height above h = 0, less r
    std::optional<Texel> texel;                         // the texel touched, before refining (none: nothing searched)
  };
  // The texels on one side of the line through the centre along one axis: the relief either side
  // of a crease of the lift (a V-groove's floor, the two rims a ball wider than the groove rests
  // on), where the two sides' lifts cross with different slopes and each side is a smooth branch.
  struct Half {
    int axis = -1;      // 0: along u (tangent x), 1: along v (tangent y); -1: every texel
    double sign = 1.0;  // +1: texels at or beyond the centre along +axis; -1: at or before it
  };
  // The ball of `radius_m` over uv, the texture laid at `metres_per_uv` (u, v) there. From behind
  // (a ball inside a sphere whose winding faces out) the relief is met from its other side: its
  // heights negated, the normal's z and lift along the texture's -z. With `half`, only its texels
  // are met; nullopt where it holds none (a clamped texture's border).
  // `near`: a texel touched by a search nearby (Touch::texel; a lift's differences search five
  // centres a quarter texel apart). Its height at this centre bounds the touch from below, so the
  // blocks lower than it are skipped at once; the result is the same to the bit (the touch found
  // is the first texel of the greatest lift in the search's fixed order, and no block holding one
  // is skipped), only found sooner. A texel outside this search's region is ignored.
  Touch touch(TexCoord uv, const Eigen::Vector2d& metres_per_uv, double radius_m, bool from_behind = false,
              std::optional<Texel> near = std::nullopt) const;
  std::optional<Touch> touchOnHalf(TexCoord uv, const Eigen::Vector2d& metres_per_uv, double radius_m, bool from_behind,
                                   Half half, std::optional<Texel> near = std::nullopt) const;

  int levels() const { return int(front_.size()); }

 private:
  struct Level {
    int width = 0, height = 0;
    std::vector<float> max_height;  // row-major, row 0 = v = 1 (the map's rows)
    float at(int i, int j) const { return max_height[std::size_t(j) * std::size_t(width) + std::size_t(i)]; }
  };
  // The bilinear height at (s, t) and its gradient per texel along s and t.
  double bilinear(const Level& base, double s, double t, Eigen::Vector2d* gradient = nullptr) const;
  std::optional<Touch> search(TexCoord uv, const Eigen::Vector2d& metres_per_uv, double radius_m, bool from_behind,
                              Half half, std::optional<Texel> near) const;
  static std::vector<Level> pyramidOf(Level base);
  double max_depth_m_;
  Address address_;
  // [0]: the heights (h = -depth; from behind, depth); [k]: maxima over 2^k x 2^k texels, while
  // both sides divide.
  std::vector<Level> front_, behind_;
};

}  // namespace thx::tex
