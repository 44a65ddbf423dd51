#include "textures/texture_map.hpp"

#include <cmath>
#include <string>

#include "textures/texture_error.hpp"

namespace thx::tex {

namespace {

std::int16_t toSnorm16(float c) {
  const float clamped = std::fmax(-1.0f, std::fmin(1.0f, c));
  return static_cast<std::int16_t>(std::lround(clamped * 32767.0f));
}
}  // namespace

const char* toString(Representation r) { return r == Representation::Relief ? "relief" : "normal"; }

TextureMap::TextureMap(int width, int height, Representation representation, double max_depth_m)
    : width_(width), height_(height), representation_(representation) {
  if (width < kMinTextureSide || height < kMinTextureSide || width > kMaxTextureSide ||
      height > kMaxTextureSide) {
    throw TextureError("texture", "size out of range", std::to_string(width) + "x" + std::to_string(height),
                       "each side in [" + std::to_string(kMinTextureSide) + ", " +
                           std::to_string(kMaxTextureSide) + "]");
  }
  if (representation == Representation::Relief) {
    if (!std::isfinite(max_depth_m) || max_depth_m <= 0.0) {
      throw TextureError("texture", "relief map maximum depth", std::to_string(max_depth_m),
                         "a finite depth > 0 in metres");
    }
    max_depth_m_ = max_depth_m;
    depth_scale_ = float(max_depth_m / 65535.0);
  }
  texels_.assign(std::size_t(width) * std::size_t(height), Texel{0, 0, 0});
}

void TextureMap::setNormal(int i, int j, const Eigen::Vector3f& n) {
  if (!n.allFinite()) throw TextureError("texture", "non-finite normal at " + texelName(i, j), "", "finite values");
  const float len = n.norm();
  if (!(len > 1e-12f)) throw TextureError("texture", "zero-length normal at " + texelName(i, j), "", "|n| > 0");
  Eigen::Vector3f u = n / len;
  if (!(u.z() > 0.0f)) {
    throw TextureError("texture", "normal points into the surface at " + texelName(i, j),
                       "n.z = " + std::to_string(u.z()), "n.z > 0");
  }
  if (u.z() < kMinNormalZ) {
    // Only z is implied by x and y: tilt a nearly grazing normal up to the flattest one stored.
    const float xy = std::sqrt(1.0f - kMinNormalZ * kMinNormalZ) / std::hypot(u.x(), u.y());
    u = Eigen::Vector3f(u.x() * xy, u.y() * xy, kMinNormalZ);
  }
  Texel& t = texels_[index(i, j)];
  t.nx = toSnorm16(u.x());
  t.ny = toSnorm16(u.y());
}

void TextureMap::setDepth(int i, int j, double depth_m) {
  if (!std::isfinite(depth_m)) {
    throw TextureError("texture", "non-finite depth at " + texelName(i, j), std::to_string(depth_m),
                       "a finite depth in metres");
  }
  if (!isRelief()) return;
  const double fraction = std::fmin(1.0, std::fmax(0.0, depth_m / max_depth_m_));
  texels_[index(i, j)].depth = static_cast<std::uint16_t>(std::lround(fraction * 65535.0));
}

void TextureMap::setDepthCode(int i, int j, std::uint16_t code) {
  if (isRelief()) texels_[index(i, j)].depth = code;
}

}  // namespace thx::tex
