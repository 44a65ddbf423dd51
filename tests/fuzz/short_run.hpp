#pragma once
// The short, deterministic fuzzing run that every fuzz target gets inside `make test` (the VRPN
// decoder's pattern, tests/vrpn/test_fuzz_decoder.cpp, made general): mutate the target's
// checked-in seed corpus (tests/fuzz/corpus/<target>/, read in file-name order) with one
// fixed-seed mutator, hand every input to the same body the libFuzzer target runs, and fail with
// the input's number and the input as hex on the first broken property (an exception that escapes
// the body is one: libFuzzer would abort on it).
//
// The input sequence is fixed. The run always covers the seeds and the first `min_inputs` mutated
// inputs (3000 unless a target asks for fewer), then keeps going through the same sequence until
// about 2 s have passed, at most 200k inputs (so the sanitizer tree, ~20x slower, stays quick);
// THX_FUZZ_ITERATIONS=N runs exactly N mutated inputs (THX_VRPN_FUZZ_ITERATIONS for the VRPN
// decoder). Mutations (1 to 5 per input): bit flips, random bytes, boundary integers (lengths,
// counts, sizes) of 1, 2, 4 or 8 bytes in either byte order at any offset, the target's dictionary
// tokens inserted or written over, separators of the text formats, inserts, deletes, duplications,
// truncations and splices with another seed.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/fuzz/failure.hpp"

namespace thx::fuzz {

inline Bytes bytesOf(std::string_view s) { return Bytes(s.begin(), s.end()); }

inline std::string hexOf(std::span<const std::uint8_t> b) {
  static const char* d = "0123456789abcdef";
  std::string s;
  for (std::uint8_t x : b) {
    s += d[x >> 4];
    s += d[x & 15];
  }
  return s;
}

inline std::filesystem::path fuzzDir() { return std::filesystem::path(THX_SOURCE_DIR) / "tests" / "fuzz"; }

inline Bytes readBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Every file of tests/fuzz/corpus/<target>/, in name order (so the run does not depend on the
// file system's order).
inline std::vector<Bytes> loadCorpus(const std::string& target) {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(fuzzDir() / "corpus" / target))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::vector<Bytes> out;
  for (const auto& f : files) out.push_back(readBytes(f));
  return out;
}

// The tokens of a libFuzzer dictionary file (tests/fuzz/dict/<target>.dict): one "token" per
// line, optionally name="token"; \\, \" and \xNN escapes; # comments. None is an empty list.
inline std::vector<Bytes> loadDictionary(const std::string& target) {
  const std::filesystem::path path = fuzzDir() / "dict" / (target + ".dict");
  std::ifstream in(path);
  std::vector<Bytes> out;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    const std::size_t open = line.find('"');
    if (line.empty() || line[0] == '#' || open == std::string::npos) continue;
    const std::size_t close = line.rfind('"');
    if (close <= open) throw std::runtime_error(path.string() + ":" + std::to_string(number) + ": unterminated token");
    Bytes tok;
    for (std::size_t i = open + 1; i < close; ++i) {
      if (line[i] == '\\' && i + 3 < close && line[i + 1] == 'x') {
        tok.push_back(std::uint8_t(std::stoi(line.substr(i + 2, 2), nullptr, 16)));
        i += 3;
      } else if (line[i] == '\\' && i + 1 < close) {
        tok.push_back(std::uint8_t(line[++i]));
      } else {
        tok.push_back(std::uint8_t(line[i]));
      }
    }
    out.push_back(std::move(tok));
  }
  return out;
}

struct Rng {
  std::uint64_t s = 0x2545f4914f6cdd1dull;
  std::uint64_t next() {
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    return s;
  }
  std::size_t below(std::size_t n) { return n == 0 ? 0 : std::size_t(next() % n); }
};

// Lengths, counts and sizes at the edges the decoders check: small counts, powers of two and their
// neighbours, zlib's ratio (1032), the log reader's 16 MiB cap, the signed and unsigned limits.
inline constexpr std::uint64_t kInterestingWords[] = {
    0,          1,          2,          7,          8,          15,         16,         27,
    28,         63,         64,         127,        128,        255,        256,        1031,
    1032,       16383,      16384,      16385,      32767,      32768,      65535,      65536,
    0x01000000, 16u << 20,  (16u << 20) + 1,        0x10000000, 0x3fffffff, 0x7fffffff, 0x80000000,
    0xfffffffe, 0xffffffff, 0x7fffffffffffffffull,  0x8000000000000000ull,  0xffffffffffffffffull};
inline constexpr char kSeparators[] = {',', '\n', '\r', ':', ' ', '#', '=', '\0', '-', '.', '+', 'e'};

