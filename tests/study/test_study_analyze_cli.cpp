// study-analyze end to end: synthetic sessions of both studies written by the SessionWriter,
// the real binary run on them, its tables, plots and errors read back.
#include <gtest/gtest.h>

#include <filesystem>

#include "clients/study/session_csv.hpp"
#include "tests/study/study_fixtures.hpp"
#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"
#include "textures/png_io.hpp"

namespace thx::study::test_study_analyze_cli {
namespace {

struct CliRun {
  int status;
  std::string out, err;
};

CliRun analyze(const test::TempDir& dir, std::vector<std::string> args) {
  args.insert(args.begin(), THX_STUDY_ANALYZE);
  const pid_t pid = test::spawnIn(dir.path().string(), args, dir.file("stdout.txt"), dir.file("stderr.txt"));
  const int status = test::reap(pid, 60);
  return {status, test::slurp(dir.file("stdout.txt")), test::slurp(dir.file("stderr.txt"))};
}

bool hasLine(const std::string& text, const std::string& line) {
  return ("\n" + text).find("\n" + line + "\n") != std::string::npos;
}

std::vector<std::string> writeAll(const test::TempDir& dir) {
  std::vector<std::string> files;
  std::vector<Session> all = fixtures::identificationSessions();
  for (Session& s : fixtures::ratingSessions()) all.push_back(s);
  for (const Session& s : all) {
    files.push_back(dir.file(s.source));
    SessionWriter w(files.back(), s.header);
    for (const TrialRow& r : s.trials) w.append(r);
  }
  return files;
}

TEST(StudyAnalyzeCli, BothStudiesToTablesAndPlots) {
  test::TempDir dir("study_cli");
  std::vector<std::string> args = writeAll(dir);
  args.insert(args.end(), {"--out", dir.file("out")});
  const CliRun r = analyze(dir, args);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("2 identification and 4 relief-vs-normal sessions; wrote 11 files"), std::string::npos) << r.out;
  const auto out = [&](const std::string& name) { return test::slurp(dir.file("out/" + name)); };

  // The hand-worked numbers of test_analysis.cpp, as a user reads them.
  EXPECT_TRUE(hasLine(out("identification_by_condition.csv"), "all cues,6,4,0.667,15.00,4.16"));
  // Times 12, 18, 30, 22: mean 20.5, squared deviations 72.25 + 6.25 + 90.25 + 2.25 = 171 over 3.
  EXPECT_TRUE(hasLine(out("identification_by_condition.csv"), "one cue removed,6,4,0.667,20.50,7.55"));
  EXPECT_TRUE(hasLine(out("identification_by_cue.csv"), "no ball,2,1,0.500,12.00,,,,,,,,"));
  EXPECT_TRUE(hasLine(out("identification_by_surface.csv"), "metal_a,metal,2,0,0.000,,"));
  EXPECT_TRUE(hasLine(out("identification_family_confusion.csv"), "metal,1,3,0,4,0.750"));
  EXPECT_TRUE(hasLine(out("ratings_relief_vs_normal.csv"), "overall,3,7.00,1.00,4.67,0.58,7.000,2.00,0.0198,2.858"));
  // wood_1 overall: relief 8, 6 (variance 2), normal 6, 5 (variance 0.5): SE sqrt(2/2 + 0.5/2),
  // t = 1.5 / sqrt(1.25) = 1.342, Welch df = 1.25² / (1² + 0.25²) = 1.47 (p from Boost.Math).
  EXPECT_TRUE(hasLine(out("ratings_by_surface.csv"), "wood_1,overall,2,7.00,2,5.50,1.342,1.47,0.3499"))
      << out("ratings_by_surface.csv");
  const std::string md = out("study.md");
  for (const char* heading : {"### Study 1: identification by condition (Table 2)",
                              "### Study 1: identification by cue removed (Table 3)",
                              "### Study 1: identification by surface (Table 4)",
                              "### Study 2: ratings, relief against normal maps (Table 5)",
                              "![ID rate and time by cue](identification_by_cue.png)",
                              "![ratings by representation](ratings_by_representation.png)"}) {
    EXPECT_NE(md.find(heading), std::string::npos) << heading;
  }
  // The plots are real pictures: sized as drawn, not blank.
  const tex::RawImage id = tex::readPng(dir.file("out/identification_by_cue.png"));
  EXPECT_EQ(id.width, 2 * 560);
  EXPECT_EQ(id.height, 440);
  const tex::RawImage rt = tex::readPng(dir.file("out/ratings_by_representation.png"));
  EXPECT_EQ(rt.width, 760);
  int dark = 0;
  for (std::size_t i = 0; i < rt.samples.size(); i += 3) dark += rt.samples[i] < 128 ? 1 : 0;
  EXPECT_GT(dark, 1000);
}

TEST(StudyAnalyzeCli, OneStudyOnlyWritesItsOwnTables) {
  test::TempDir dir("study_cli");
  const std::vector<std::string> files = writeAll(dir);
  const CliRun r = analyze(dir, {files[0], files[1], "--out", dir.file("s1")});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.file("s1/identification_by_cue.png")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("s1/ratings_relief_vs_normal.csv")));
  EXPECT_EQ(test::slurp(dir.file("s1/study.md")).find("Study 2"), std::string::npos);
}

TEST(StudyAnalyzeCli, ErrorsAreClear) {
  test::TempDir dir("study_cli");
  const std::vector<std::string> files = writeAll(dir);
  CliRun r = analyze(dir, {});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "study-analyze: expected at least one session file\n(study-analyze --help lists the options)\n");
  r = analyze(dir, {"--bins", "3", files[0]});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("unknown option '--bins'"), std::string::npos);
  r = analyze(dir, {files[0], "--out"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--out: expected a folder after it"), std::string::npos);
  r = analyze(dir, {"--help"});
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("usage: study-analyze [--out DIR] SESSION.csv..."), std::string::npos);

  // A damaged session: the message names file, line and field; nothing is written.
  std::string text = test::slurp(files[0]);
  text.replace(text.find("\n3,metal_a,normal,1,1,1,metal_b,0,30,"), 37, "\n3,metal_a,normal,1,1,1,metal_b,0,3O,");
  std::ofstream(dir.file("bad.csv"), std::ios::binary) << text;
  r = analyze(dir, {files[1], dir.file("bad.csv"), "--out", dir.file("never")});
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "study-analyze: " + dir.file("bad.csv") +
                       ":11: field 'time_s': expected seconds (a number) or nothing, got '3O'\n");
  EXPECT_FALSE(std::filesystem::exists(dir.file("never")));
  // The same participant twice in one study: refused before anything is written.
  r = analyze(dir, {files[0], files[0], "--out", dir.file("never")});
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "study-analyze: " + files[0] + ": participant 'P1' already has a session of study identification in " +
                       files[0] + "\n");
  EXPECT_FALSE(std::filesystem::exists(dir.file("never")));
}

}  // namespace
}  // namespace thx::study::test_study_analyze_cli
