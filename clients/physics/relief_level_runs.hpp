#pragma once
// Where a relief stays level along its rows: for every texel, how many texels from it along +i
// (within its row, not across the map's edge) have its depth code. A box's contact search reads
// a level stretch's ends instead of its every texel (box_relief_contacts.hpp); a flat relief is
// one stretch per row, a brick relief one per brick top. Built once per relief plane (allocates,
// 2 bytes per texel); read-only afterwards.
#include <cstdint>
#include <vector>

#include "textures/texture_map.hpp"

namespace thx::phys {

class ReliefLevelRuns {
 public:
  explicit ReliefLevelRuns(const tex::TextureMap& map);
  // Texels from (i, j) along +i with its depth code, itself included (>= 1; at most 65535).
  long long levelAlong(int i, int j) const { return runs_[std::size_t(j) * std::size_t(width_) + std::size_t(i)]; }

 private:
  int width_ = 0;
  std::vector<std::uint16_t> runs_;
};

}  // namespace thx::phys
