#pragma once
// A vertex position as a hash key: its exact bits (+0.0 for -0.0, which compare equal and are the
// same point). Meshes split a vertex where its texture coordinates or frames jump, and the copies
// keep the very same coordinates; a tolerance instead would weld parts that only touch. Shared by
// the frames, the edge table (textured_mesh.cpp) and the checks (mesh_check.cpp).
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace thx::mesh {

using PositionBits = std::array<std::uint64_t, 3>;

inline PositionBits bitsOf(const Eigen::Vector3d& p) {
  PositionBits k{};
  for (int a = 0; a < 3; ++a) {
    const double v = p[a] + 0.0;
    std::memcpy(&k[std::size_t(a)], &v, sizeof v);
  }
  return k;
}

inline std::uint64_t mixBits(std::uint64_t x) {  // splitmix64's finaliser: every input bit reaches every output bit
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

struct PositionHash {
  std::size_t operator()(const PositionBits& k) const { return std::size_t(mixBits(k[0] ^ mixBits(k[1] ^ mixBits(k[2])))); }
};

}  // namespace thx::mesh
