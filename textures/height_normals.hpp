#pragma once
// Height field -> normals and relief maps.
//
// A HeightField holds heights in metres, positive UP (out of the surface), row-major with row 0
// at the TOP of the image, like TextureMap. Normals follow the TextureMap tangent frame
// (+x = image right, +y = image up, i.e. decreasing row): for h(x, y),
//   n ∝ (-dh/dx, -dh/dy, 1),
// where dh/dy at texel (i, j) is estimated from rows j-1 (above, +y) and j+1 (below).
//
// Gradients are central differences. At the border, Address::Wrap treats the field as periodic;
// Address::Clamp uses a one-sided difference there (replicating the edge row would halve the
// slope at the border). Central differences are second-order accurate: for a feature of
// wavelength L sampled at texel size d the slope error is about (2*pi*d/L)^2 / 6 of the slope
// (tests/textures/test_height_normals.cpp measures it).
//
// No OpenCV here: thx_textures is linked by the real-time server.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "textures/sampling.hpp"
#include "textures/texture_map.hpp"

namespace thx::tex {

struct HeightField {
  int width = 0;
  int height = 0;
  std::vector<double> heights_m;  // row-major, row 0 = top, +up

  HeightField() = default;
  HeightField(int w, int h, double value_m = 0.0)
      : width(w), height(h), heights_m(std::size_t(w > 0 ? w : 0) * std::size_t(h > 0 ? h : 0), value_m) {}

  double at(int i, int j) const { return heights_m[std::size_t(j) * std::size_t(width) + std::size_t(i)]; }
  double& at(int i, int j) { return heights_m[std::size_t(j) * std::size_t(width) + std::size_t(i)]; }
};

// Depth range given to a relief map built from a flat height field: TextureMap needs a maximum
// depth > 0, and 1 nm is far below anything a device or a renderer resolves.
inline constexpr double kFlatReliefDepth_m = 1e-9;

// Throws TextureError (naming `source`) if the size is outside [kMinTextureSide, kMaxTextureSide],
// the sample count does not match the size, or a height is not finite (naming the first bad
// sample (i, j) in row-major order and how many there are).
void checkHeightField(const HeightField& field, const std::string& source = "height field");

// Unit normal at texel (i, j); texel_m = (size along x, size along y) in metres, both finite > 0.
// Unchecked: the caller has validated the field (checkHeightField) and the index.
Eigen::Vector3d heightNormalAt(const HeightField& field, int i, int j, const Eigen::Vector2d& texel_m,
                               Address address);

// Unit normals for every texel, row-major like the field. Validates the field and texel size.
std::vector<Eigen::Vector3f> normalsFromHeight(const HeightField& field, const Eigen::Vector2d& texel_m,
                                               Address address, const std::string& source = "height field");

struct ReliefFromHeightOptions {
  Eigen::Vector2d texel_m{0.0, 0.0};  // required: texel size in metres along x and y
  Address address = Address::Clamp;   // border rule for the gradients
  Representation representation = Representation::Relief;
  std::string source = "height field";  // names the input in error messages
};

// Relief: depth = max(h) - h, maxDepth = max(h) - min(h) (kFlatReliefDepth_m when flat), normals
// from the gradients. Normal: the same normals, no depth.
// meta: kind "height", extent = texel size * texel count, params describe the conversion.
TextureMap reliefFromHeight(const HeightField& field, const ReliefFromHeightOptions& options);

}  // namespace thx::tex
