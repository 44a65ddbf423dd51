#pragma once
// The short, deterministic mutation run every file-format fuzz body gets inside `make test`
// (the long runs use libFuzzer, docs/fuzzing_formats.md). Seeds are the checked-in corpus of the
// target (tests/fuzz/corpus/<target>/, read in file-name order) and the target's dictionary; the
// mutations are a fixed-seed sequence of bit flips, random bytes, boundary integers (1, 2 and 4
// bytes, both byte orders) at any offset, dictionary tokens inserted or written over, deletions,
// duplications, truncations and splices with another seed.
//
// The run always covers the first `min_inputs` inputs, then continues through the same sequence
// until `budget_s` has passed (so an unoptimised sanitizer build still finishes in seconds). The
// environment variable THX_FUZZ_FORMATS_ITERATIONS=N runs exactly N inputs instead. A failure
// names the input's number and gives it as hex, which reproduces it anywhere.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace thx::fuzz {

using Bytes = std::vector<std::uint8_t>;
// The description of the first broken property, or nothing.
using Failure = std::optional<std::string>;
using Body = Failure (*)(std::span<const std::uint8_t>);

// A refused input's message must say which input it was.
inline Failure mustName(const std::string& message, const std::string& source, const char* what) {
  if (message.find(source) == std::string::npos)
    return std::string(what) + " does not name '" + source + "': " + message;
  return std::nullopt;
}

inline Bytes readBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  return Bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline std::vector<Bytes> readCorpus(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::vector<Bytes> corpus;
  for (const auto& f : files) corpus.push_back(readBytes(f));
  if (corpus.empty()) throw std::runtime_error("empty seed corpus " + dir.string());
  return corpus;
}

// libFuzzer's dictionary format: one "token" per line, optionally name="token"; \\, \" and \xNN
// escapes; # comments.
inline std::vector<Bytes> readDictionary(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::vector<Bytes> tokens;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const auto open = line.find('"');
    if (line.empty() || line[0] == '#' || open == std::string::npos) continue;
    const auto close = line.rfind('"');
    if (close <= open) throw std::runtime_error(path.string() + ":" + std::to_string(number) + ": unterminated token");
    Bytes token;
    for (std::size_t k = open + 1; k < close; ++k) {
      if (line[k] != '\\') {
        token.push_back(std::uint8_t(line[k]));
      } else if (k + 3 < close + 1 && line[k + 1] == 'x') {
        token.push_back(std::uint8_t(std::stoi(line.substr(k + 2, 2), nullptr, 16)));
        k += 3;
      } else {
        token.push_back(std::uint8_t(line[++k]));
      }
    }
    tokens.push_back(std::move(token));
  }
  return tokens;
}

class Mutator {
 public:
  Mutator(const std::vector<Bytes>& seeds, const std::vector<Bytes>& dictionary, std::uint64_t seed)
      : seeds_(seeds), dictionary_(dictionary), state_(seed | 1u) {}

  Bytes next() {
    Bytes b = seeds_[below(seeds_.size())];
    const int rounds = 1 + int(below(5));
    for (int r = 0; r < rounds; ++r) mutateOnce(b);
    return b;
  }

 private:
  std::uint64_t random() {
    state_ ^= state_ >> 12;
    state_ ^= state_ << 25;
    state_ ^= state_ >> 27;
    return state_ * 0x2545f4914f6cdd1dull;
  }
  std::size_t below(std::size_t n) { return n == 0 ? 0 : std::size_t(random() % n); }

  void putInteger(Bytes& b) {
    static constexpr std::uint32_t kBoundaries[] = {0,     1,     2,          7,          8,          15,        16,
                                                    127,   128,   255,        256,        1031,       1032,      16383,
                                                    16384, 16385, 32767,      32768,      65535,      65536,     0x7fffffff,
                                                    0x80000000,   0xfffffffe, 0xffffffff, 0x10000000, 0x3fffffff};
    const std::size_t width = std::size_t(1) << below(3);  // 1, 2 or 4 bytes
    if (b.size() < width) return;
    const std::size_t at = below(b.size() - width + 1);
    const std::uint32_t v = kBoundaries[below(std::size(kBoundaries))];
    const bool big_endian = below(2) == 0;
    for (std::size_t k = 0; k < width; ++k)
      b[at + k] = std::uint8_t(v >> (8 * (big_endian ? width - 1 - k : k)));
  }

