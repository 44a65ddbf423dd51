#pragma once
// What every test_fuzz_*.cpp shares: the checked-in corpus and dictionary of a target, the short
// run inside gtest, and writing freshly generated seeds when asked (to regenerate the corpus).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/fuzz/format_short_run.hpp"

namespace thx::fuzz::test {

inline std::filesystem::path fuzzDir() { return std::filesystem::path(THX_SOURCE_DIR) / "tests" / "fuzz"; }
inline std::vector<Bytes> corpusOf(const std::string& target) { return readCorpus(fuzzDir() / "corpus" / target); }
inline std::vector<Bytes> dictionaryOf(const std::string& target) {
  return readDictionary(fuzzDir() / "dict" / (target + ".dict"));
}

// Every checked-in seed holds the properties.
inline void expectSeedsHold(Body body, const std::string& target) {
  const std::vector<Bytes> seeds = corpusOf(target);
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    const Failure f = body(seeds[k]);
    EXPECT_FALSE(f) << target << " seed " << k << ": " << *f;
  }
}

// The fixed-seed run (short_run.hpp): at least min_inputs, then up to ~2 s.
inline void expectShortRun(Body body, const std::string& target, int min_inputs) {
  const ShortRun run = shortRun(body, corpusOf(target), dictionaryOf(target), min_inputs, 2.0, 200000);
  EXPECT_FALSE(run.failure) << *run.failure;
  std::printf("%s: %d inputs in %.2f s\n", target.c_str(), run.inputs, run.seconds);
}

// With THX_FUZZ_FORMATS_WRITE_SEEDS=DIR, writes the generated seeds as DIR/<target>/seed-NN.
inline void writeSeedsWhenAsked(const std::string& target, const std::vector<Bytes>& seeds) {
  const char* dir = std::getenv("THX_FUZZ_FORMATS_WRITE_SEEDS");
  if (!dir) GTEST_SKIP() << "set THX_FUZZ_FORMATS_WRITE_SEEDS=<dir> to write the seed corpus";
  const std::filesystem::path out = std::filesystem::path(dir) / target;
  std::filesystem::create_directories(out);
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "seed-%02zu", k);
    std::ofstream f(out / name, std::ios::binary);
    f.write(reinterpret_cast<const char*>(seeds[k].data()), std::streamsize(seeds[k].size()));
    ASSERT_TRUE(f) << (out / name);
  }
}

}  // namespace thx::fuzz::test
