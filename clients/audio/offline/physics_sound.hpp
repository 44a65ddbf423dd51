#pragma once
// The physics client's streams made audible, offline and deterministic (docs/audio.md §9–§11):
//   - impacts (physics_impact_t): the impulse on the modes of both bodies at the contact point,
//     spread over a Hertz contact time (contact_pulse.hpp);
//   - lasting contacts on a normal map (physics_contacts_t texel paths): Eq. 5 meso impulses at
//     every texel entered, with the object's mass and the texel's own normal, on the surface and,
//     opposite, on the object;
//   - lasting contacts on a relief map: the change of the object's momentum along the plane's
//     normal between two contact reports, m (v_k - v_{k-1}) . n_g (the relief pushing the body up
//     or catching it, without the static support), on both sides;
//   - lasting contacts between two objects: the micro level's roughness force (the scene's
//     surface.roughness profile) over each report's window, on both objects, opposite.
// The strikes come from PhysicsExcitation (physics_excitation.hpp, the live client's too); they
// are collected per body with their sample times, then every body's resonator bank is rendered
// in one pass: the same streams give the same samples. The scene's sounding bodies they strike
// are built by sounding_scene.hpp (shared with the live client).
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <thx_msgs/physics_contacts_t.hpp>
#include <thx_msgs/physics_impact_t.hpp>
#include <thx_msgs/physics_poses_t.hpp>

#include "clients/audio/synthesis/object_contact.hpp"
#include "clients/audio/synthesis/physics_excitation.hpp"

namespace thx::audio {

// The physics client's events of a log, and the scene hapticd announced (THX_HELLO), in log order.
struct PhysicsStreams {
  std::vector<thx_msgs::physics_poses_t> poses;
  std::vector<thx_msgs::physics_impact_t> impacts;
  std::vector<thx_msgs::physics_contacts_t> contacts;
  struct SceneAnnouncement {
    std::int64_t utime = 0;
    std::string scene_name;
  };
  std::vector<SceneAnnouncement> hellos;
  bool empty() const { return poses.empty() && impacts.empty() && contacts.empty(); }
  // The earliest utime of a physics event (0 when there is none).
  std::int64_t firstUtime() const;
};
// Throws thx_msgs::LogError naming the file and event on an unreadable log or event.
PhysicsStreams readPhysicsStreams(const std::string& log_path);

struct PhysicsSoundOptions {
  double sample_rate_hz = 44100.0;
  double tail_s = 0.5;            // rendered after the last strike
  double min_normal_dot = 0.05;   // Eq. 5's floor of n_g . n_s (meso_impulses.hpp)
  // Lasting contacts between two objects (the micro level, object_contact.hpp); a scene whose
  // surface.roughness amplitude is 0 has none.
  ObjectContactOptions object_contacts;
};

struct PhysicsRender {
  std::vector<double> samples;  // the sum of every body's modal displacements, from the origin
  std::size_t impacts = 0, meso_impulses = 0, relief_impulses = 0;  // excitations applied (non-zero)
  std::size_t strikes = 0;                  // body strikes (an impact strikes up to two bodies)
  std::size_t object_impacts = 0;           // impacts between two objects (of `impacts`)
  std::size_t object_contact_segments = 0; // reports of two objects rubbing that sounded (micro level)
  double min_contact_s = 0, max_contact_s = 0;  // the impacts' Hertz durations
  std::vector<std::string> scenes;          // the scenes that sounded, in order of first use
};

// `scene_for(name)` returns the scene hapticd switched to (called once per name); `first` is the
// scene the log starts in. Events are placed on the utime clock: sample 0 = `origin_utime`.
PhysicsRender renderPhysicsStreams(const PhysicsStreams& streams, const SoundingScene& first,
                                   const std::function<SoundingScene(const std::string&)>& scene_for,
                                   std::int64_t origin_utime, const PhysicsSoundOptions& options);

// One track of a session: `scrape` (normalised samples; times `scrape_scale` gives its modal
// displacements) plus `physics` (modal displacements), both from the same origin, normalised to
// a peak of `peak` (silence stays silence).
std::vector<float> mixSessionSound(std::span<const float> scrape, double scrape_scale, std::span<const double> physics,
                                   double peak);

// The same track at a fixed gain instead (audio-client --gain): (scrape + physics) x gain, both
// the listeners' sums (m^3) from the same origin, not normalised nor clamped, so that renders of
// one session at one gain compare sample for sample (a pen alone against the mix of every pen).
std::vector<float> scaledSessionSound(std::span<const double> scrape, std::span<const double> physics, double gain);

}  // namespace thx::audio