// One mutated input: 1 to 5 of the mutations above applied to `b`; `pool` gives the splices.
inline void mutate(Bytes& b, Rng& rng, const std::vector<Bytes>& pool, const std::vector<Bytes>& dict) {
  const int rounds = 1 + int(rng.below(5));
  for (int r = 0; r < rounds; ++r) {
    const std::size_t n = b.size();
    switch (rng.below(11)) {
      case 0:  // flip a bit
        if (n) b[rng.below(n)] ^= std::uint8_t(1u << rng.below(8));
        break;
      case 1:  // random byte
        if (n) b[rng.below(n)] = std::uint8_t(rng.next());
        break;
      case 2: {  // an interesting integer of 1, 2, 4 or 8 bytes, either byte order, at any offset
        const std::uint64_t w = kInterestingWords[rng.below(std::size(kInterestingWords))];
        const std::size_t width = std::size_t(1) << rng.below(4);
        const bool big_endian = rng.below(2) == 0;
        if (n >= width) {
          const std::size_t at = rng.below(n - width + 1);
          for (std::size_t k = 0; k < width; ++k) b[at + k] = std::uint8_t(w >> (8 * (big_endian ? width - 1 - k : k)));
        }
        break;
      }
      case 3:
      case 4:  // a dictionary token, inserted or written over
        if (!dict.empty()) {
          const Bytes& t = dict[rng.below(dict.size())];
          const std::size_t at = rng.below(n + 1);
          if (rng.below(2) && at + t.size() <= n) std::copy(t.begin(), t.end(), b.begin() + std::ptrdiff_t(at));
          else b.insert(b.begin() + std::ptrdiff_t(at), t.begin(), t.end());
        }
        break;
      case 5:  // a separator of the text formats
        if (n) b[rng.below(n)] = std::uint8_t(kSeparators[rng.below(std::size(kSeparators))]);
        break;
      case 6:  // insert a few random bytes
        b.insert(b.begin() + std::ptrdiff_t(rng.below(n + 1)), 1 + rng.below(8), std::uint8_t(rng.next()));
        break;
      case 7:  // delete a range
        if (n) {
          const std::size_t at = rng.below(n);
          b.erase(b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(std::min(n, at + 1 + rng.below(32))));
        }
        break;
      case 8:  // duplicate a range (repeated events, rows, fields, chunks)
        if (n && n < (1u << 20)) {
          const std::size_t at = rng.below(n);
          const std::size_t len = std::min(n - at, 1 + rng.below(128));
          const Bytes piece(b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(at + len));
          b.insert(b.begin() + std::ptrdiff_t(rng.below(n + 1)), piece.begin(), piece.end());
        }
        break;
      case 9:  // truncate
        if (n) b.resize(rng.below(n));
        break;
      case 10: {  // the head of this input, the tail of another seed
        const Bytes& other = pool[rng.below(pool.size())];
        if (!other.empty()) {
          const std::size_t from = rng.below(other.size());
          b.resize(rng.below(n + 1));
          b.insert(b.end(), other.begin() + std::ptrdiff_t(from), other.end());
        }
        break;
      }
    }
  }
}

// Mutated inputs from `pool`, `mutate_one` applied to a copy of a random seed, each handed to
// `body`, under the budget above; `iterations_env` names the variable that fixes the count.
using Mutator = std::function<void(Bytes&, Rng&)>;
inline void runMutated(const std::string& label, const std::vector<Bytes>& pool, const Mutator& mutate_one, Body body,
                       const char* iterations_env, int min_inputs) {
  constexpr int kMaxIterations = 200000;
  constexpr double kBudgetS = 2.0;
  const char* fixed = std::getenv(iterations_env);
  const int exact = fixed ? std::atoi(fixed) : 0;
  Rng rng;
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  int i = 0;
  for (; exact > 0 ? i < exact : (i < min_inputs || (i < kMaxIterations && elapsed() < kBudgetS)); ++i) {
    Bytes input = pool[rng.below(pool.size())];
    mutate_one(input, rng);
    Failure f;
    try {
      f = body(input);
    } catch (const std::exception& e) {
      f = std::string("exception escaped the body: ") + e.what();
    }
    if (f) FAIL() << "input " << i << ": " << *f << "\ninput (hex): " << hexOf(input);
  }
  std::printf("%s: %d inputs in %.2f s\n", label.c_str(), i, elapsed());
}

// Every checked-in seed of the target holds the properties.
inline void expectSeedsHold(const std::string& target, Body body) {
  const std::vector<Bytes> pool = loadCorpus(target);
  ASSERT_FALSE(pool.empty()) << "no seeds in tests/fuzz/corpus/" << target;
  for (std::size_t k = 0; k < pool.size(); ++k) {
    const Failure f = body(pool[k]);
    EXPECT_FALSE(f) << target << " seed " << k << ": " << *f << "\ninput: " << hexOf(pool[k]);
  }
}

// The run itself: the target's seeds (each must hold the properties too), then mutated inputs.
inline void shortRun(const std::string& target, Body body, int min_inputs = 3000) {
  expectSeedsHold(target, body);
  if (::testing::Test::HasFailure()) return;
  const std::vector<Bytes> pool = loadCorpus(target);
  const std::vector<Bytes> dict = loadDictionary(target);
  runMutated(
      target, pool, [&](Bytes& b, Rng& rng) { mutate(b, rng, pool, dict); }, body, "THX_FUZZ_ITERATIONS", min_inputs);
}

}  // namespace thx::fuzz
