#pragma once
// The terminal prompt a real session asks its ratings with: a question and its scale, re-asked
// until the answer is a whole number in the scale (docs/study.md §5.3).
#include <iosfwd>
#include <optional>
#include <string>

namespace thx::study {

// Asks on `out`, reads lines from `in` until one holds a whole number in [min, max] (spaces
// around it allowed); says what was wrong before asking again. Empty when `in` ends first.
std::optional<int> askRating(std::istream& in, std::ostream& out, const std::string& question, int min, int max);

}  // namespace thx::study
