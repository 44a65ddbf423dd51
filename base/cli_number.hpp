#pragma once
// Strict number parsing for command lines: the whole text must be a finite number inside the
// option's range, or UsageError names the option, the range with its unit and what was given:
//   --rate: expected a number in [10, 10000] Hz, got 'fast'
#include <string>
#include <string_view>
#include <vector>

namespace thx::cli {

struct Range {
  double min = -1e300, max = 1e300;
  bool min_open = false;  // (min, max] instead of [min, max]
  std::string_view unit;  // "Hz", "s", ... ("" for none)
};

double parseNumber(std::string_view option, std::string_view text, const Range& range = {});
// A whole number in [min, max].
long long parseInteger(std::string_view option, std::string_view text, long long min, long long max);
// A comma-separated list of whole numbers, each in [min, max] ("500,2000,5000").
std::vector<int> parseIntegerList(std::string_view option, std::string_view text, int min, int max);
// A comma-separated list of numbers, each as parseNumber reads it ("0.02,0.05,0.1").
std::vector<double> parseNumberList(std::string_view option, std::string_view text, const Range& range = {});

}  // namespace thx::cli
