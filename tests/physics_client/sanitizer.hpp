#pragma once
// True in the AddressSanitizer build (Debug ASan+UBSan), where rasterising a box on a relief runs
// ~300x slower than in RelWithDebInfo: tests that run whole scenes use coarser texels there.
namespace thx::physclient::test {
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
}  // namespace thx::physclient::test
