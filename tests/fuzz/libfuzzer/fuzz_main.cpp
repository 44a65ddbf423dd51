// libFuzzer entry point for one file-format fuzz body (built once per body with
// -DTHX_FUZZ=ON and clang; tests/fuzz/CMakeLists.txt names the header and the function).
// A broken property aborts with its description; the long-run commands are in
// docs/fuzzing_formats.md.
#include <cstdio>
#include <cstdlib>

#include THX_FUZZ_BODY_HEADER

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (auto failure = thx::fuzz::THX_FUZZ_BODY(std::span(data, size))) {
    std::fprintf(stderr, "%s: property broken: %s\n", THX_FUZZ_NAME, failure->c_str());
    std::abort();
  }
  return 0;
}
