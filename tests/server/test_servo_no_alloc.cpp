// DESIGN §4 rule 1: nothing in the servo tick allocates. Every operator new in this binary is
// counted while `counting` is set; a full tick pipeline (render with crease handling, passivity,
// safety, flight recorder, ring) runs 5000 ticks of presses and strokes across V-valleys.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "tests/server/servo_fixture.hpp"

// The replacement operators pair new with malloc and delete with free, which is correct; g++
// cannot see that across the replacement and warns.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  if (counting.load(std::memory_order_relaxed)) allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

using namespace thx;

TEST(ServoRealtime, NoAllocationInTheTick) {
  test::ServoRig rig([](std::int64_t tick, dev::DeviceState& s) {
    // Hover, press into a valley, stroke across five valleys and back, lift.
    const double t = double(tick % 5000) / 1000.0;
    const double x = t < 2.0 ? 0.0 : 0.02 * std::sin((t - 2.0) * 2.0);
    const double z = t < 1.0 ? 0.002 - 0.0065 * t : (t < 4.5 ? -0.0045 : 0.002);
    s.p_world = Eigen::Vector3d(x, 0.001 * t, z);
    s.v_world = Eigen::Vector3d(0.04 * std::cos((t - 2.0) * 2.0), 0.001, 0.0);
    if (tick == 3000) s.timing.missed = 4;  // a fault: flight recorder freeze on the path too
  });
  rig.run(10);  // let lazily initialised runtime pieces settle outside the measurement
  srv::ClientForce cf;
  cf.force_world_n[2] = 0.1;
  counting = true;
  for (int k = 0; k < 5000; ++k) {
    if (k % 10 == 0) rig.servo->clientForceSlot().write(cf);
    rig.servo->tick();
    srv::TickRecord r;
    while (rig.ring.pop(r)) {
    }
  }
  counting = false;
  EXPECT_EQ(allocations.load(), 0);
  EXPECT_GT(rig.servo->counters().contact_ticks, 2000u);
  EXPECT_EQ(rig.servo->counters().faults, 1u);
}
