#pragma once
// A mesh chart's edges at random for the raster's tests (clients/physics/chart_boundary.hpp).
#include <Eigen/Core>
#include <random>

#include "clients/physics/chart_boundary.hpp"

namespace thx::phys::test {

// One to three edges through the footprint, some of them along the rows or the columns exactly,
// one nearly along the rows (the raster tests each texel there).
inline ChartBoundary randomBoundary(std::mt19937& rng, const Eigen::Vector2d& near) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  ChartBoundary b;
  b.count = std::size_t(1 + rng() % 3);
  for (std::size_t k = 0; k < b.count; ++k) {
    Eigen::Vector2d n(unit(rng), unit(rng));
    switch (rng() % 5) {
      case 0: n = Eigen::Vector2d(0.0, 1.0); break;
      case 1: n = Eigen::Vector2d(-1.0, 0.0); break;
      case 2: n = Eigen::Vector2d(1e-9, -1.0); break;
      default: break;
    }
    b.edges[k].normal = n.normalized();
    b.edges[k].offset = b.edges[k].normal.dot(near) + 0.003 * unit(rng);
  }
  return b;
}

}  // namespace thx::phys::test
