// libFuzzer entry point for the lcm_messages fuzz target (built only with -DTHX_FUZZ=ON and clang; the
// long-run command is in docs/fuzzing.md). A broken property aborts with its description.
#include <cstdio>
#include <cstdlib>

#include "tests/fuzz/lcm_messages_body.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (auto failure = thx::fuzz::lcm_messages::fuzzOnce(std::span(data, size))) {
    std::fprintf(stderr, "lcm_messages: property broken: %s\n", failure->c_str());
    std::abort();
  }
  return 0;
}
