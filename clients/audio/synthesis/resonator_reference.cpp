// The resonator loop as it was before vectorisation, built with the project's flags (-O2): the
// baseline of benchmarks/bench_audio_synth.cpp and the scalar reference of the tests.
#include "clients/audio/synthesis/resonator_kernel.hpp"

namespace thx::audio {

template <class T>
void resonateReference(const ResonatorArrays<T>& s, std::size_t modes, std::size_t samples, T* out) {
  if (samples == 0) return;
  T* __restrict y = s.y;
  T* __restrict yp = s.y_prev;
  const T* __restrict a1 = s.a1;
  const T* __restrict a2 = s.a2;
  const T* __restrict b = s.b;
  std::size_t n = 0;
  if (s.pending) {
    double sum = 0.0;
    for (std::size_t k = 0; k < modes; ++k) {
      sum += y[k];
      const T next = a1[k] * y[k] + a2[k] * yp[k] + b[k] * s.pending[k];
      yp[k] = y[k];
      y[k] = next;
      s.pending[k] = 0;
    }
    out[0] = T(sum);
    n = 1;
  }
  for (; n < samples; ++n) {
    double sum = 0.0;
    for (std::size_t k = 0; k < modes; ++k) {
      sum += y[k];
      const T next = a1[k] * y[k] + a2[k] * yp[k];
      yp[k] = y[k];
      y[k] = next;
    }
    out[n] = T(sum);
  }
}

template void resonateReference<float>(const ResonatorArrays<float>&, std::size_t, std::size_t, float*);
template void resonateReference<double>(const ResonatorArrays<double>&, std::size_t, std::size_t, double*);

}  // namespace thx::audio
