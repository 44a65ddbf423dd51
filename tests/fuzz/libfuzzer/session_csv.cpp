// libFuzzer entry point for the session_csv fuzz target (built only with -DTHX_FUZZ=ON and clang; the
// long-run command is in docs/fuzzing.md). A broken property aborts with its description.
#include <cstdio>
#include <cstdlib>

#include "tests/fuzz/session_csv_body.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (auto failure = thx::fuzz::session_csv::fuzzOnce(std::span(data, size))) {
    std::fprintf(stderr, "session_csv: property broken: %s\n", failure->c_str());
    std::abort();
  }
  return 0;
}
