#pragma once
// TextureMap: the single in-memory representation of a normal map or a relief map.
//
// Conventions (the one sampling convention of the project; docs/textures.md explains them):
//  - Texel (i, j): i = column, 0 at the left of the image; j = row, 0 at the TOP of the image
//    (the order PNG stores rows in).
//  - Normals are stored in the plane's tangent frame: +x = increasing column (image right),
//    +y = decreasing row (image up), +z = out of the surface. The green-channel convention of a
//    file (OpenGL +Y up / DirectX -Y) is resolved when the file is read or written, never here.
//  - Depth is measured INTO the surface, in metres, 0 = at the plane, never negative and never
//    above maxDepth(). The relief surface's height in the plane frame is z = -depth.
//    A normal map has no depth (all zero, maxDepth() == 0).
//  - Storage is compact so a 1024^2 relief map costs 6 MiB: the normal's x and y as snorm16 (z
//    is implied: every stored normal points out of the surface, so z = sqrt(1 - x^2 - y^2) > 0),
//    depth as a 16-bit fraction of maxDepth().
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace thx::tex {

enum class Representation { Normal, Relief };

struct TexelIndex {
  int i = 0;  // column
  int j = 0;  // row (0 = top)
  friend bool operator==(const TexelIndex&, const TexelIndex&) = default;
};

// Limits every loader and generator enforces.
inline constexpr int kMinTextureSide = 2;
inline constexpr int kMaxTextureSide = 16384;

// Descriptive metadata carried with the texture (stored in PNG text chunks, see texture_io.hpp).
struct TextureMeta {
  std::string kind = "unknown";  // generator name, "height" (from a height field) or "file"
  double extent_x_m = 0.0;       // physical size the normals were computed for; 0 = unknown
  double extent_y_m = 0.0;
  std::string params;            // free text: generator parameters, for `texturetool info`
};

class TextureMap {
 public:
  TextureMap() = default;
  // A flat map: every normal (0,0,1), every depth 0. Throws TextureError on a size outside
  // [kMinTextureSide, kMaxTextureSide] or a relief map whose maxDepth is not finite and > 0.
  TextureMap(int width, int height, Representation representation, double max_depth_m = 0.0);

  int width() const { return width_; }
  int height() const { return height_; }
  Representation representation() const { return representation_; }
  bool isRelief() const { return representation_ == Representation::Relief; }
  double maxDepth() const { return max_depth_m_; }

  TextureMeta& meta() { return meta_; }
  const TextureMeta& meta() const { return meta_; }

  // Unchecked texel access: the caller resolves wrap/clamp (see sampling.hpp).
  Eigen::Vector3f normal(int i, int j) const {
    const Texel& t = texels_[index(i, j)];
    const float x = float(t.nx) * (1.0f / 32767.0f), y = float(t.ny) * (1.0f / 32767.0f);
    // setNormal() keeps x^2 + y^2 < 1, so z is real and positive; the max() only guards rounding.
    return {x, y, std::sqrt(std::fmax(kMinNormalZ * kMinNormalZ, 1.0f - x * x - y * y))};
  }
  // Raw stored normal x and y (snorm16: component = code / 32767), for exact comparisons and hashing.
  std::int16_t normalCodeX(int i, int j) const { return texels_[index(i, j)].nx; }
  std::int16_t normalCodeY(int i, int j) const { return texels_[index(i, j)].ny; }
  float depth(int i, int j) const { return float(texels_[index(i, j)].depth) * depth_scale_; }
  // Metres per depth code: two texels on one plane may read depths this far apart (0 for a normal map).
  double depthStep() const { return double(depth_scale_); }
  // Raw 16-bit depth fraction (0 = plane, 65535 = maxDepth()).
  std::uint16_t depthCode(int i, int j) const { return texels_[index(i, j)].depth; }

  // Stores n / |n|. Throws TextureError if n is not finite, has zero length, or points into the
  // surface (n.z <= 0): such a texel has no meaning for contact.
  void setNormal(int i, int j, const Eigen::Vector3f& n);
  // Stores depth clamped to [0, maxDepth()]. Throws TextureError if not finite. No-op for normal maps.
  void setDepth(int i, int j, double depth_m);
  void setDepthCode(int i, int j, std::uint16_t code);

  std::size_t bytes() const { return texels_.size() * sizeof(Texel); }

 private:
  // The flattest representable grazing normal: z below this is stored as this (about 0.06 deg
  // above the plane), so a stored normal always points out of the surface.
  static constexpr float kMinNormalZ = 1e-3f;
  struct Texel {
    std::int16_t nx, ny;
    std::uint16_t depth;
  };
  std::size_t index(int i, int j) const { return std::size_t(j) * std::size_t(width_) + std::size_t(i); }

  int width_ = 0;
  int height_ = 0;
  Representation representation_ = Representation::Normal;
  double max_depth_m_ = 0.0;
  float depth_scale_ = 0.0f;  // metres per depth code
  TextureMeta meta_;
  std::vector<Texel> texels_;
};

const char* toString(Representation r);

}  // namespace thx::tex
