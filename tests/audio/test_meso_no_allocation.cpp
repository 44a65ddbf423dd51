// The meso impulses' walk (the real-time form, mesoImpulsesAlong) never allocates.
#include <gtest/gtest.h>

#include "clients/audio/synthesis/meso_impulses.hpp"
#include "tests/support/allocation_counter.hpp"

namespace thx::audio::test_meso_no_allocation {
namespace {

TEST(MesoNoAllocation, WalkAllocatesNothing) {
  tex::TextureMap map(64, 64, tex::Representation::Normal);
  for (int j = 0; j < 64; ++j) map.setNormal(7, j, Eigen::Vector3f(0.3f, 0.0f, 1.0f));
  MesoSurface surface{&map, tex::Address::Wrap, {0, 0, 1}, 0.02, 0.05};
  MesoState state;
  double sum = 0;
  const long before = thx::test::t_allocations;
  const std::size_t n = mesoImpulsesAlong(surface, state, {0.01, 0.5}, {0.99, 0.5}, {0.5, 0, 0},
                                          [&](const MesoImpulse& m) { sum += m.impulse.z(); });
  EXPECT_EQ(thx::test::t_allocations - before, 0);
  EXPECT_EQ(n, 63u);
  EXPECT_NEAR(sum, 0.0, 1e-12);  // in and out of the tilted column: equal and opposite
}

}  // namespace
}  // namespace thx::audio::test_meso_no_allocation
