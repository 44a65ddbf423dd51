#pragma once
// The resonator bank's inner loop (docs/audio.md §3), built with -O3 and -ffp-contract=off in
// one file and compiled once per instruction set (GCC `target` attributes); the variant is chosen
// at run time from what the CPU supports, so one binary runs everywhere and uses AVX-512 where it
// exists (a -march=native build would not travel). Every variant computes the same operations in
// the same order on 64-byte vectors (16 floats or 8 doubles, "lanes"), so all of them give
// bit-identical samples; only their speed differs.
//
// Per mode k: y_k[n+1] = a1_k y_k[n] + a2_k y_k[n-1] (+ b_k g_k on the block's first sample when
// impulses are pending); out[n] = sum_k y_k[n], summed lane by lane in mode order, then across the
// lanes in lane order.
#include <cstddef>

namespace thx::audio {

enum class Isa { Default, Avx2, Avx512 };  // Default: the x86-64 baseline (SSE2)

const char* isaName(Isa isa);
bool isaSupported(Isa isa);  // by this CPU
Isa bestIsa();               // the fastest supported

template <class T>
inline constexpr std::size_t kResonatorLanes = 64 / sizeof(T);
inline constexpr std::size_t kResonatorBlock = 256;  // samples per kernel call, at most

template <class T>
struct ResonatorArrays {
  const T* a1;
  const T* a2;
  const T* b;
  T* y;        // y[n], the next sample out
  T* y_prev;   // y[n-1]
  T* pending;  // impulses for the first sample; zeroed when used (null: none)
};

// Advances modes [0, modes) by `samples` (<= kResonatorBlock) samples and writes their sum to
// out. `lanes` is scratch of kResonatorBlock * kResonatorLanes<T> values. No allocation.
template <class T>
using ResonatorKernel = void (*)(const ResonatorArrays<T>& s, std::size_t modes, std::size_t samples, T* lanes, T* out);

// The variant for `isa` (which must be supported; see isaSupported).
template <class T>
ResonatorKernel<T> resonatorKernel(Isa isa);

// The loop as it was before vectorisation (samples outer, one running sum over the modes, built
// with the project's flags): kept as the benchmark's baseline and the tests' scalar reference.
template <class T>
void resonateReference(const ResonatorArrays<T>& s, std::size_t modes, std::size_t samples, T* out);

}  // namespace thx::audio
