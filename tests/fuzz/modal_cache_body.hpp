#pragma once
// One fuzzing step for the modal cache reader (clients/audio/analysis/modal_cache.hpp, layout in
// docs/audio.md §2). Shared by the libFuzzer target and the short run in test_fuzz_modal_cache.cpp.
//
// Input: byte 0 picks the mode (bit 0: rewrite the trailing checksum to match, so mutations reach
// the checks behind it; bit 1: ask for another key than the header's), the rest is the file.
// Properties:
//  1. a refused file gives no solution and exactly one warning, naming the file;
//  2. asked for another key, the reader never accepts;
//  3. an accepted file has consistent counts (D x N shapes, R rigid frequencies, free DOFs <= D),
//     finite values, ascending frequencies, and encodes back to exactly its own bytes.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "clients/audio/analysis/modal_cache.hpp"
#include "tests/fuzz/failure.hpp"

namespace thx::fuzz {

inline constexpr const char* kModalCacheSource = "fuzz.modes";

namespace modal_detail {

inline std::uint64_t fnv1a(const std::uint8_t* p, std::size_t n) {
  std::uint64_t h = 14695981039346656037ull;
  for (std::size_t k = 0; k < n; ++k) h = (h ^ p[k]) * 1099511628211ull;
  return h;
}

inline Failure checkSolution(const audio::ModalSolution& s) {
  if (s.shapes.rows() != s.mesh_dofs || s.shapes.cols() != s.omega_rad_per_s.size() ||
      s.rigid_hz.size() != s.rigid_modes || s.free_dofs > s.mesh_dofs || s.free_dofs < 0)
    return std::string("accepted inconsistent counts");
  if (!s.rigid_hz.allFinite() || !s.omega_rad_per_s.allFinite() || !s.shapes.allFinite())
    return std::string("accepted a value that is not finite");
  for (Eigen::Index m = 1; m < s.omega_rad_per_s.size(); ++m)
    if (s.omega_rad_per_s[m] < s.omega_rad_per_s[m - 1]) return std::string("accepted descending frequencies");
  return std::nullopt;
}

}  // namespace modal_detail

inline Failure fuzzModalCacheOnce(std::span<const std::uint8_t> data) {
  if (data.empty()) return std::nullopt;
  const std::uint8_t mode = data[0];
  Bytes file(data.begin() + 1, data.end());
  if ((mode & 1) && file.size() >= 8) {
    const std::uint64_t sum = modal_detail::fnv1a(file.data(), file.size() - 8);
    std::memcpy(file.data() + file.size() - 8, &sum, 8);
  }
  std::uint64_t key = 0;
  if (file.size() >= 24) std::memcpy(&key, file.data() + 16, 8);
  const bool other_key = mode & 2;
  if (other_key) key ^= 0x5a5a5a5a5a5a5a5aull;

  std::vector<std::string> warnings;
  const auto solution = audio::decodeModalCache(file, key, kModalCacheSource,
                                                [&](const std::string& w) { warnings.push_back(w); });
  if (!solution) {
    if (warnings.size() != 1) return "a refusal gave " + std::to_string(warnings.size()) + " warnings";
    return mustName(warnings[0], kModalCacheSource, "cache refusal");
  }
  if (other_key) return std::string("accepted a file of another key");
  if (!warnings.empty()) return std::string("an accepted file gave a warning: ") + warnings[0];
  if (Failure f = modal_detail::checkSolution(*solution)) return f;
  if (audio::encodeModalCache(key, *solution) != file) return std::string("encode(decode(file)) differs from the file");
  return std::nullopt;
}

}  // namespace thx::fuzz
