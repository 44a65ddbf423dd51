#pragma once
// What each cue of a trial carries, measured on the running parts (docs/study.md §6.1): the
// features a simulated participant perceives and compares with what each candidate look leads
// it to expect. Every feature is read off what a component produces, lock-step and in-process:
//  - sound: the audio client's synthesis struck once (sound_percept.hpp): the RMS frequency
//    (pitch) and the early decay time (ring) of the samples;
//  - ball: the physics client's Bullet simulation of the scene's ball (ball_percept.hpp): how
//    much the texture shakes it and how much it slips;
//  - pen: the force hapticd's servo actually renders while the simulated hand strokes the
//    surface (server/servo_rig.hpp on the simulated PHANToM, lock-step): log10 of the RMS of the
//    lateral force over the mean normal force, and the normal force's RMS variation over its mean.
// A cue that is removed carries nothing, because nothing reaches the participant, not because a
// flag says so: the NAME.nosound scene is muted (no samples), NAME.noball has no ball to watch,
// NAME.nopen is rendered with zero stiffness (no force to feel). measureSurface given the pen
// off renders it with zero stiffness too; given the sound or the ball off, it leaves their
// features out without hearing or watching.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "clients/study/session.hpp"
#include "device/hand_script.hpp"

namespace thx::study {

inline constexpr int kFeatureCount = 6;
enum Feature : int { kSoundPitch, kSoundRing, kBallShake, kBallSlip, kPenLateral, kPenNormalVar };

// The perceptual resolution (just-noticeable difference) of each feature, in its own units: a
// difference of one JND is what noise of one standard deviation blurs. Our model's choice: pitch
// 0.02 in log10 (5 %), ring 0.1 (26 %), the other log features 0.08 (a Weber fraction of 20 %),
// the ball's slip fraction 0.05, the force variation 0.03.
inline constexpr std::array<double, kFeatureCount> kFeatureJnd{0.02, 0.1, 0.08, 0.05, 0.08, 0.03};

// The cue each feature belongs to.
enum class Cue { Sound, Ball, Pen };
Cue cueOf(int feature);
bool cueOn(const Cues& cues, Cue cue);

struct Percept {
  std::array<std::optional<double>, kFeatureCount> features{};  // empty: not carried
  Representation representation = Representation::Normal;       // of the scene's surface
  double explore_s = 0.0;  // simulated time the hand spent stroking
};

// The hand's exploration of a surface: a hold (the safety stage's engage ramp), then one diagonal
// stroke over half the surface at 0.08 m/s, pushing with force_n. `extent_m` the surface's
// smaller side.
dev::HandScript explorationScript(double extent_m, double force_n = 1.0);

// Measures a scene's cues as `cues` leaves them on. Loads the scene from `scene_path`; hears its
// synthesis unless the sound is off or the scene muted; watches its ball unless the ball is off
// or there is none; prepares it as hapticd does (server/prepared_scene.hpp; the pen removed =
// stiffness fraction 0) and runs the simulated PHANToM with the exploration script through the
// servo rig. Throws thx::Error naming the scene file.
Percept measureSurface(const std::string& scene_path, const Cues& cues);

// The percept of a trial under `cues` from the same scene's percept with every cue on: the sound
// and ball features dropped where removed. Equal to measureSurface(scene, cues) whenever the pen
// is on (the sound and the ball do not depend on the pen: the exploration never touches the
// ball); a trial without the pen needs its own measurement, since the force the servo renders is
// what changes.
Percept withoutSoundOrBall(Percept all, const Cues& cues);

// The result of a scripted answer: simulated time from the answer phase's start to the
// CONFIRM, and how many NEXT events the button protocol decoded before it.
struct ButtonRun {
  std::optional<double> confirm_s;
  int nexts = 0;
};
// Presses the simulated PHANToM's button (bit 0 while the hand pushes) `nexts` times briefly,
// then holds it, through the servo rig on `scene_path`, and decodes the ticks' buttons with the
// ButtonProtocol, as a real session decodes hapticd's device_state_t.
ButtonRun pressButton(const std::string& scene_path, const Cues& cues, int nexts);

}  // namespace thx::study
