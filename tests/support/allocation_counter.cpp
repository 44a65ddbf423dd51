// The replacement allocation functions behind allocation_counter.hpp: they must exist once per
// program, so thx_add_test(... COUNTS_ALLOCATIONS) compiles this file once into the executable.
#include "tests/support/allocation_counter.hpp"

#include <cstddef>
#include <cstdlib>
#include <new>

namespace thx::test {
std::atomic<long> g_allocations{0};
thread_local long t_allocations = 0;
thread_local long t_frees = 0;
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
