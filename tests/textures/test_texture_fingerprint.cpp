// textureFingerprint: the documented byte stream (recomputed here independently), and every
// property a sense reads changes it while nothing else does.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "textures/generators.hpp"
#include "textures/texture_fingerprint.hpp"

namespace test_texture_fingerprint {

namespace {

using namespace thx::tex;

PlaneMapping squareMapping(double side_m) {
  PlaneMapping m;
  m.size_m = {side_m, side_m};
  return m;
}

TextureMap smallRelief() {
  TextureMap map(3, 2, Representation::Relief, 0.002);
  map.setNormal(1, 0, Eigen::Vector3f(0.3f, -0.2f, 1.0f));
  map.setNormal(2, 1, Eigen::Vector3f(-0.1f, 0.4f, 1.0f));
  map.setDepth(0, 1, 0.0015);
  map.setDepth(2, 0, 0.0002);
  return map;
}

// The byte stream of texture_fingerprint.hpp, written out step by step.
struct Stream {
  std::vector<std::uint8_t> bytes;
  void le(std::uint64_t v, int n) {
    for (int k = 0; k < n; ++k) bytes.push_back(std::uint8_t(v >> (8 * k)));
  }
  void q(double v) { le(std::uint64_t(std::llround(v * 1e12)), 8); }
  std::uint64_t fnv1a() const {
    std::uint64_t h = 14695981039346656037ULL;
    for (std::uint8_t b : bytes) h = (h ^ b) * 1099511628211ULL;
    return h;
  }
};

TEST(TextureFingerprint, IsFnv1aOverTheDocumentedByteStream) {
  const TextureMap map = smallRelief();
  PlaneMapping mapping = squareMapping(0.2);
  mapping.plane_to_world.translation() = Eigen::Vector3d(0.01, -0.02, 0.003);
  const TexturedSurface surface(map, mapping, SampleOptions{Filter::Bilinear, Address::Clamp}, true);

  Stream s;
  const char tag[16] = "thx.texture.v1";
  for (char c : tag) s.bytes.push_back(std::uint8_t(c));
  s.le(3, 4);
  s.le(2, 4);
  s.bytes.insert(s.bytes.end(), {1, 1, 1});  // relief read, bilinear, clamp
  s.q(0.2);
  s.q(0.2);
  for (double r : {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0}) s.q(r);
  for (double t : {0.01, -0.02, 0.003}) s.q(t);
  s.q(0.002);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      s.le(std::uint16_t(map.normalCodeX(i, j)), 2);
      s.le(std::uint16_t(map.normalCodeY(i, j)), 2);
      s.le(map.depthCode(i, j), 2);
    }
  EXPECT_EQ(textureFingerprint(surface), s.fnv1a());
  EXPECT_EQ(formatFingerprint(0x00ab00000000cd01ULL), "0x00ab00000000cd01");
}

TEST(TextureFingerprint, SameTextureSameFingerprint) {
  GenerateRequest req;
  req.kind = "bricks";
  req.size = 64;
  req.seed = 7;
  const TextureMap a = generate(req), b = generate(req);
  const TexturedSurface sa(a, squareMapping(0.2), {}, true), sb(b, squareMapping(0.2), {}, true);
  EXPECT_EQ(textureFingerprint(sa), textureFingerprint(sb));
  req.seed = 8;  // other jitter
  const TextureMap c = generate(req);
  EXPECT_NE(textureFingerprint(sa), textureFingerprint(TexturedSurface(c, squareMapping(0.2), {}, true)));
}

TEST(TextureFingerprint, EveryPropertyASenseReadsChangesIt) {
  const TextureMap map = smallRelief();
  const TexturedSurface base(map, squareMapping(0.2), {}, true);
  const std::uint64_t fp = textureFingerprint(base);

  TextureMap texel = smallRelief();
  texel.setNormal(0, 0, Eigen::Vector3f(0.0f, 0.001f, 1.0f));  // one normal code
  EXPECT_NE(textureFingerprint(TexturedSurface(texel, squareMapping(0.2), {}, true)), fp);
  TextureMap depth = smallRelief();
  depth.setDepthCode(1, 1, std::uint16_t(depth.depthCode(1, 1) + 1));  // one depth code
  EXPECT_NE(textureFingerprint(TexturedSurface(depth, squareMapping(0.2), {}, true)), fp);
  TextureMap bigger(4, 2, Representation::Relief, 0.002);  // other dimensions
  EXPECT_NE(textureFingerprint(TexturedSurface(bigger, squareMapping(0.2), {}, true)),
            textureFingerprint(TexturedSurface(TextureMap(2, 4, Representation::Relief, 0.002), squareMapping(0.2), {}, true)));
  TextureMap deeper(3, 2, Representation::Relief, 0.003);  // same codes, other maximum depth
  TextureMap shallow(3, 2, Representation::Relief, 0.002);
  EXPECT_NE(textureFingerprint(TexturedSurface(deeper, squareMapping(0.2), {}, true)),
            textureFingerprint(TexturedSurface(shallow, squareMapping(0.2), {}, true)));

  EXPECT_NE(textureFingerprint(TexturedSurface(map, squareMapping(0.21), {}, true)), fp);  // size
  EXPECT_NE(textureFingerprint(TexturedSurface(map, squareMapping(0.2), {}, false)), fp);  // read as a normal map
  EXPECT_NE(textureFingerprint(TexturedSurface(map, squareMapping(0.2), {Filter::Nearest, Address::Wrap}, true)), fp);
  EXPECT_NE(textureFingerprint(TexturedSurface(map, squareMapping(0.2), {Filter::Bilinear, Address::Clamp}, true)), fp);
  PlaneMapping moved = squareMapping(0.2);
  moved.plane_to_world.translation().z() = 1e-6;  // a micrometre higher
  EXPECT_NE(textureFingerprint(TexturedSurface(map, moved, {}, true)), fp);
  PlaneMapping tilted = squareMapping(0.2);
  tilted.plane_to_world.linear() = Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitX()).toRotationMatrix();
  EXPECT_NE(textureFingerprint(TexturedSurface(map, tilted, {}, true)), fp);
}

TEST(TextureFingerprint, IgnoresWhatNoSenseReads) {
  TextureMap map = smallRelief();
  const std::uint64_t fp = textureFingerprint(TexturedSurface(map, squareMapping(0.2), {}, true));
  map.meta().kind = "other";
  map.meta().extent_x_m = 5.0;
  map.meta().params = "whatever";
  EXPECT_EQ(textureFingerprint(TexturedSurface(map, squareMapping(0.2), {}, true)), fp);
  // Depth is not read by a normal-map reading: two reliefs differing only in depth read alike.
  TextureMap other_depth = smallRelief();
  other_depth.setDepth(0, 0, 0.001);
  EXPECT_EQ(textureFingerprint(TexturedSurface(map, squareMapping(0.2), {}, false)),
            textureFingerprint(TexturedSurface(other_depth, squareMapping(0.2), {}, false)));
  // A last-bit difference of a computed rotation (another host's libm) does not count.
  PlaneMapping a = squareMapping(0.2), b = squareMapping(0.2);
  a.plane_to_world.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()).toRotationMatrix();
  b.plane_to_world.linear() = a.plane_to_world.linear();
  b.plane_to_world.linear()(0, 0) = std::nextafter(b.plane_to_world.linear()(0, 0), 2.0);
  EXPECT_EQ(textureFingerprint(TexturedSurface(map, a, {}, true)), textureFingerprint(TexturedSurface(map, b, {}, true)));
}

}  // namespace

}  // namespace test_texture_fingerprint
