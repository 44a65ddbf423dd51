// study-run end to end (docs/study.md §6): simulated participants run both studies on the test
// manifests (the servo rig lock-step, no real-time process, nothing timed), the session files read
// back valid, Study 1 has its cue schedule and Study 2 its split, and study-analyze makes the
// tables from them. Also the program's usage and errors. Under the label slow, also on the
// shipped manifests (scenes/study/).
#include <gtest/gtest.h>

#include <set>

#include "clients/study/session_csv.hpp"
#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"

namespace thx::study::test_study_run_e2e {
namespace {

const std::string kData = THX_TEST_DATA_DIR "/study";

struct CliRun {
  int status;
  std::string out, err;
};

CliRun run(const test::TempDir& dir, const char* program, std::vector<std::string> args) {
  args.insert(args.begin(), program);
  const pid_t pid = test::spawnIn(dir.path().string(), args, dir.file("stdout.txt"), dir.file("stderr.txt"));
  const int status = test::reap(pid, 120);
  return {status, test::slurp(dir.file("stdout.txt")), test::slurp(dir.file("stderr.txt"))};
}

bool has(const std::string& text, const std::string& s) { return text.find(s) != std::string::npos; }

// The manifests a run uses and what their sessions must show.
struct Manifests {
  std::string identification, relief_vs_normal;
  Representation study1_representation;  // every Study 1 surface's
  std::size_t study2_surfaces;           // half of them shown as relief maps
};
const Manifests kTestManifests{kData + "/identification/manifest.yaml", kData + "/relief_vs_normal/manifest.yaml",
                               Representation::Relief, 4};

// `participants` simulated participants through both studies, their sessions checked, then
// study-analyze on them. With `rerun`, one session is run again and must come out byte for byte.
void bothStudies(int participants, bool rerun, const Manifests& m = kTestManifests) {
  test::TempDir dir("study_run");
  std::vector<std::string> files;
  for (int p = 1; p <= participants; ++p) {
    for (const char* study : {"identification", "relief_vs_normal"}) {
      const std::string id = "S0" + std::to_string(p);
      const std::string out = dir.file(id + "_" + study + ".csv");
      const std::string& manifest = std::string(study) == "identification" ? m.identification : m.relief_vs_normal;
      const CliRun r = run(dir, THX_STUDY_RUN,
                        {"--simulate", "--manifest", manifest, "--participant", id,
                         "--seed", std::to_string(100 + p), "--out", out});
      ASSERT_EQ(r.status, 0) << r.err;
      EXPECT_TRUE(has(r.out, "trials written to " + out)) << r.out;
      files.push_back(out);
    }
  }
  for (const std::string& f : files) {
    const Session s = readSession(f);  // every row valid, or this throws naming the line
    EXPECT_EQ(s.header.software, softwareVersion());
    if (s.header.study == Study::Identification) {
      ASSERT_EQ(s.trials.size(), 6u) << f;
      std::set<std::string> removed;
      for (const TrialRow& t : s.trials) {
        if (t.trial <= 3) {
          EXPECT_EQ(t.cues, Cues{}) << f << " trial " << t.trial;
        } else {
          EXPECT_NE(t.cues, Cues{});
          removed.insert(cueCondition(t.cues));
        }
        ASSERT_TRUE(t.time_s);
        EXPECT_GT(*t.time_s, 0.0);
        EXPECT_EQ(t.representation, m.study1_representation);
        EXPECT_TRUE(t.rating(Rating::Ease));
        EXPECT_EQ(t.rating(Rating::UsePen).has_value(), t.cues.pen);  // a removed cue is not rated
      }
      EXPECT_EQ(removed, (std::set<std::string>{"no sound", "no ball", "no pen"})) << f;
    } else {
      ASSERT_EQ(s.trials.size(), m.study2_surfaces) << f;
      std::set<std::string> surfaces;
      std::size_t relief = 0;
      for (const TrialRow& t : s.trials) {
        surfaces.insert(t.surface);  // each once: never both versions of one surface
        relief += t.representation == Representation::Relief;
        EXPECT_TRUE(t.rating(Rating::Overall));
      }
      EXPECT_EQ(surfaces.size(), m.study2_surfaces);
      EXPECT_EQ(relief, m.study2_surfaces / 2) << f;
    }
  }

  if (rerun) {
  // The same seed, the same session, byte for byte.
  const CliRun again = run(dir, THX_STUDY_RUN,
                        {"--simulate", "--manifest", m.identification, "--participant", "S01",
                         "--seed", "101", "--out", dir.file("again.csv")});
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(test::slurp(dir.file("again.csv")), test::slurp(files[0]));
  }

  std::vector<std::string> args = files;
  args.insert(args.end(), {"--out", dir.file("results")});
  const CliRun a = run(dir, THX_STUDY_ANALYZE, args);
  ASSERT_EQ(a.status, 0) << a.err;
  const std::string n = std::to_string(participants);
  EXPECT_TRUE(has(a.out, n + " identification and " + n + " relief-vs-normal sessions")) << a.out;
  const std::string by_cue = test::slurp(dir.file("results/identification_by_cue.csv"));
  const std::vector<std::string> rows{"\nall cues," + std::to_string(3 * participants) + ",", "\nno sound," + n + ",",
                                      "\nno ball," + n + ",", "\nno pen," + n + ","};
  for (const std::string& row : rows) EXPECT_TRUE(has(by_cue, row)) << row << " in\n" << by_cue;
  const std::string paired = test::slurp(dir.file("results/ratings_relief_vs_normal.csv"));
  EXPECT_TRUE(has(paired, "\noverall," + n + ",")) << paired;
  EXPECT_TRUE(has(test::slurp(dir.file("results/study.md")), "identification"));
}

#ifdef THX_STUDY_RUN_E2E_SLOW
// The long version (label slow): three participants per study, and one session run again.
TEST(StudyRunE2eSlow, ThreeParticipantsAndARerun) { bothStudies(3, true); }

// The shipped surfaces (scenes/study/, 512² textures) through the runner: one participant per
// study; Study 1's ten surfaces are normal maps, Study 2 has six surfaces.
TEST(StudyRunE2eSlow, ShippedManifestsOneParticipantEach) {
  const std::string shipped = std::string(THX_SOURCE_DIR) + "/scenes/study/";
  bothStudies(1, false, Manifests{shipped + "identification.yaml", shipped + "relief_vs_normal.yaml", Representation::Normal, 6});
}
#else
// One participant per study: the short version every test run has (this file built without
// THX_STUDY_RUN_E2E_SLOW).
TEST(StudyRunE2e, BothStudiesSimulatedThenAnalysed) { bothStudies(1, false); }

TEST(StudyRunE2e, UsageAndErrors) {
  test::TempDir dir("study_run");
  const CliRun help = run(dir, THX_STUDY_RUN, {"--help"});
  EXPECT_EQ(help.status, 0);
  EXPECT_TRUE(has(help.out, "usage: study-run"));
  const CliRun no_manifest = run(dir, THX_STUDY_RUN, {"--participant", "P1"});
  EXPECT_EQ(no_manifest.status, 2);
  EXPECT_TRUE(has(no_manifest.err, "--manifest: required")) << no_manifest.err;
  const CliRun bad_id = run(dir, THX_STUDY_RUN, {"--manifest", "m.yaml", "--participant", "P 1"});
  EXPECT_EQ(bad_id.status, 2);
  const CliRun missing = run(dir, THX_STUDY_RUN, {"--simulate", "--manifest", dir.file("none.yaml"), "--participant", "P1"});
  EXPECT_EQ(missing.status, 1);
  EXPECT_TRUE(has(missing.err, "none.yaml: cannot read the manifest")) << missing.err;
}
#endif

}  // namespace
}  // namespace thx::study::test_study_run_e2e
