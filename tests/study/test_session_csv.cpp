// The session CSV: what the writer writes reads back equal, every row is on disk once append()
// returns, and each kind of bad input is refused with its file, line and field.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "clients/study/session_csv.hpp"
#include "tests/study/study_fixtures.hpp"
#include "tests/support/error_text.hpp"
#include "tests/support/temp_dir.hpp"

namespace thx::study::test_session_csv {
namespace {

using test::errorOf;

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream s(text);
  for (std::string l; std::getline(s, l);) out.push_back(l);
  return out;
}

std::string join(const std::vector<std::string>& ls) {
  std::string s;
  for (const std::string& l : ls) s += l + "\n";
  return s;
}

// The text with line `n` (1-based) replaced.
std::string withLine(const std::string& text, int n, const std::string& line) {
  std::vector<std::string> ls = lines(text);
  ls.at(std::size_t(n - 1)) = line;
  return join(ls);
}

// The text with field `k` (0-based) of line `n` replaced.
std::string withField(const std::string& text, int n, int k, const std::string& value) {
  std::vector<std::string> ls = lines(text);
  std::vector<std::string> f;
  std::stringstream s(ls.at(std::size_t(n - 1)) + ",");
  for (std::string x; std::getline(s, x, ',');) f.push_back(x);
  f.at(std::size_t(k)) = value;
  std::string l;
  for (std::size_t i = 0; i < f.size(); ++i) l += (i ? "," : "") + f[i];
  ls[std::size_t(n - 1)] = l;
  return join(ls);
}

void expectSame(const Session& a, const Session& b) {
  EXPECT_EQ(a.header, b.header);
  ASSERT_EQ(a.trials.size(), b.trials.size());
  for (std::size_t i = 0; i < a.trials.size(); ++i) EXPECT_EQ(a.trials[i], b.trials[i]) << "row " << i;
}

TEST(SessionCsv, RoundTripsBothStudies) {
  test::TempDir dir("study_csv");
  std::vector<Session> all = fixtures::identificationSessions();
  for (Session& s : fixtures::ratingSessions()) all.push_back(s);
  // Times that print with many digits, a mesh row, runner-defined header lines.
  all[0].trials[1].time_s = 0.1 + 0.2;
  all[0].trials[2].time_s = 1.0 / 3.0;
  all[0].trials[3].representation = Representation::Mesh;
  all[0].header.extra = {{"started", "2026-11-26T00:00:00Z"}, {"scenes", "scenes/study1"}};
  for (const Session& s : all) {
    const std::string path = dir.file(s.header.participant + "_" + std::string(studyName(s.header.study)) + ".csv");
    writeSession(path, s);
    const Session back = readSession(path);
    EXPECT_EQ(back.source, path);
    expectSame(s, back);
  }
}

TEST(SessionCsv, EveryAppendedRowIsOnDiskAtOnce) {
  test::TempDir dir("study_csv");
  const Session s = fixtures::identificationSessions()[0];
  const std::string path = dir.file("live.csv");
  SessionWriter w(path, s.header);
  EXPECT_TRUE(readSession(path).trials.empty());
  for (std::size_t i = 0; i < s.trials.size(); ++i) {
    w.append(s.trials[i]);
    // Read while the writer is still open, as after a crash of the runner.
    EXPECT_EQ(readSession(path).trials.size(), i + 1);
  }
}

TEST(SessionCsv, TheFileLooksAsDocumented) {
  test::TempDir dir("study_csv");
  const Session s = fixtures::identificationSessions()[0];
  writeSession(dir.file("p1.csv"), s);
  const std::vector<std::string> ls = lines(slurp(dir.file("p1.csv")));
  ASSERT_EQ(ls.size(), 8u + 6u);
  EXPECT_EQ(ls[0], "# texhaptics study session");
  EXPECT_EQ(ls[1], "# format: 1");
  EXPECT_EQ(ls[2], "# study: identification");
  EXPECT_EQ(ls[3], "# participant: P1");
  EXPECT_EQ(ls[4], "# seed: 11");
  EXPECT_EQ(ls[5], "# software: texhaptics 0.1 test");
  EXPECT_EQ(ls[6], "# surfaces: bricks_a=bricks bricks_b=bricks metal_a=metal metal_b=metal wood_a=wood wood_b=wood");
  EXPECT_EQ(ls[7],
            "trial,surface,representation,sound,ball,pen,answer,correct,time_s,ease,use_sound,use_ball,use_pen,"
            "acc_sound,acc_ball,acc_pen,realism,match_physics,match_sound,match_haptics,overall");
  EXPECT_EQ(ls[8], "1,bricks_a,normal,1,1,1,bricks_a,1,10,6,3,2,5,7,4,9,,,,,");
  EXPECT_EQ(ls[11], "4,bricks_b,normal,0,1,1,wood_a,0,40,6,,2,5,,4,9,,,,,");
}

struct BadCase {
  std::string name;
  std::function<std::string(const std::string&)> mutate;
  std::string expected;  // the whole message after the file name
};

TEST(SessionCsv, BadInputNamesFileLineAndField) {
  test::TempDir dir("study_csv");
  writeSession(dir.file("id.csv"), fixtures::identificationSessions()[0]);
  writeSession(dir.file("rv.csv"), fixtures::ratingSessions()[0]);
  const std::string id = slurp(dir.file("id.csv")), rv = slurp(dir.file("rv.csv"));
  const std::vector<std::pair<std::string, BadCase>> cases = {
      {id, {"magic", [](auto t) { return withLine(t, 1, "trial,surface"); },
            ":1: expected '# texhaptics study session' (not a session file of this project)"}},
      {id, {"format", [](auto t) { return withLine(t, 2, "# format: 2"); },
            ":2: field 'format': expected 1 (the format this reader knows), got '2'"}},
      {id, {"no seed", [](auto t) { return withLine(t, 5, "# note: none"); },
            ":1: header: missing the line '# seed: ...'"}},
      {id, {"study", [](auto t) { return withLine(t, 3, "# study: study3"); },
            ":3: field 'study': expected identification or relief-vs-normal, got 'study3'"}},
      {id, {"seed", [](auto t) { return withLine(t, 5, "# seed: -4"); },
            ":5: field 'seed': expected a whole number in [0, 2^64), got '-4'"}},
      {id, {"twice", [](auto t) { return withLine(t, 5, "# participant: P2"); },
            ":5: header key 'participant' appears twice"}},
      {id, {"header line", [](auto t) { return withLine(t, 6, "# software=1"); },
            ":6: expected a header line '# key: value', got '# software=1'"}},
      {id, {"surfaces item", [](auto t) { return withLine(t, 7, "# surfaces: bricks_a wood_a=wood"); },
            ":7: field 'surfaces': expected space-separated NAME=FAMILY items, got 'bricks_a'"}},
      {id, {"participant", [](auto t) { return withLine(t, 4, "# participant: P 1"); },
            ":1: header: field 'participant': expected letters, digits or _-.+, got 'P 1'"}},
      {id, {"columns", [](auto t) { return withLine(t, 8, "trial,surface"); },
            ":8: expected the column line '" + columnLine() + "', got 'trial,surface'"}},
      {id, {"field count", [](auto t) { return withLine(t, 9, "1,bricks_a,normal"); },
            ":9: expected 21 comma-separated fields, got 3"}},
      {id, {"trial", [](auto t) { return withField(t, 9, 0, "0"); },
            ":9: field 'trial': expected a trial number >= 1, got '0'"}},
      {id, {"trial order", [](auto t) { return withField(t, 10, 0, "1"); },
            ":10: field 'trial': expected a trial number above the previous row's 1, got 1"}},
      {id, {"surface", [](auto t) { return withField(withField(t, 9, 1, "glass"), 9, 7, "0"); },
            ":9: field 'surface': 'glass' is not one of the header's surfaces (bricks_a, bricks_b, metal_a, "
            "metal_b, wood_a, wood_b)"}},
      {id, {"representation", [](auto t) { return withField(t, 9, 2, "bump"); },
            ":9: field 'representation': expected normal, relief or mesh, got 'bump'"}},
      {id, {"cue", [](auto t) { return withField(t, 9, 4, "2"); },
            ":9: field 'ball': expected 1 (cue on) or 0 (off), got '2'"}},
      {id, {"answer", [](auto t) { return withField(t, 9, 6, "glass"); },
            ":9: field 'answer': 'glass' is not one of the header's surfaces (bricks_a, bricks_b, metal_a, "
            "metal_b, wood_a, wood_b)"}},
      {id, {"no answer", [](auto t) { return withField(t, 9, 6, ""); },
            ":9: field 'answer': study identification needs the surface chosen"}},
      {id, {"correct", [](auto t) { return withField(t, 9, 7, "0"); },
            ":9: field 'correct': 0 contradicts answer 'bricks_a' for surface 'bricks_a'"}},
      {id, {"time", [](auto t) { return withField(t, 9, 8, "abc"); },
            ":9: field 'time_s': expected seconds (a number) or nothing, got 'abc'"}},
      {id, {"negative time", [](auto t) { return withField(t, 9, 8, "-1"); },
            ":9: field 'time_s': expected seconds >= 0, got -1"}},
      {id, {"no time", [](auto t) { return withField(t, 9, 8, ""); },
            ":9: field 'time_s': study identification needs the time to answer"}},
      {id, {"ease", [](auto t) { return withField(t, 9, 9, "11"); },
            ":9: field 'ease': expected a whole number in [1, 10], got 11"}},
      {id, {"use", [](auto t) { return withField(t, 9, 10, "2.5"); },
            ":9: field 'use_sound': expected a whole number or nothing, got '2.5'"}},
      {id, {"other study's rating", [](auto t) { return withField(t, 9, 16, "5"); },
            ":9: field 'realism': study identification leaves it empty, got 5"}},
      {rv, {"missing rating", [](auto t) { return withField(t, 9, 20, ""); },
            ":9: field 'overall': study relief-vs-normal needs this rating"}},
      {rv, {"rated twice", [](auto t) { return withField(t, 10, 1, "wood_1"); },
            ":10: field 'surface': 'wood_1' was already rated in this session (each surface once, as relief or "
            "as normal)"}},
      {rv, {"answer in study 2", [](auto t) { return withField(t, 9, 6, "tile"); },
            ":9: field 'answer': study relief-vs-normal leaves it empty, got 'tile'"}},
  };
  for (const auto& [good, c] : cases) {
    const std::string path = dir.file("bad.csv");
    std::ofstream(path, std::ios::binary | std::ios::trunc) << c.mutate(good);
    EXPECT_EQ(errorOf([&] { readSession(path); }), path + c.expected) << c.name;
  }
  EXPECT_EQ(errorOf([&] { readSession(dir.file("missing.csv")); }).rfind(dir.file("missing.csv") +
                                                                          ": cannot open the session file", 0),
            0u);
}

TEST(SessionCsv, TheWriterRefusesWhatTheReaderWould) {
  test::TempDir dir("study_csv");
  SessionHeader h = fixtures::header(Study::Identification, "P,1", 1);
  const std::string path = dir.file("w.csv");
  EXPECT_EQ(errorOf([&] { SessionWriter w(path, h); }),
            path + ": header: field 'participant': expected letters, digits or _-.+, got 'P,1'");
  h.participant = "P1";
  SessionWriter w(path, h);
  TrialRow bad = fixtures::idTrial(1, "bricks_a", "", "wood_a", 3);
  bad.correct = true;
  EXPECT_EQ(errorOf([&] { w.append(bad); }),
            path + ":9: field 'correct': 1 contradicts answer 'wood_a' for surface 'bricks_a'");
  w.append(fixtures::idTrial(1, "bricks_a", "", "bricks_a", 3));
  EXPECT_EQ(readSession(path).trials.size(), 1u);
}

TEST(SessionCsv, SoftwareVersionFitsTheHeader) {
  const std::string v = softwareVersion();
  EXPECT_EQ(v.rfind("texhaptics ", 0), 0u) << v;
  EXPECT_TRUE(isHeaderValue(v)) << v;
}

TEST(SessionCsv, CueConditionNames) {
  EXPECT_EQ(cueCondition({}), "all cues");
  EXPECT_EQ(cueCondition({false, true, true}), "no sound");
  EXPECT_EQ(cueCondition({true, false, true}), "no ball");
  EXPECT_EQ(cueCondition({true, true, false}), "no pen");
  EXPECT_EQ(cueCondition({false, true, false}), "no sound+pen");
}

}  // namespace
}  // namespace thx::study::test_session_csv
