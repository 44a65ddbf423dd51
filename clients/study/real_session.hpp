#pragma once
// A session with a person at the device (docs/study.md §7): hapticd and the clients run on the
// staged folder (scene_stage.hpp); the runner switches the scene for each trial
// (ClientApp::loadScene; NAME.nopen without the pen's force, NAME.noball without the ball,
// NAME.nosound with the audio client silent), decodes the device button from hapticd's
// device_state_t stream (button_protocol.hpp) and asks the ratings on the terminal
// (rating_prompt.hpp). Each row is flushed as its trial ends.
//
// Not automated, and said on the terminal as an OPERATOR step that must be confirmed with Enter
// (recorded in the session header): without --visual-client, showing the candidate look the
// participant is on (the visual client draws hapticd's scene, which is the trial's surface: in Study 1 it must
// not be on the participant's screen).
#include <cstdint>
#include <string>

#include "clients/study/session.hpp"
#include "clients/study/study_manifest.hpp"

namespace thx::study {

struct RealSessionOptions {
  std::string participant;
  std::uint64_t seed = 0;
  std::string out_csv;
  std::string lcm_url;         // "" = LCM's default
  double long_press_s = 0.8;   // ButtonProtocolConfig::long_press_s
  std::string visual_client;   // Study 1: show the candidate looks with it (look_window.hpp); "" = operator
};

Session runRealSession(const StudyManifest& manifest, const RealSessionOptions& options);

}  // namespace thx::study
