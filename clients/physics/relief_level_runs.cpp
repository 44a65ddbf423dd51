#include "clients/physics/relief_level_runs.hpp"

#include <limits>

namespace thx::phys {

ReliefLevelRuns::ReliefLevelRuns(const tex::TextureMap& map) : width_(map.width()) {
  runs_.assign(std::size_t(map.width()) * std::size_t(map.height()), 1);
  constexpr unsigned kMax = std::numeric_limits<std::uint16_t>::max();
  for (int j = 0; j < map.height(); ++j) {
    std::uint16_t* row = runs_.data() + std::size_t(j) * std::size_t(width_);
    for (int i = map.width() - 2; i >= 0; --i)
      if (map.depthCode(i, j) == map.depthCode(i + 1, j) && row[i + 1] < kMax) row[i] = std::uint16_t(row[i + 1] + 1);
  }
}

}  // namespace thx::phys
