#pragma once
// Counts every global operator new of a test executable (DESIGN §4 rule 1: nothing in the servo
// tick allocates). Include it in exactly ONE source file per executable: it defines the
// replacement allocation functions, which must exist once per program.
#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

namespace thx::test {
inline std::atomic<long> g_allocations{0};
}  // namespace thx::test

// The replacements pair new with malloc and delete with free, which is correct; g++ cannot see
// that once it inlines them and warns.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  thx::test::g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop
