#pragma once
// True in the AddressSanitizer build (Debug ASan+UBSan, `make test`'s second tree), where code runs
// 10-300x slower than in RelWithDebInfo. Long sweeps use fewer probes there: the sanitizers need
// the code paths, not the statistics; the optimised tree runs every probe.
namespace thx::test {
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif
#else
inline constexpr bool kSanitized = false;
#endif
}  // namespace thx::test