  void mutateOnce(Bytes& b) {
    const std::size_t n = b.size();
    switch (below(10)) {
      case 0:
        if (n) b[below(n)] ^= std::uint8_t(1u << below(8));
        break;
      case 1:
        if (n) b[below(n)] = std::uint8_t(random());
        break;
      case 2: putInteger(b); break;
      case 3:
      case 4: {  // a dictionary token, inserted or written over
        if (dictionary_.empty()) break;
        const Bytes& t = dictionary_[below(dictionary_.size())];
        const std::size_t at = below(n + 1);
        if (below(2) == 0 || at + t.size() > n) {
          b.insert(b.begin() + std::ptrdiff_t(at), t.begin(), t.end());
        } else {
          std::copy(t.begin(), t.end(), b.begin() + std::ptrdiff_t(at));
        }
        break;
      }
      case 5:  // delete a range
        if (n > 1) {
          const std::size_t at = below(n);
          b.erase(b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(std::min(n, at + 1 + below(32))));
        }
        break;
      case 6:  // duplicate a range
        if (n > 1 && n < (1u << 20)) {
          const std::size_t at = below(n), len = std::min(n - at, 1 + below(128));
          const Bytes piece(b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(at + len));
          b.insert(b.begin() + std::ptrdiff_t(below(n + 1)), piece.begin(), piece.end());
        }
        break;
      case 7:
        if (n > 1) b.resize(below(n));
        break;
      case 8: {  // the head of this seed, the tail of another
        const Bytes& other = seeds_[below(seeds_.size())];
        b.resize(below(n + 1));
        const std::size_t from = below(other.size() + 1);
        b.insert(b.end(), other.begin() + std::ptrdiff_t(from), other.end());
        break;
      }
      case 9:  // a few random bytes inserted
        b.insert(b.begin() + std::ptrdiff_t(below(n + 1)), 1 + below(8), std::uint8_t(random()));
        break;
    }
  }

  const std::vector<Bytes>& seeds_;
  const std::vector<Bytes>& dictionary_;
  std::uint64_t state_;
};

inline std::string hexOf(std::span<const std::uint8_t> b) {
  static const char* kHex = "0123456789abcdef";
  std::string s;
  for (std::uint8_t c : b) {
    s += kHex[c >> 4];
    s += kHex[c & 15];
  }
  return s;
}

struct ShortRun {
  int inputs = 0;
  double seconds = 0.0;
  Failure failure;  // with the input's number and hex
};

// Runs `body` on mutated seeds as described at the top. Exceptions the body lets through are
// failures too (in libFuzzer they abort).
inline ShortRun shortRun(Body body, const std::vector<Bytes>& seeds, const std::vector<Bytes>& dictionary,
                         int min_inputs, double budget_s, int max_inputs) {
  const char* fixed = std::getenv("THX_FUZZ_FORMATS_ITERATIONS");
  const int exact = fixed ? std::atoi(fixed) : 0;
  Mutator mutator(seeds, dictionary, 0x9e3779b97f4a7c15ull);
  ShortRun run;
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  for (; exact > 0 ? run.inputs < exact
                   : (run.inputs < min_inputs || (run.inputs < max_inputs && elapsed() < budget_s));
       ++run.inputs) {
    const Bytes input = mutator.next();
    Failure f;
    try {
      f = body(input);
    } catch (const std::exception& e) {
      f = std::string("exception escaped the body: ") + e.what();
    }
    if (f) {
      run.failure = "input " + std::to_string(run.inputs) + ": " + *f + "\ninput (hex): " + hexOf(input);
      break;
    }
  }
  run.seconds = elapsed();
  return run;
}

}  // namespace thx::fuzz
