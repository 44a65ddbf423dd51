// The micro level's read (microForce) and the relief impulses never allocate: the live client
// will call them in the audio path.
#include <gtest/gtest.h>

#include <array>

#include "clients/audio/synthesis/fractal_roughness.hpp"
#include "clients/audio/synthesis/relief_impulses.hpp"
#include "tests/support/allocation_counter.hpp"

namespace thx::audio::test_micro_no_allocation {
namespace {

TEST(MicroNoAllocation, ReadingTheProfileAndReliefImpulsesAllocateNothing) {
  RoughnessOptions o;
  o.length = 1u << 10;
  const RoughnessProfile profile(o);
  std::array<double, 64> out{};
  const ReliefTick a{true, {0, 0, 1}, {0, 0, 1}, {0.1, 0, 0}}, b{true, {0, 0, 1}, {0.3, 0, 1}, {0.1, 0, 0}};
  const long before = thx::test::t_allocations;
  microForce(profile, 0.0, 1e-3, 1.0, 2.0, out);           // 1.6 entries per sample: level 1
  microForce(profile, 1e-3, 1.1e-3, 2.0, 2.0, out);        // level 0
  const double j = reliefImpulse(a, b, 0.045);
  EXPECT_EQ(thx::test::t_allocations - before, 0);
  EXPECT_NE(out[10], 0.0);
  EXPECT_NE(j, 0.0);
}

}  // namespace
}  // namespace thx::audio::test_micro_no_allocation
