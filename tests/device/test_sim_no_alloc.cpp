// docs/design.md §4 rule 1: the simulated device's read() and write() run inside the servo tick, so
// they must not allocate. Its executable replaces the global operator new to count allocations
// (COUNTS_ALLOCATIONS, tests/device/CMakeLists.txt).
// (Eigen heap use would go through malloc, not operator new; device/ uses fixed-size types only.)
#include <gtest/gtest.h>

#include "tests/support/allocation_counter.hpp"

#include <atomic>
#include <cstdlib>
#include <new>

#include "device/sim_phantom.hpp"

namespace test_sim_no_alloc {



using namespace thx::dev;

namespace {

// A bump under the script (device/surface_height.hpp): the hand's script samples it every step.
class Bump final : public SurfaceHeight {
 public:
  bool heightAt(const Eigen::Vector2d& xy, double& z_m) const override {
    if (xy.squaredNorm() > 1e-3) return false;
    z_m = 0.01 * (1.0 - 1e3 * xy.squaredNorm());
    return true;
  }
  double top() const override { return 0.01; }
};

long allocationsDuringTicks(OutputMode mode, const SimFaults& faults, const SurfaceHeight* height = nullptr) {
  SimPhantomConfig c;
  c.output_mode = mode;
  c.faults = faults;
  c.surface_height = height;
  const HandScript script({HandPress{{0.0, 0.0}, 1.0, 0.3}, HandStroke{{0.0, 0.0}, {0.02, 0.0}, 0.05, 1.0}});
  SimPhantom sim(c, script);
  sim.open();
  DeviceCommand cmd;
  cmd.forces_enabled = true;
  cmd.num_planes = 1;
  cmd.planes[0].k_n_per_m = 500.0;
  const long before = thx::test::g_allocations.load();
  for (int k = 0; k < 1500; ++k) {
    const DeviceState s = sim.read();
    cmd.force_world_n = Eigen::Vector3d(0, 0, 600.0 * std::max(0.0, -s.p_world.z()));
    if (k % 7 != 3) sim.write(cmd);  // some ticks without a write: the watchdog path too
  }
  return thx::test::g_allocations.load() - before;
}

}  // namespace

TEST(SimNoAlloc, ReadAndWriteNeverAllocate) {
  const SimFaults faults{100, 5, 200, 5};
  EXPECT_EQ(allocationsDuringTicks(OutputMode::Force, faults), 0);
  EXPECT_EQ(allocationsDuringTicks(OutputMode::Planes, faults), 0);
}

TEST(SimNoAlloc, ReadAndWriteNeverAllocateOnACurvedSurface) {
  const Bump bump;
  EXPECT_EQ(allocationsDuringTicks(OutputMode::Force, SimFaults{}, &bump), 0);
}

TEST(SimNoAlloc, TheCounterWorks) {
  // Through a volatile pointer: g++ may elide a new/delete pair whose operators it cannot see.
  const long before = thx::test::g_allocations.load();
  void* volatile probe = ::operator new(16);
  ::operator delete(probe);
  EXPECT_EQ(thx::test::g_allocations.load() - before, 1);
}

}  // namespace test_sim_no_alloc
