#pragma once
// Counts every global operator new (and, per thread, every delete) of a test executable
// (docs/design.md §4 rule 1: nothing in the servo tick allocates). The replacement allocation
// functions live in allocation_counter.cpp, which a test executable gets once with
// thx_add_test(... COUNTS_ALLOCATIONS) (tests/CMakeLists.txt); every file of it may include this.
// The counters are defined there too, so an executable without the counting operator new does not
// link (rather than count nothing and pass).
#include <atomic>

namespace thx::test {
extern std::atomic<long> g_allocations;
// This thread's allocations and frees (a real-time thread's own, while other threads load).
extern thread_local long t_allocations;
extern thread_local long t_frees;
}  // namespace thx::test
