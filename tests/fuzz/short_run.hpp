#pragma once
// The short, deterministic fuzzing run that each fuzz target gets inside `make test` (the VRPN
// decoder's pattern, tests/vrpn/test_fuzz_decoder.cpp, made general): mutate the target's
// checked-in seed corpus (tests/fuzz/corpus/<target>/) with a fixed-seed generator, hand every
// input to the same body the libFuzzer target runs, and fail with the input as hex on the first
// broken property.
//
// The input sequence is fixed. The run always covers the first min_iterations inputs (3000 here,
// 4000 for VRPN), then keeps going through the same sequence until about 2 s have passed, at most
// 200k inputs (so the sanitizer tree, ~20x slower, stays quick); THX_FUZZ_ITERATIONS=N runs
// exactly N inputs. Mutations: bit
// flips, random bytes, big-endian "interesting" 32- and 64-bit words (lengths, counts), the
// target's dictionary tokens, separators of text formats, inserts, deletes, duplications,
// truncations and splices with other seeds.
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
#include <string>
#include <vector>

namespace thx::fuzz {

using Bytes = std::vector<std::uint8_t>;
using Failure = std::optional<std::string>;
using Body = Failure (*)(std::span<const std::uint8_t>);

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

// Every file of tests/fuzz/corpus/<target>/, in name order (so the run does not depend on the
// file system's order).
inline std::vector<Bytes> loadCorpus(const std::string& target) {
  const std::filesystem::path dir = std::filesystem::path(THX_SOURCE_DIR) / "tests/fuzz/corpus" / target;
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::vector<Bytes> out;
  for (const auto& f : files) {
    std::ifstream in(f, std::ios::binary);
    out.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  return out;
}

// The tokens of a libFuzzer dictionary file (tests/fuzz/dict/<target>.dict): every "..." value,
// with \\, \" and \xNN escapes.
inline std::vector<Bytes> loadDictionary(const std::string& target) {
  std::ifstream in(std::string(THX_SOURCE_DIR) + "/tests/fuzz/dict/" + target + ".dict");
  std::vector<Bytes> out;
  for (std::string line; std::getline(in, line);) {
    const std::size_t q = line.find('"');
    if (line.empty() || line[0] == '#' || q == std::string::npos) continue;
    Bytes tok;
    for (std::size_t i = q + 1; i < line.size() && line[i] != '"'; ++i) {
      if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == 'x' && i + 3 < line.size()) {
        tok.push_back(std::uint8_t(std::stoi(line.substr(i + 2, 2), nullptr, 16)));
        i += 3;
      } else if (line[i] == '\\' && i + 1 < line.size()) {
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

inline constexpr std::uint64_t kInterestingWords[] = {
    0, 1, 2, 7, 8, 27, 28, 63, 64, 255, 256, 65535, 65536, 0x7fffffff, 0x80000000, 0xffffffff, 0xfffffffe,
    0x01000000, 16u << 20, (16u << 20) + 1, 0x7fffffffffffffffull, 0x8000000000000000ull, 0xffffffffffffffffull};
inline constexpr char kSeparators[] = {',', '\n', '\r', ':', ' ', '#', '=', '\0', '-', '.', '+', 'e'};

inline void mutate(Bytes& b, Rng& rng, const std::vector<Bytes>& pool, const std::vector<Bytes>& dict) {
  const int rounds = 1 + int(rng.below(4));
  for (int r = 0; r < rounds; ++r) {
    const std::size_t n = b.size();
    switch (rng.below(10)) {
      case 0:  // flip a bit
        if (n) b[rng.below(n)] ^= std::uint8_t(1u << rng.below(8));
        break;
      case 1:  // random byte
        if (n) b[rng.below(n)] = std::uint8_t(rng.next());
        break;
      case 2: {  // big-endian interesting word, 4 or 8 bytes, at any offset
        const std::uint64_t w = kInterestingWords[rng.below(std::size(kInterestingWords))];
        const int len = rng.below(2) ? 8 : 4;
        if (n >= std::size_t(len)) {
          const std::size_t at = rng.below(n - std::size_t(len) + 1);
          for (int k = 0; k < len; ++k) b[at + std::size_t(k)] = std::uint8_t(w >> (8 * (len - 1 - k)));
        }
        break;
      }
      case 3:  // a dictionary token, inserted or overwriting
        if (!dict.empty()) {
          const Bytes& t = dict[rng.below(dict.size())];
          const std::size_t at = rng.below(n + 1);
          if (rng.below(2) && at + t.size() <= n) std::copy(t.begin(), t.end(), b.begin() + std::ptrdiff_t(at));
          else b.insert(b.begin() + std::ptrdiff_t(at), t.begin(), t.end());
        }
        break;
      case 4:  // a separator of the text formats
        if (n) b[rng.below(n)] = std::uint8_t(kSeparators[rng.below(std::size(kSeparators))]);
        break;
      case 5:  // insert a few random bytes
        b.insert(b.begin() + std::ptrdiff_t(rng.below(n + 1)), 1 + rng.below(8), std::uint8_t(rng.next()));
        break;
      case 6:  // delete a range
        if (n) {
          const std::size_t at = rng.below(n);
          b.erase(b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(std::min(n, at + 1 + rng.below(16))));
        }
        break;
      case 7:  // duplicate a range (repeated events, rows, fields)
        if (n && n < 20000) {
          const std::size_t at = rng.below(n);
          const std::size_t len = std::min(n - at, 1 + rng.below(96));
          const Bytes piece(b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(at + len));
          b.insert(b.begin() + std::ptrdiff_t(rng.below(n + 1)), piece.begin(), piece.end());
        }
        break;
      case 8:  // truncate
        if (n) b.resize(rng.below(n));
        break;
      case 9: {  // splice the tail of another seed
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

// Mutated inputs from `pool`, `mutate` applied to a copy of a random seed, each handed to `body`,
// under the budget above; `iterations_env` names the variable that fixes the count.
using Mutator = std::function<void(Bytes&, Rng&)>;
inline void runMutated(const std::string& label, const std::vector<Bytes>& pool, const Mutator& mutate_one, Body body,
                       const char* iterations_env, int min_iterations) {
  constexpr int kMaxIterations = 200000;
  constexpr double kBudgetS = 2.0;
  const char* fixed = std::getenv(iterations_env);
  const int exact = fixed ? std::atoi(fixed) : 0;
  Rng rng;
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  int i = 0;
  for (; exact > 0 ? i < exact : (i < min_iterations || (i < kMaxIterations && elapsed() < kBudgetS)); ++i) {
    Bytes input = pool[rng.below(pool.size())];
    mutate_one(input, rng);
    if (const Failure f = body(input)) FAIL() << "iteration " << i << ": " << *f << "\ninput: " << hexOf(input);
  }
  std::printf("%s: %d inputs in %.2f s\n", label.c_str(), i, elapsed());
}

// The run itself: the target's seeds (each must hold the properties too), then mutated inputs.
inline void shortRun(const std::string& target, Body body) {
  const std::vector<Bytes> pool = loadCorpus(target);
  const std::vector<Bytes> dict = loadDictionary(target);
  ASSERT_FALSE(pool.empty()) << "no seeds in tests/fuzz/corpus/" << target;
  for (const Bytes& s : pool)
    if (const Failure f = body(s)) FAIL() << "seed: " << *f << "\ninput: " << hexOf(s);
  runMutated(
      target, pool, [&](Bytes& b, Rng& rng) { mutate(b, rng, pool, dict); }, body, "THX_FUZZ_ITERATIONS", 3000);
}

}  // namespace thx::fuzz
