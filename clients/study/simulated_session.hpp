#pragma once
// One whole session run by a simulated participant (docs/study.md §6): the trial plan from the
// seed, each trial's cues measured on the servo rig lock-step (surface_percept.hpp), the answer
// from the participant model, the button presses through the simulated PHANToM and the button
// protocol, one row appended to the session CSV per trial (SessionWriter flushes each).
#include <cstdint>
#include <string>

#include "clients/study/session.hpp"
#include "clients/study/study_manifest.hpp"

namespace thx::study {

struct SimulatedSessionOptions {
  std::string participant = "S01";
  std::uint64_t seed = 1;    // draws the trials; the participant's noise uses a seed derived from it
  double noise_jnd = 1.0;    // perceptual noise, in JNDs (participant_model.hpp)
  std::string out_csv;       // the session file written
};

// Returns the session as written. Throws thx::Error (a scene that does not load, a press the
// protocol did not decode as planned, a file that cannot be written).
Session runSimulatedSession(const StudyManifest& manifest, const SimulatedSessionOptions& options);

}  // namespace thx::study
