// study-run's real session beside a real-time hapticd (label slow, serial): the documented
// command of docs/study.md §7 with the staged folder, the simulated PHANToM's scene script
// tapping and holding its button (down while the hand pushes), the ratings piped on stdin. Only
// what does not depend on the scheduler is asserted: the session ends, its six rows are valid,
// the cue schedule holds and the scene variants (.nopen, .noball, .nosound) were accepted. Which look each hold confirms
// depends on timing and is not checked.
#include <gtest/gtest.h>

#include <fstream>
#include <set>

#include "clients/study/scene_stage.hpp"
#include "clients/study/session_csv.hpp"
#include "tests/support/hapticd_harness.hpp"

namespace thx::test::test_study_run_live {
namespace {

struct StudyRunLive : HapticdProcessTest {};

TEST_F(StudyRunLive, Study1BesideHapticd) {
  if (!udpmAvailable()) GTEST_SKIP() << "no multicast route for " << url_;
  const std::string manifest = std::string(THX_TEST_DATA_DIR) + "/study/identification/manifest.yaml";
  const std::string stage = path("stage");
  study::stageScenes(study::loadManifest(manifest), stage);
  // The training scene's hand: every 4.5 s a tap (NEXT), then a hold (CONFIRM); twelve, where
  // seven are needed (one may fall in a scene switch).
  std::string script = "device:\n  script:\n    - hold: {duration: 2.0}\n";
  for (int i = 0; i < 12; ++i)
    script += "    - press: {position: [0.0, 0.0], force: 1.0, duration: 0.1}\n    - hold: {duration: 0.5}\n"
              "    - press: {position: [0.0, 0.0], force: 1.0, duration: 1.2}\n    - hold: {duration: 1.5}\n";
  std::string training = slurp(stage + "/training.yaml");
  const auto at = training.find("device:\n");
  ASSERT_NE(at, std::string::npos);
  training.replace(at, 8, script);
  std::ofstream(stage + "/training.yaml") << training;
  std::ofstream answers(path("answers.txt"));
  for (int i = 0; i < 200; ++i) answers << "5\n";
  answers.close();

  startServer({"--scene", stage + "/training.yaml", "--scenes-dir", stage});
  const std::string out = path("P01.csv");
  const std::string cmd = "timeout 180 '" + std::string(THX_STUDY_RUN) + "' --manifest '" + manifest +
                          "' --participant P01 --seed 7 --out '" + out + "' --lcm-url '" + url_ + "' <'" +
                          path("answers.txt") + "' >'" + path("run.out") + "' 2>'" + path("run.err") + "'";
  ASSERT_EQ(shellStatus(cmd), 0) << slurp(path("run.err")) << slurp(path("run.out"));
  const study::Session s = study::readSession(out);
  ASSERT_EQ(s.trials.size(), 6u);
  std::set<std::string> removed;
  for (const study::TrialRow& t : s.trials) {
    EXPECT_EQ(t.representation, study::Representation::Relief);
    if (t.trial > 3) removed.insert(study::cueCondition(t.cues));
  }
  EXPECT_EQ(removed, (std::set<std::string>{"no sound", "no ball", "no pen"}));
  const std::string log = slurp(path("run.out"));
  // The sound is removed by the NAME.nosound switch, not by the operator; the looks still are.
  EXPECT_EQ(log.find("remove the sound"), std::string::npos) << log;
  EXPECT_NE(log.find("OPERATOR (not automated, docs/study.md §8): show candidate look"), std::string::npos) << log;
  bool recorded = false;
  for (const auto& [key, value] : s.header.extra)
    if (key == "operator_steps") recorded = value == "candidate looks by hand: docs/study.md section 8";
  EXPECT_TRUE(recorded);
  EXPECT_NE(log.find("6 trials written"), std::string::npos) << log;
  stopServer();
}

}  // namespace
}  // namespace thx::test::test_study_run_live
