// libFuzzer entry point for the VRPN decoder (built only with -DTHX_VRPN_FUZZ=ON and clang; the
// long-run command is in docs/vrpn.md). Any broken invariant aborts with its description.
#include <cstdio>
#include <cstdlib>

#include "tests/vrpn/fuzz_decoder_body.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (auto failure = thx::vrpn::fuzz::fuzzDecoderOnce(std::span(data, size))) {
    std::fprintf(stderr, "vrpn decoder invariant broken: %s\n", failure->c_str());
    std::abort();
  }
  return 0;
}
