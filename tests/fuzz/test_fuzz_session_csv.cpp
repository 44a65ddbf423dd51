// The study session CSV reader under the short fixed-seed fuzz run (tests/fuzz/short_run.hpp,
// body in session_csv_body.hpp), its seeds, and formatSession against the file writer.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <sstream>

#include "tests/fuzz/seed_writer.hpp"
#include "tests/fuzz/session_csv_body.hpp"
#include "tests/fuzz/short_run.hpp"
#include "tests/study/study_fixtures.hpp"
#include "tests/support/temp_dir.hpp"

namespace thx::fuzz::test_fuzz_session_csv {
namespace {

// One session of each study (study_fixtures.hpp), one with extra header lines and optional fields
// left empty, as the writer writes them.
std::vector<std::pair<std::string, Bytes>> seeds() {
  using namespace study;
  Session id = fixtures::identificationSessions().front();
  Session rv = fixtures::ratingSessions().front();
  Session extra = id;
  extra.header.extra = {{"started", "2026-11-26 02:40"}, {"scenes", "scenes/study1"}};
  extra.trials.resize(2);
  extra.trials[1].ratings = {};
  extra.trials[1].time_s = 0.125;
  return {{"identification.csv", bytesOf(formatSession(id, "seed"))},
          {"relief_vs_normal.csv", bytesOf(formatSession(rv, "seed"))},
          {"extra_header.csv", bytesOf(formatSession(extra, "seed"))}};
}

TEST(FuzzSessionCsv, WriteSeedCorpusWhenAsked) { writeSeedsWhenAsked(seeds()); }

TEST(FuzzSessionCsv, CheckedInSeedsAreTheGeneratedOnes) {
  const std::vector<Bytes> corpus = loadCorpus("session_csv");
  for (const auto& [name, bytes] : seeds())
    EXPECT_NE(std::find(corpus.begin(), corpus.end(), bytes), corpus.end()) << name << " missing from the corpus";
}

// formatSession is the text SessionWriter writes, so the fuzz run's round trip is the file's.
TEST(FuzzSessionCsv, FormatSessionIsWhatTheWriterWrites) {
  test::TempDir dir("thx_fuzz");
  for (const auto& [name, bytes] : seeds()) {
    const study::Session s = study::parseSession(std::string(bytes.begin(), bytes.end()), name);
    const std::string path = dir.file(name);
    study::writeSession(path, s);
    std::ifstream f(path, std::ios::binary);
    std::stringstream text;
    text << f.rdbuf();
    EXPECT_EQ(text.str(), std::string(bytes.begin(), bytes.end())) << name;
    EXPECT_EQ(study::readSession(path).trials, s.trials) << name;
  }
}

// Found by the long run (corpus/session_csv/regression_nul_in_header_key): a header key holding a
// NUL was quoted raw in the error, so what() ended at the NUL and the message lost its reason.
// Text from the file is now quoted with shownText(): non-printable bytes as \xNN, at most 100
// characters.
TEST(FuzzSessionCsv, ErrorsQuoteTheFileSafely) {
  const std::string head = "# texhaptics study session\n# format: 1\n";
  auto error = [](const std::string& text) {
    try {
      study::parseSession(text, "s.csv");
    } catch (const study::SessionError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string key("k\0y", 3);
  EXPECT_EQ(error(head + "# " + key + ": a\n# " + key + ": b\n"), "s.csv:4: header key 'k\\x00y' appears twice");
  EXPECT_EQ(error(head + "#\x01\n"), "s.csv:3: expected a header line '# key: value', got '#\\x01'");
  EXPECT_EQ(error(head + "# seed: " + std::string(300, '7') + "\n"),
            "s.csv:3: field 'seed': expected a whole number in [0, 2^64), got '" + std::string(100, '7') + "...'");
  std::ifstream f(std::string(THX_SOURCE_DIR) + "/tests/fuzz/corpus/session_csv/regression_nul_in_header_key",
                  std::ios::binary);
  const Bytes found((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(found.empty());
  EXPECT_EQ(session_csv::fuzzOnce(found), std::nullopt);
}

TEST(FuzzSessionCsv, ShortRun) { shortRun("session_csv", &session_csv::fuzzOnce); }

}  // namespace
}  // namespace thx::fuzz::test_fuzz_session_csv
