#pragma once
// Normals -> heights: the relief a normal map's slopes stand for.
//
// A map's normals are the slopes of its relief at the size it was made for (docs/meshes.md): with
// the texel size in metres, dh/dx = -n.x / n.z and dh/dy = -n.y / n.z (the TextureMap tangent
// frame, +y up the image). The heights are the least-squares surface whose central differences
// (height_normals.hpp's, so a map made from heights gives its heights back) best match those
// slopes, solved in Fourier space (Frankot and Chellappa, 1988): exact for a periodic map
// (Address::Wrap); with Address::Clamp the slopes are mirrored first, so the surface is read as
// even across each border instead of wrapping round. A normal map need not be integrable (one
// imported from a photograph): the answer is then the surface nearest its slopes. The mean height
// is zero. Offline (allocates); not for the servo.
#include <Eigen/Core>
#include <string>

#include "textures/height_normals.hpp"
#include "textures/sampling.hpp"
#include "textures/texture_map.hpp"

namespace thx::tex {

// A map whose mean slope (its norm) is within this is level on average: its relief, periodic,
// loses nothing of it. A mean slope above it is a lean the relief cannot hold; users of the
// relief say so.
inline constexpr double kLevelMeanSlope = 1e-3;

struct IntegratedNormals {
  HeightField heights;
  // What a periodic relief cannot hold (Address::Wrap): the slopes' mean (dh/dx, dh/dy), all of a
  // uniformly tilted map. Zero with Address::Clamp, whose mirrored surface keeps its ramp.
  Eigen::Vector2d mean_slope = Eigen::Vector2d::Zero();
};

// texel_m: the texel's size in metres along x and y where the map was made (finite, > 0).
IntegratedNormals heightsFromNormals(const TextureMap& map, const Eigen::Vector2d& texel_m, Address address);

// Those heights as a relief map (reliefFromHeight), for a map made for a tile of `tile_m` metres,
// with the mean slope the relief cannot hold. `source` names the relief in error messages.
struct ReliefOfNormals {
  TextureMap relief;
  Eigen::Vector2d mean_slope = Eigen::Vector2d::Zero();
};
ReliefOfNormals reliefFromNormals(const TextureMap& map, const Eigen::Vector2d& tile_m, Address address,
                                  const std::string& source = "the relief of a normal map");

}  // namespace thx::tex
