#pragma once
// Rasterising a box on a relief runs ~300x slower in the sanitizer build: tests that run whole
// scenes use coarser texels there (tests/support/sanitized_build.hpp).
#include "tests/support/sanitized_build.hpp"

namespace thx::physclient::test {
using thx::test::kSanitized;
}  // namespace thx::physclient::test
