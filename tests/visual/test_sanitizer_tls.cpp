// The sanitizer tree's executables run without ASan's __tls_get_addr interception
// (base/sanitizer/asan_defaults.cpp): GCC 12's libasan misreads a dynamic TLS block 16 bytes into a
// page, and LeakSanitizer then crashed at exit by chance in programs that render with Mesa (whose
// llvmpipe loads libLLVM with dynamic TLS). The check: visual-client renders a picture with ASan
// at verbosity 2, which logs every intercepted __tls_get_addr call; there must be none, and the
// program (leak check included) must end cleanly. In the optimised tree there is nothing to check.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <string>

#include "tests/support/process.hpp"
#include "tests/support/sanitized_build.hpp"
#include "tests/support/temp_dir.hpp"

namespace thx::test::test_sanitizer_tls {
namespace {

TEST(SanitizerDefaults, ARenderingProgramRecordsNoDynamicTls) {
  if (!kSanitized) GTEST_SKIP() << "not a sanitizer build";
  const TempDir dir("sanitizer_tls");
  // The environment's options are added to the compiled-in defaults (they win per option).
  ASSERT_EQ(setenv("ASAN_OPTIONS", "detect_leaks=1:abort_on_error=1:verbosity=2", 1), 0);
  const std::string err = dir.file("visual.err");
  const pid_t pid = spawnIn(THX_SOURCE_DIR,
                            {THX_VISUAL_CLIENT, "--scene", "scenes/default.yaml", "--screenshot",
                             dir.file("frame.ppm"), "--size", "64x36"},
                            dir.file("visual.out"), err);
  ASSERT_GT(pid, 0);
  EXPECT_EQ(reap(pid, 120), 0) << slurp(err).substr(0, 4000);
  const std::string log = slurp(err);
  ASSERT_NE(log.find("AddressSanitizer Init done"), std::string::npos) << "verbosity 2 logs the runtime's start";
  EXPECT_EQ(log.find("__tls_get_addr:"), std::string::npos) << "an intercepted __tls_get_addr call was logged";
}

}  // namespace
}  // namespace thx::test::test_sanitizer_tls
