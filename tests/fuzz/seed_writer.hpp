#pragma once
// Writes a target's seeds as files when THX_FUZZ_WRITE_SEEDS=<dir> is set: how the checked-in
// corpora in tests/fuzz/corpus/<target>/ were made (docs/fuzzing.md). Skipped otherwise.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "tests/fuzz/short_run.hpp"

namespace thx::fuzz {

inline void writeSeedsWhenAsked(const std::vector<std::pair<std::string, Bytes>>& seeds) {
  const char* dir = std::getenv("THX_FUZZ_WRITE_SEEDS");
  if (!dir) GTEST_SKIP() << "set THX_FUZZ_WRITE_SEEDS=<dir> to write the seed corpus";
  for (const auto& [name, bytes] : seeds) {
    std::ofstream f(std::string(dir) + "/" + name, std::ios::binary);
    f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    ASSERT_TRUE(f.good()) << dir << "/" << name;
  }
}

// Seeds without names of their own are written as seed-00, seed-01, ...
inline void writeSeedsWhenAsked(const std::vector<Bytes>& seeds) {
  std::vector<std::pair<std::string, Bytes>> named;
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "seed-%02zu", k);
    named.emplace_back(name, seeds[k]);
  }
  writeSeedsWhenAsked(named);
}

}  // namespace thx::fuzz
