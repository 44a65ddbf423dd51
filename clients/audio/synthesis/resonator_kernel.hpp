#pragma once
// The resonator bank's inner loop (docs/audio.md §3), built with -O3 and -ffp-contract=off in
// one file and compiled once per instruction set (GCC `target` attributes); the variant is chosen
// at run time from what the CPU supports, so one binary runs everywhere and uses AVX-512 where it
// exists (a -march=native build would not travel). Every variant computes the same operations in
// the same order on 64-byte vectors (16 floats or 8 doubles, "lanes"), so all of them give
// bit-identical samples; only their speed differs.
//
// Per mode: y[n+1] = a1 y[n] + a2 y[n-1] (+ b g on the block's first sample when impulses are
// pending), a1 = 2R cos(theta), a2 = -R^2; out[n] = sum over modes of y[n], summed lane by lane in
// mode order, then across the lanes in lane order. Two algebraically equal forms, by precision:
//  - double, the direct form: x = y[n-1], c1 = a1, c2 = a2; y[n+1] = c1 y + c2 x (+ b g).
//  - float, the difference form: x = y[n] - y[n-1], c1 = a1 - 1 - R^2 = -(1-R)^2 - 4R sin^2(theta/2),
//    c2 = R^2; x[n+1] = c1 y + c2 x (+ b g), y[n+1] = y + x[n+1]. At low frequencies a1 is
//    within ~theta^2 of 2, so a float a1 (steps of 2.4e-7 there) misplaces a 55 Hz mode by 1e-4
//    relative; c1 itself is small and keeps float's relative precision (docs/audio.md §3).
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
inline constexpr bool kResonatorDifferenceForm = sizeof(T) < sizeof(double);

template <class T>
struct ResonatorArrays {
  const T* a1;  // c1 (see above)
  const T* a2;  // c2
  const T* b;
  T* y;        // y[n], the next sample out
  T* y_prev;   // x: y[n-1] (direct form) or y[n] - y[n-1] (difference form)
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
// with the project's flags), always in the direct form (c1 = a1, c2 = a2, x = y[n-1]): kept as
// the benchmark's baseline and the tests' scalar reference.
template <class T>
void resonateReference(const ResonatorArrays<T>& s, std::size_t modes, std::size_t samples, T* out);

}  // namespace thx::audio
