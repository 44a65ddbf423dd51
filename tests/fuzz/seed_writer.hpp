#pragma once
// Writes a target's seeds as files when THX_FUZZ_WRITE_SEEDS=<dir> is set: how the checked-in
// corpora in tests/fuzz/corpus/<target>/ were made (docs/fuzzing.md). Skipped otherwise.
#include <gtest/gtest.h>

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

}  // namespace thx::fuzz
