#pragma once
// The ball cue as a simulated participant sees it: the scene's first dynamic object, run by the
// physics client's own simulation (clients/physics_client/physics_scene.hpp: Bullet on the
// scene's textured plane, lock-step, no pen) for a second, and two things read off its motion
// (docs/study.md §6.1):
//  - shake: log10 of the RMS of its acceleration about the mean acceleration, over g: how much
//    the texture kicks it about as it rolls;
//  - slip: the mean over its contact steps of |slip velocity| / |velocity|: how much it slides
//    rather than rolls, where friction shows.
// A scene without a dynamic object (Study 1's NAME.noball) has no ball to watch: no features.
#include <optional>

#include "scenes/scene.hpp"

namespace thx::study {

struct BallPercept {
  double shake_log10 = 0.0;
  double slip = 0.0;
  double watched_s = 0.0;  // simulated time the ball was watched
};

inline constexpr double kBallWatchS = 1.0;

// Throws thx::Error (scene or texture errors) naming the scene.
std::optional<BallPercept> watchBall(const scene::Scene& scene);

}  // namespace thx::study
