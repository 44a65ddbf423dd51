#pragma once
// Sound files for the audio tests, written byte by byte (independent of libsndfile, which reads
// them): a 16-bit PCM mono WAV of a sine.
#include <cmath>
#include <cstdint>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

namespace thx::audio::test {

inline std::vector<float> tone(double f_hz, double amplitude, std::size_t n, double rate = 44100.0) {
  std::vector<float> x(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = float(amplitude * std::sin(2 * std::numbers::pi * f_hz * double(i) / rate));
  return x;
}

inline void writePcm16(const std::string& path, const std::vector<float>& x, int rate) {
  std::ofstream out(path, std::ios::binary);
  auto u32 = [&](std::uint32_t v) { out.write(reinterpret_cast<const char*>(&v), 4); };
  auto u16 = [&](std::uint16_t v) { out.write(reinterpret_cast<const char*>(&v), 2); };
  const std::uint32_t bytes = std::uint32_t(2 * x.size());
  out.write("RIFF", 4), u32(36 + bytes), out.write("WAVEfmt ", 8), u32(16), u16(1), u16(1), u32(std::uint32_t(rate)),
      u32(std::uint32_t(2 * rate)), u16(2), u16(16), out.write("data", 4), u32(bytes);
  for (float v : x) u16(std::uint16_t(std::int16_t(std::lround(v * 32767))));
}

}  // namespace thx::audio::test
