#pragma once
// Counts every global operator new (and, per thread, every delete) of a test executable
// (docs/design.md §4 rule 1: nothing in the servo tick allocates). Include it in exactly ONE source
// file per executable: it defines the replacement allocation functions, which must exist once per
// program.
#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

namespace thx::test {
inline std::atomic<long> g_allocations{0};
// This thread's allocations and frees (a real-time thread's own, while other threads load).
inline thread_local long t_allocations = 0;
inline thread_local long t_frees = 0;
}  // namespace thx::test

// The replacements pair new with malloc and delete with free, which is correct; g++ cannot see
// that once it inlines them and warns.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  thx::test::g_allocations.fetch_add(1, std::memory_order_relaxed);
  ++thx::test::t_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept {
  if (p) ++thx::test::t_frees;
  std::free(p);
}
void operator delete[](void* p) noexcept { operator delete(p); }
void operator delete(void* p, std::size_t) noexcept { operator delete(p); }
void operator delete[](void* p, std::size_t) noexcept { operator delete(p); }
#pragma GCC diagnostic pop
