// bench_report (tools/report/bench_report.cpp) run as a process on the small results files in
// tests/data/report/: every section, its picture and machine line, the picks the readings compute
// from the fixture's numbers, a missing file marked "not measured", a malformed one refused naming
// the file and the field.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"

namespace test_bench_report {

namespace {

namespace fs = std::filesystem;
using thx::test::slurp;
using thx::test::TempDir;

const fs::path kFixtures = fs::path(THX_TEST_DATA_DIR) / "report";

struct ReportRun {
  int status = -1;
  std::string out, err, report;
};

// bench_report with `args` in `dir`, the report written to dir/report.md.
ReportRun runReport(const TempDir& dir, const fs::path& results, std::vector<std::string> args = {}) {
  std::vector<std::string> argv = {THX_BENCH_REPORT, "--results", results.string(), "--out", dir.file("report.md")};
  argv.insert(argv.end(), args.begin(), args.end());
  ReportRun r;
  const pid_t pid = thx::test::spawnIn(dir.path().string(), argv, dir.file("stdout"), dir.file("stderr"));
  r.status = thx::test::waitExit(pid);
  r.out = slurp(dir.file("stdout"));
  r.err = slurp(dir.file("stderr"));
  r.report = slurp(dir.file("report.md"));
  return r;
}

// The fixtures copied into dir/results, for tests that spoil one of them.
fs::path copyFixtures(const TempDir& dir) {
  const fs::path results = dir.path() / "results";
  fs::create_directories(results);
  for (const auto& e : fs::directory_iterator(kFixtures)) fs::copy_file(e.path(), results / e.path().filename());
  return results;
}

// The text of the section whose heading starts "## N.", up to the next heading.
std::string section(const std::string& report, int n) {
  const std::string head = "## " + std::to_string(n) + ". ";
  const std::size_t from = report.find(head);
  if (from == std::string::npos) return "";
  const std::size_t to = report.find("\n## ", from + head.size());
  return report.substr(from, to == std::string::npos ? std::string::npos : to - from);
}

// Replaces the first `from` in a file by `to`; fails the test when it is not there.
void spoil(const fs::path& file, const std::string& from, const std::string& to) {
  std::string text = slurp(file);
  const std::size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from << " not in " << file;
  text.replace(at, from.size(), to);
  std::ofstream(file) << text;
}

TEST(BenchReport, WritesEverySectionWithPictureMachineLineAndCommand) {
  TempDir dir("bench_report");
  const ReportRun r = runReport(dir, kFixtures);
  ASSERT_EQ(r.status, 0) << r.err;
  const struct {
    int n;
    const char* title;
    const char* picture;
    const char* command;
    const char* stamp;
    const char* build;
  } expected[] = {
      {1, "Haptics", "haptics.png", "benchmarks/run.sh BUILD force_error", "measured 2030-01-02T03:04:05Z", "not recorded"},
      {2, "Physics", "physics.png", "benchmarks/run.sh BUILD physics", "measured 2030-01-02T03:04:06Z", "not recorded"},
      {3, "Visual", "visual.png", "benchmarks/run.sh BUILD visual", "renderer Fixture GL 1.0", "not recorded"},
      {4, "Modal analysis", "modal.png", "benchmarks/run.sh BUILD audio", "load average 0.10 0.20 0.30", "not recorded"},
      {5, "Modal synthesis", "synthesis.png", "benchmarks/run.sh BUILD audio", "machine Fixture CPU, 2 CPUs, Linux 9.9",
       "RelWithDebInfo"},
  };
  for (const auto& e : expected) {
    const std::string s = section(r.report, e.n);
    ASSERT_FALSE(s.empty()) << "no section " << e.n << " in\n" << r.report;
    EXPECT_NE(s.find(e.title), std::string::npos) << s;
    EXPECT_NE(s.find("](report/" + std::string(e.picture) + ")"), std::string::npos) << s;
    EXPECT_GT(fs::file_size(dir.path() / "report" / e.picture), 1000u) << e.picture;
    EXPECT_NE(s.find("**Regenerate:** `" + std::string(e.command) + "`"), std::string::npos) << s;
    EXPECT_NE(s.find("**Machine:**"), std::string::npos) << s;
    EXPECT_NE(s.find(e.stamp), std::string::npos) << s;
    EXPECT_NE(s.find("build type " + std::string(e.build)), std::string::npos) << s;
    EXPECT_NE(s.find("|---|"), std::string::npos) << "no table in " << s;
    EXPECT_NE(s.find("**Reading (computed from the table):**"), std::string::npos) << s;
  }
  // The fixture's physics file carries the machine's own load average; the haptics file's machine string too.
  EXPECT_NE(section(r.report, 1).find("machine Fixture CPU, 2 CPUs; load average at start 0.50 0.40 0.30"),
            std::string::npos);
  // Tables hold the fixture's numbers.
  EXPECT_NE(section(r.report, 1).find("| sine | bilinear+crease | 2.8 %, 400 | 0.3 %, 420 |"), std::string::npos)
      << section(r.report, 1);
  EXPECT_NE(section(r.report, 3).find("| relief max-mipmap | 30 | 0.001 % | 0.001 |"), std::string::npos)
      << section(r.report, 3);
}

TEST(BenchReport, ReadingsPickFromTheFixtureData) {
  TempDir dir("bench_report");
  const ReportRun r = runReport(dir, kFixtures);
  ASSERT_EQ(r.status, 0) << r.err;
  // Haptics: bilinear 512² is the most accurate under 250 ns (3.5 % at 200 ns beats 4 % at 190 ns);
  // with a microsecond, crease handling at 512²; under 1 % on the valleys, the cheaper 256².
  const std::string h = section(r.report, 1);
  EXPECT_NE(h.find("On `sine`, within 250 ns the most accurate is bilinear 512² (3.5 % at 200 ns)"), std::string::npos) << h;
  EXPECT_NE(h.find("within 1,000 ns the most accurate is bilinear+crease 512² (0.3 % at 420 ns)"), std::string::npos) << h;
  EXPECT_NE(h.find("the cheapest under 1 % error is bilinear+crease 256² (0.002 %, 380 ns)"), std::string::npos) << h;
  EXPECT_NE(h.find("at most 420 ns per tick"), std::string::npos) << h;
  // Physics: the plain plane (0.001 %) is the baseline, never the pick; the relief within 5 µs, the
  // heightfield (0.1 %) within 50 µs; the normal map's worst case is its escape (5 %), the null
  // "sink" case is left out.
  const std::string p = section(r.report, 2);
  EXPECT_NE(p.find("For the sphere, within 5 µs per step the most accurate ground is relief map 64² (0.5 % worst error, 3 µs)"),
            std::string::npos) << p;
  EXPECT_NE(p.find("within 50 µs per step the most accurate ground is heightfield 64² (0.1 % worst error, 40 µs)"),
            std::string::npos) << p;
  EXPECT_NE(p.find("| normal map 64² | 1.2 | 5 % | – | – |"), std::string::npos) << p;
  EXPECT_EQ(p.find("ground is plain plane"), std::string::npos) << p;
  // Visual: at 60 Hz the linear search (2 %), at 30 Hz the max-mipmap walk (0.001 %).
  const std::string v = section(r.report, 3);
  EXPECT_NE(v.find("within 16.7 ms per frame (60 Hz) the most accurate is relief linear 8 + binary 4 at 2 % mis-texels"),
            std::string::npos) << v;
  EXPECT_NE(v.find("within 33.3 ms per frame (30 Hz) the most accurate is relief max-mipmap at 0.001 % mis-texels"),
            std::string::npos) << v;
  // Modal analysis: Tet4 within 0.1 s, Tet10 size 1 within 1 s and the cheapest under 1 %.
  const std::string m = section(r.report, 4);
  EXPECT_NE(m.find("within 0.1 s the most accurate is Tet4 size 2 (2,745 DOF) at 10 % (0.05 s)"), std::string::npos) << m;
  EXPECT_NE(m.find("within 1 s the most accurate is Tet10 size 1 (2,745 DOF) at 0.5 % (0.5 s)"), std::string::npos) << m;
  // Synthesis: float avx2 is the fastest (2× double); 200,000 / 30 and / 10 modes give the sounds per core.
  const std::string s = section(r.report, 5);
  EXPECT_NE(s.find("The fastest full path is float avx2 at 200,000 modes per core (2× the other precision"),
            std::string::npos) << s;
  EXPECT_NE(s.find("within 0.1 dB the fewest modes is truncate to 30 (30 modes), 6,667 sounds per core"), std::string::npos) << s;
  EXPECT_NE(s.find("within 1 dB the fewest modes is truncate to 10 (10 modes), 20,000 sounds per core"), std::string::npos) << s;
}

TEST(BenchReport, MissingResultsFileMarksItsSectionNotMeasured) {
  TempDir dir("bench_report");
  const fs::path results = copyFixtures(dir);
  fs::remove(results / "bench_visual.json");
  const ReportRun r = runReport(dir, results);
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string v = section(r.report, 3);
  EXPECT_NE(v.find("**Not measured.** `" + (results / "bench_visual.json").string() + "` does not exist"),
            std::string::npos) << v;
  EXPECT_EQ(v.find("|---"), std::string::npos) << "a table for a file that is not there:\n" << v;
  EXPECT_FALSE(fs::exists(dir.path() / "report" / "visual.png"));
  EXPECT_NE(r.report.find("- [3. Visual: image error against frame time](#3-visual-image-error-against-frame-time) (not measured)"), std::string::npos);
  EXPECT_NE(section(r.report, 2).find("**Reading"), std::string::npos) << "the other sections are still there";
}

TEST(BenchReport, MalformedFileIsRefusedNamingFileAndField) {
  const struct {
    const char* file;
    const char* from;
    const char* to;
    const char* message;
  } cases[] = {
      {"bench_visual.json", "\"median_ms\": 15.0", "\"median_ms\": \"fast\"",
       "rows[1].median_ms: expected a number, got \"fast\""},
      {"bench_force_error.json", "\"rel_rms\": 0.040, ", "",
       "results[0].rel_rms: expected a number, got nothing (the field is missing)"},
      {"bench_physics.json", "\"timing\": [", "\"timings\": [",
       "timing: expected an array, got nothing (the field is missing)"},
      {"bench_audio_fem.json", "\"element\": \"Tet10\", \"size\": \"1\"", "\"element\": 10, \"size\": \"1\"",
       "cases[1].element: expected a string, got 10"},
      {"bench_audio_synth.json", "\"compression\": [", "\"compression\": [,", "not valid JSON"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.message);
    TempDir dir("bench_report");
    const fs::path results = copyFixtures(dir);
    spoil(results / c.file, c.from, c.to);
    const ReportRun r = runReport(dir, results);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find((results / c.file).string() + ": " + c.message), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir.file("report.md"))) << "a report written from a malformed file";
  }
}

TEST(BenchReport, HelpAndUsageErrors) {
  TempDir dir("bench_report");
  ReportRun r = runReport(dir, kFixtures, {"--help"});
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("Usage: bench_report"), std::string::npos) << r.out;
  r = runReport(dir, kFixtures, {"--colour"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("unknown option '--colour'"), std::string::npos) << r.err;
  r = runReport(dir, dir.path() / "nowhere");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("nowhere: expected a folder of results files"), std::string::npos) << r.err;
}

}  // namespace

}  // namespace test_bench_report
