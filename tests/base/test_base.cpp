// The error base, strict command-line numbers and JSON string literals.
#include <gtest/gtest.h>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "base/json_text.hpp"

#include <functional>

namespace test_base {

using namespace thx;

namespace {
std::string usageMessage(const std::function<void()>& f) {
  try {
    f();
  } catch (const UsageError& e) {
    EXPECT_EQ(exitStatus(e), 2);
    return e.what();
  }
  return "<no error>";
}
}  // namespace

TEST(Error, KindsAndExitStatus) {
  const Error config(Error::Kind::Config, "scenes/x.yaml:3:1: bad");
  EXPECT_EQ(exitStatus(config), 1);
  EXPECT_STREQ(config.what(), "scenes/x.yaml:3:1: bad");
  const UsageError usage("--rate: bad");
  const Error& as_base = usage;  // one catch in main
  EXPECT_EQ(as_base.kind(), Error::Kind::Usage);
}

TEST(CliNumber, AcceptsWholeNumbersInRange) {
  EXPECT_EQ(cli::parseNumber("--rate", "250", {10, 10000, false, "Hz"}), 250.0);
  EXPECT_EQ(cli::parseNumber("--x", "-1.5e-3"), -1.5e-3);
  EXPECT_EQ(cli::parseInteger("--n", "42", 0, 100), 42);
  EXPECT_EQ(cli::parseIntegerList("--n", "500,2000", 1, 5000), (std::vector<int>{500, 2000}));
  EXPECT_EQ(cli::parseNumberList("--s", "0.02,0.1", {0, 1, false, ""}), (std::vector<double>{0.02, 0.1}));
}

TEST(CliNumber, ErrorsNameTheOptionTheRangeAndTheValue) {
  EXPECT_EQ(usageMessage([] { cli::parseNumber("--rate", "fast", {10, 10000, false, "Hz"}); }),
            "--rate: expected a number in [10, 10000] Hz, got 'fast'");
  EXPECT_EQ(usageMessage([] { cli::parseNumber("--duration", "0", {0, 1e6, true, "s"}); }),
            "--duration: expected a number in (0, 1e+06] s, got '0'");
  EXPECT_EQ(usageMessage([] { cli::parseNumber("--x", "nan"); }), "--x: expected a number, got 'nan'");
  EXPECT_EQ(usageMessage([] { cli::parseNumber("--x", "1.5x"); }), "--x: expected a number, got '1.5x'");
  EXPECT_EQ(usageMessage([] { cli::parseNumber("--x", ""); }), "--x: expected a number, got ''");
  EXPECT_EQ(usageMessage([] { cli::parseInteger("--n", "3.5", 0, 9); }),
            "--n: expected a whole number in [0, 9], got '3.5'");
  EXPECT_EQ(usageMessage([] { cli::parseInteger("--n", "99999999999999999999", 0, 9); }),
            "--n: expected a whole number in [0, 9], got '99999999999999999999'");
  EXPECT_EQ(usageMessage([] { cli::parseNumberList("--s", "0.02,x", {0, 1, false, ""}); }),
            "--s: expected a number in [0, 1], got 'x'");
}

TEST(JsonText, EscapesQuotesBackslashesAndControlCharacters) {
  EXPECT_EQ(json::escaped("plain"), "plain");
  EXPECT_EQ(json::escaped("a\"b\\c"), "a\\\"b\\\\c");
  EXPECT_EQ(json::escaped(std::string("x\ny\x01", 4)), "x\\u000ay\\u0001");
  EXPECT_EQ(json::quoted("scenes/default.yaml"), "\"scenes/default.yaml\"");
}

}  // namespace test_base
