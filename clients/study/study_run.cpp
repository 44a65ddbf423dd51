// study-run: the user studies' trial runner (docs/study.md §5-§7).
#include <cstdio>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "base/program_main.hpp"
#include "clients/study/real_session.hpp"
#include "clients/study/scene_stage.hpp"
#include "clients/study/simulated_session.hpp"
#include "clients/study/study_manifest.hpp"

namespace {

constexpr const char* kHelp = R"(usage: study-run --manifest FILE --participant ID [--seed N] [--out FILE]
                 [--simulate [--noise JND]] [--lcm-url URL] [--long-press S]
                 [--visual-client PATH]
       study-run --manifest FILE --stage DIR

Runs one participant's session of a user study (docs/study.md) and writes it as a session CSV,
one row per trial, flushed as each trial ends (study-analyze reads it).

The manifest (docs/study.md §5.1) names the study (identification or relief-vs-normal), the
candidate surfaces with their sound families and scene files; the trials are drawn from the
seed, which the session file records.

Stage (--stage DIR): writes the manifest's scenes into DIR, and for Study 1 each surface's
variants NAME.nopen.yaml (no pen force), NAME.noball.yaml (no ball) and NAME.nosound.yaml
(audio.mute: the audio client plays silence), then exits.

Real session (default): hapticd and the clients run on the staged folder, e.g.
  hapticd --scene DIR/TRAINING.yaml --scenes-dir DIR
with physics-client, audio-client (--scenes-dir DIR) beside it (docs/study.md §7). The runner
switches hapticd's scene for each trial (a variant where a cue is removed), reads the device
button from hapticd's device_state_t stream and asks the ratings on this terminal. Study 1's
candidate looks: with --visual-client, a window of visual-client --live --allow-different-scene
per look; without it, an operator step it prints (docs/study.md §8).
Button: short press (< --long-press s) of button 1 = next look / next surface; hold button 1
for --long-press s, or press button 2 = confirm.

Simulated session (--simulate): no processes; each trial's surface is rendered lock-step on
the simulated PHANToM through hapticd's servo rig, and a simulated participant strokes it,
answers from the cues the trial leaves on and presses the simulated button (docs/study.md §6).

options:
  --manifest FILE    the study's manifest (required)
  --participant ID   the participant's id: letters, digits and _-.+ (required)
  --seed N           the seed that draws the trials, a whole number in [0, 2^63); default: a
                     random one (printed, and recorded in the session file)
  --out FILE         the session CSV (default: ID_STUDY.csv)
  --stage DIR        write the staged scene folder and exit
  --simulate         a simulated participant instead of a person
  --noise JND        --simulate: the participant's perceptual noise in JNDs (default 1)
  --lcm-url URL      real session: the LCM bus hapticd publishes on (default LCM's)
  --long-press S     real session: the hold that confirms (default 0.8 s)
  --visual-client P  real session, Study 1: show each candidate look with the program P
                     (e.g. build/clients/visual/visual-client; needs a display)
  --help             this text
exit status: 0 done, 1 an error (bad manifest, a scene hapticd refused, no hapticd...), 2 a
command-line mistake.
)";

std::string need(std::size_t& i, const std::vector<std::string>& args, const std::string& opt) {
  if (i + 1 >= args.size()) throw thx::UsageError(opt + ": expected a value after it");
  return args[++i];
}

}  // namespace

int main(int argc, char** argv) {
  return thx::runProgram("study-run", kHelp, argc, argv, [](const std::vector<std::string>& args) {
    std::string manifest_path, participant, out, lcm_url, stage_dir, visual_client;
    std::optional<std::uint64_t> seed;
    bool simulate = false;
    double noise = 1.0, long_press = 0.8;
    for (std::size_t i = 0; i < args.size(); ++i) {
      const std::string& a = args[i];
      if (a == "--manifest") manifest_path = need(i, args, a);
      else if (a == "--participant") participant = need(i, args, a);
      else if (a == "--seed") seed = std::uint64_t(thx::cli::parseInteger(a, need(i, args, a), 0, std::numeric_limits<long long>::max()));
      else if (a == "--out") out = need(i, args, a);
      else if (a == "--simulate") simulate = true;
      else if (a == "--stage") stage_dir = need(i, args, a);
      else if (a == "--noise") noise = thx::cli::parseNumber(a, need(i, args, a), {0.0, 100.0, false, "JND"});
      else if (a == "--lcm-url") lcm_url = need(i, args, a);
      else if (a == "--visual-client") visual_client = need(i, args, a);
      else if (a == "--long-press") long_press = thx::cli::parseNumber(a, need(i, args, a), {0.1, 10.0, false, "s"});
      else throw thx::UsageError("unknown option '" + a + "'");
    }
    if (manifest_path.empty()) throw thx::UsageError("--manifest: required");
    if (!stage_dir.empty()) {
      const auto files = thx::study::stageScenes(thx::study::loadManifest(manifest_path), stage_dir);
      std::printf("study-run: staged %zu scenes in %s\n", files.size(), stage_dir.c_str());
      return 0;
    }
    if (participant.empty()) throw thx::UsageError("--participant: required");
    if (!thx::study::isToken(participant))
      throw thx::UsageError("--participant: expected letters, digits and _-.+, got '" + participant + "'");
    const thx::study::StudyManifest m = thx::study::loadManifest(manifest_path);
    if (!seed) {
      std::random_device rd;
      seed = ((std::uint64_t(rd()) << 32) | rd()) >> 1;
    }
    if (out.empty()) out = participant + "_" + std::string(thx::study::studyName(m.study)) + ".csv";
    std::fprintf(stderr, "study-run: %s, participant %s, seed %llu, %zu surfaces -> %s\n",
                 std::string(thx::study::studyName(m.study)).c_str(), participant.c_str(),
                 static_cast<unsigned long long>(*seed), m.surfaces.size(), out.c_str());
    thx::study::Session s;
    if (simulate) {
      thx::study::SimulatedSessionOptions o;
      o.participant = participant;
      o.seed = *seed;
      o.noise_jnd = noise;
      o.out_csv = out;
      s = thx::study::runSimulatedSession(m, o);
    } else {
      thx::study::RealSessionOptions o;
      o.participant = participant;
      o.seed = *seed;
      o.out_csv = out;
      o.lcm_url = lcm_url;
      o.long_press_s = long_press;
      o.visual_client = visual_client;
      s = thx::study::runRealSession(m, o);
    }
    int correct = 0;
    for (const auto& r : s.trials) correct += r.correct.value_or(false) ? 1 : 0;
    std::printf("study-run: %zu trials written to %s", s.trials.size(), out.c_str());
    if (m.study == thx::study::Study::Identification) std::printf(" (%d correct)", correct);
    std::printf("\n");
    return 0;
  });
}
