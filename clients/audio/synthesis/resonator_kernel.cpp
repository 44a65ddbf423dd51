// Built with -O3 -ffp-contract=off (clients/audio/synthesis/CMakeLists.txt): no fused multiply-add, so the
// variants round identically and the output does not depend on the machine.
#include "clients/audio/synthesis/resonator_kernel.hpp"

#include <cstring>

namespace thx::audio {
namespace {

// One sample of one mode, or of a vector of modes (resonator_kernel.hpp: c1, c2, x). The scalar
// tail and the vectors go through these same lines, so they round alike.
template <bool kDifference, class V>
[[gnu::always_inline]] inline void step(const V& c1, const V& c2, V& y, V& x) {
  if constexpr (kDifference) {
    x = c1 * y + c2 * x;
    y = y + x;
  } else {
    const V next = c1 * y + c2 * x;
    x = y;
    y = next;
  }
}

template <bool kDifference, class V>
[[gnu::always_inline]] inline void stepStruck(const V& c1, const V& c2, const V& bg, V& y, V& x) {
  if constexpr (kDifference) {
    x = c1 * y + c2 * x + bg;
    y = y + x;
  } else {
    const V next = c1 * y + c2 * x + bg;
    x = y;
    y = next;
  }
}

// Whole 64-byte vectors of modes ("logical" vectors, the lanes of resonator_kernel.hpp), each
// held as 64 / kBytes native vectors of the instruction set (GCC lowers a vector wider than the
// hardware's badly), kNative native vectors at a time: their recurrences are independent, so
// several are in flight while each waits for its multiply and add. The running sum per sample is
// kept per lane in `lanes` (sample-major) and added to in mode order, whatever the native width.
template <class T, std::size_t kBytes, std::size_t kNative>
[[gnu::always_inline]] inline void chunkOfVectors(const ResonatorArrays<T>& s, std::size_t first, std::size_t samples,
                                                  T* lanes) {
  using V [[gnu::vector_size(kBytes)]] = T;
  constexpr std::size_t W = kResonatorLanes<T>;
  constexpr std::size_t kPer = kBytes / sizeof(T);  // values per native vector
  constexpr std::size_t kParts = W / kPer;          // native vectors per lane vector
  static_assert(kNative % kParts == 0);
  V a1[kNative], a2[kNative], y[kNative], yp[kNative];  // c1, c2, y, x
#pragma GCC unroll 16
  for (std::size_t c = 0; c < kNative; ++c) {
    const std::size_t at = first + c * kPer;
    std::memcpy(&a1[c], s.a1 + at, sizeof(V));
    std::memcpy(&a2[c], s.a2 + at, sizeof(V));
    std::memcpy(&y[c], s.y + at, sizeof(V));
    std::memcpy(&yp[c], s.y_prev + at, sizeof(V));
  }
  std::size_t n = 0;
  if (s.pending) {
    // The first sample carries the struck impulses into y[n+1].
    V acc[kParts];
    for (std::size_t p = 0; p < kParts; ++p) std::memcpy(&acc[p], lanes + p * kPer, sizeof(V));
    for (std::size_t c = 0; c < kNative; ++c) {
      const std::size_t at = first + c * kPer;
      V b, g;
      std::memcpy(&b, s.b + at, sizeof(V));
      std::memcpy(&g, s.pending + at, sizeof(V));
      acc[c % kParts] += y[c];
      stepStruck<kResonatorDifferenceForm<T>>(a1[c], a2[c], V(b * g), y[c], yp[c]);
      std::memset(s.pending + at, 0, sizeof(V));
    }
    for (std::size_t p = 0; p < kParts; ++p) std::memcpy(lanes + p * kPer, &acc[p], sizeof(V));
    n = 1;
  }
  for (; n < samples; ++n) {
    // Loaded and stored one native vector at a time: a wider copy through the stack would defeat
    // store-to-load forwarding.
    V acc[kParts];
#pragma GCC unroll 16
    for (std::size_t p = 0; p < kParts; ++p) std::memcpy(&acc[p], lanes + n * W + p * kPer, sizeof(V));
#pragma GCC unroll 16
    for (std::size_t l = 0; l < kNative; l += kParts)
#pragma GCC unroll 16
      for (std::size_t p = 0; p < kParts; ++p) {
        const std::size_t c = l + p;
        acc[p] += y[c];
        step<kResonatorDifferenceForm<T>>(a1[c], a2[c], y[c], yp[c]);
      }
#pragma GCC unroll 16
    for (std::size_t p = 0; p < kParts; ++p) std::memcpy(lanes + n * W + p * kPer, &acc[p], sizeof(V));
  }
#pragma GCC unroll 16
  for (std::size_t c = 0; c < kNative; ++c) {
    const std::size_t at = first + c * kPer;
    std::memcpy(s.y + at, &y[c], sizeof(V));
    std::memcpy(s.y_prev + at, &yp[c], sizeof(V));
  }
}

// The modes past the last whole vector, one by one, into the lane each would occupy in a vector:
// the same operations in the same order as chunkOfVectors, so the sum is as if they were one.
template <class T>
[[gnu::always_inline]] inline void tailModes(const ResonatorArrays<T>& s, std::size_t first, std::size_t last,
                                             std::size_t samples, T* lanes) {
  constexpr std::size_t W = kResonatorLanes<T>;
  for (std::size_t k = first; k < last; ++k) {
    const std::size_t lane = k - first;
    T y = s.y[k], yp = s.y_prev[k];
    std::size_t n = 0;
    if (s.pending) {
      lanes[lane] += y;
      stepStruck<kResonatorDifferenceForm<T>>(s.a1[k], s.a2[k], T(s.b[k] * s.pending[k]), y, yp);
      s.pending[k] = 0;
      n = 1;
    }
    for (; n < samples; ++n) {
      lanes[n * W + lane] += y;
      step<kResonatorDifferenceForm<T>>(s.a1[k], s.a2[k], y, yp);
    }
    s.y[k] = y, s.y_prev[k] = yp;
  }
}

template <class T, std::size_t kBytes, std::size_t kNative>
[[gnu::always_inline]] inline void resonate(const ResonatorArrays<T>& s, std::size_t modes, std::size_t samples,
                                            T* lanes, T* out) {
  constexpr std::size_t W = kResonatorLanes<T>;
  std::memset(lanes, 0, samples * W * sizeof(T));
  const std::size_t whole = modes / W * W;
  std::size_t k = 0;
  constexpr std::size_t kStep = kNative * kBytes / sizeof(T);
  for (; k + kStep <= whole; k += kStep) chunkOfVectors<T, kBytes, kNative>(s, k, samples, lanes);
  // What is left of a small bank still goes several vectors at a time when it can.
  constexpr std::size_t kParts = 64 / kBytes;
  if constexpr (kNative / 2 >= kParts && (kNative / 2) % kParts == 0)
    for (; k + kStep / 2 <= whole; k += kStep / 2) chunkOfVectors<T, kBytes, kNative / 2>(s, k, samples, lanes);
  for (; k < whole; k += W) chunkOfVectors<T, kBytes, kParts>(s, k, samples, lanes);
  tailModes(s, whole, modes, samples, lanes);
  for (std::size_t n = 0; n < samples; ++n) {
    T sum = 0;
    for (std::size_t l = 0; l < W; ++l) sum += lanes[n * W + l];
    out[n] = sum;
  }
}

// Native vectors in flight per pass, measured best with benchmarks/bench_audio_synth.cpp on a
// Xeon with AVX-512 (32 vector registers: 8; AVX2 has 16: 4, 8 spills; SSE: 8). They do not
// change the result (each lane's sum stays in mode order).
constexpr std::size_t kNativeAvx512 = 8, kNativeAvx2 = 4, kNativeSse = 8;

#if defined(__x86_64__) || defined(__i386__)
#define THX_RESONATOR_X86 1
template <class T>
[[gnu::target("avx512f")]] void resonateAvx512(const ResonatorArrays<T>& s, std::size_t modes, std::size_t samples,
                                                T* lanes, T* out) {
  resonate<T, 64, kNativeAvx512>(s, modes, samples, lanes, out);
}
template <class T>
[[gnu::target("avx2")]] void resonateAvx2(const ResonatorArrays<T>& s, std::size_t modes, std::size_t samples, T* lanes,
                                           T* out) {
  resonate<T, 32, kNativeAvx2>(s, modes, samples, lanes, out);
}
#endif
template <class T>
void resonateDefault(const ResonatorArrays<T>& s, std::size_t modes, std::size_t samples, T* lanes, T* out) {
  resonate<T, 16, kNativeSse>(s, modes, samples, lanes, out);
}

}  // namespace

const char* isaName(Isa isa) {
  switch (isa) {
    case Isa::Avx512: return "avx512f";
    case Isa::Avx2: return "avx2";
    case Isa::Default: return "default";
  }
  return "?";
}

bool isaSupported(Isa isa) {
  if (isa == Isa::Default) return true;
#ifdef THX_RESONATOR_X86
  __builtin_cpu_init();
  if (isa == Isa::Avx512) return __builtin_cpu_supports("avx512f");
  if (isa == Isa::Avx2) return __builtin_cpu_supports("avx2");
#endif
  return false;  // other architectures: only the portable build
}

Isa bestIsa() {
  if (isaSupported(Isa::Avx512)) return Isa::Avx512;
  if (isaSupported(Isa::Avx2)) return Isa::Avx2;
  return Isa::Default;
}

template <class T>
ResonatorKernel<T> resonatorKernel(Isa isa) {
#ifdef THX_RESONATOR_X86
  if (isa == Isa::Avx512) return &resonateAvx512<T>;
  if (isa == Isa::Avx2) return &resonateAvx2<T>;
#endif
  (void)isa;
  return &resonateDefault<T>;
}

template ResonatorKernel<float> resonatorKernel<float>(Isa);
template ResonatorKernel<double> resonatorKernel<double>(Isa);

}  // namespace thx::audio
