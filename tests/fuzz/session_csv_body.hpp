#pragma once
// One fuzzing step for the study session CSV reader (clients/study/session_csv.hpp: parseSession,
// which readSession runs on a file's text), shared by the libFuzzer target
// (libfuzzer/session_csv.cpp) and the short run in `make test` (test_fuzz_session_csv.cpp).
// Returns the first broken property.
//
// Properties:
//  1. a refused input throws SessionError whose message starts with "FILE:LINE: " and names the
//     field or what was expected; nothing else escapes;
//  2. an accepted session is accepted by the writer's rules too (formatSession, the same text
//     SessionWriter writes), reads back equal (header and every row), and its text is a fixed
//     point: format(read(format(s))) == format(s).
// The reader allocates only in proportion to the text (lines, fields); no length comes from the
// input.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "clients/study/session_csv.hpp"

namespace thx::fuzz::session_csv {

using Failure = std::optional<std::string>;

inline constexpr char kName[] = "fuzz.csv";

inline bool namesLine(const std::string& what, const std::string& file) {
  if (what.rfind(file + ":", 0) != 0) return false;
  std::size_t i = file.size() + 1, digits = 0;
  while (i < what.size() && what[i] >= '0' && what[i] <= '9') ++i, ++digits;
  return digits > 0 && what.compare(i, 2, ": ") == 0;
}

inline bool namesWhat(const std::string& what) {
  for (const char* k : {"field '", "expected", "appears twice", "missing the line"})
    if (what.find(k) != std::string::npos) return true;
  return false;
}

inline Failure fuzzOnce(std::span<const std::uint8_t> data) {
  const std::string_view text(reinterpret_cast<const char*>(data.data()), data.size());
  study::Session s;
  try {
    s = study::parseSession(text, kName);
  } catch (const study::SessionError& e) {
    const std::string what = e.what();
    if (!namesLine(what, kName)) return "refusal does not start with 'fuzz.csv:LINE: ': " + what;
    if (!namesWhat(what)) return "refusal names no field or expectation: " + what;
    return std::nullopt;
  } catch (const std::exception& e) {
    return std::string("unexpected exception from the reader: ") + e.what();
  }
  std::string written;
  try {
    written = study::formatSession(s, "out.csv");
  } catch (const std::exception& e) {
    return std::string("the writer refuses what the reader accepted: ") + e.what();
  }
  study::Session back;
  try {
    back = study::parseSession(written, "out.csv");
  } catch (const std::exception& e) {
    return std::string("the reader refuses what the writer wrote: ") + e.what() + "\ntext:\n" + written;
  }
  if (!(back.header == s.header)) return "the header does not read back equal\ntext:\n" + written;
  if (back.trials != s.trials) return "the rows do not read back equal\ntext:\n" + written;
  if (study::formatSession(back, "out.csv") != written) return "the written text is not a fixed point\ntext:\n" + written;
  return std::nullopt;
}

}  // namespace thx::fuzz::session_csv
