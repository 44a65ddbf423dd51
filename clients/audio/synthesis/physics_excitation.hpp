#pragma once
// The physics client's streams as strikes on one scene's sounding bodies, message by message
// (docs/audio.md §9–§10): shared by the offline render (physics_sound.hpp) and the live client
// (physics_source.hpp), so both strike the same bodies at the same points with the same impulses.
//   - impacts: J n on body a, -J n on body b, at p_world, with the Hertz contact time
//     (contact_pulse.hpp), at the impact's time + tau/2: the surface, any object (two objects
//     striking each other ring both) and the pen (at its tip);
//   - lasting contacts of an object on a normal map: Eq. 5 at every texel entered (the object
//     +dp, the surface -dp), at the texel's entry time;
//   - on a relief map: the change of the object's normal momentum between two reports;
//   - lasting contacts between two objects: the micro level's roughness force over each report's
//     window (object_contact.hpp), +n on a and -n on b at the contact point (a force segment).
// Each strike is given in its body's frame: the surface slab's (plane-local, wrapped into the
// texture's one span, depth clamped into the slab) or a mesh scene's surface's (the mesh's frame), an object's (from the newest pose at or
// before the event, moved on by its velocities) or the pen's (its tip node).
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <thx_msgs/physics_contacts_t.hpp>
#include <thx_msgs/physics_impact_t.hpp>
#include <thx_msgs/physics_poses_t.hpp>

#include "clients/audio/analysis/modal_body.hpp"
#include "clients/audio/synthesis/object_contact.hpp"
#include "scenes/scene.hpp"
#include "textures/plane_mapping.hpp"

namespace thx::audio {

// One scene's sounding bodies.
struct SoundingScene {
  std::string name;  // the scene file's stem, as hapticd's hello names it
  scene::Scene scene;
  tex::PlaneMapping mapping;
  bool relief = false;     // the surface texture is a relief map (else a normal map)
  double slab_thickness_m = 0.01;
  std::shared_ptr<const ModalBody> surface;
  // A mesh scene: the surface body is the solid its mesh encloses, in the mesh's frame, placed
  // in the world by this (strikes are moved into it, not wrapped into a slab).
  std::optional<Eigen::Isometry3d> surface_mesh_to_world;
  std::vector<std::shared_ptr<const ModalBody>> objects;  // by objects[] index; null for fixed ones
  // The pen's own modes (the scrape's, device.pen; null: the pen is silent here). Impacts with the
  // pen strike it at its tip node, the impulse turned into its frame (axis +z from the tip, tilted
  // from the surface normal about y by pen_tilt_deg, as the scrape strikes it).
  std::shared_ptr<const ModalBody> pen;
  int pen_tip_node = 0;
  double pen_tilt_deg = 30.0;
};

// One strike on one body, in the body's frame.
struct BodyStrike {
  int body = -1;                 // -1: the surface, -2: the pen, else the scene's objects[] index
  const ModalBody* modal = nullptr;
  std::int64_t utime = 0;        // the event's time (µs)
  double delay_s = 0.0;          // after utime: an impact's half contact time
  Eigen::Vector3d point{0, 0, 0};
  Eigen::Vector3d impulse{0, 0, 0};  // N s
  double pulse_s = 0.0;          // the Hertz contact time (0: an ideal impulse)
  // A micro-level force segment instead (a lasting contact between two objects): `impulse` is a
  // unit direction; the force of the roughness profile (microForce, fractal_roughness.hpp) from
  // distance s0 and force f0 at utime to s1, f1 at end_utime, on the samples after utime's up to
  // end_utime's.
  bool micro = false;
  std::int64_t end_utime = 0;
  double s0 = 0.0, s1 = 0.0, f0 = 0.0, f1 = 0.0;
};

// The newest poses message at or before a time (nullptr: none).
using PoseLookup = std::function<const thx_msgs::physics_poses_t*(std::int64_t utime)>;
// Takes a strike; returns whether it sounded.
using StrikeSink = std::function<bool(const BodyStrike&)>;

struct PhysicsExcitationCounts {
  std::size_t impacts = 0, meso_impulses = 0, relief_impulses = 0;  // excitations that sounded
  std::size_t strikes = 0;                                          // body strikes that sounded
  std::size_t object_impacts = 0;                                   // impacts between two objects that sounded
  std::size_t object_contact_segments = 0;  // reports of a lasting contact between two objects that sounded
  double min_contact_s = 0, max_contact_s = 0;                      // the impacts' Hertz times
};

class PhysicsExcitation {
 public:
  // `scene` must outlive this.
  explicit PhysicsExcitation(const SoundingScene& scene, double min_normal_dot = 0.05,
                             ObjectContactOptions object_contacts = {});

  void impact(const thx_msgs::physics_impact_t& m, const PoseLookup& poses, const StrikeSink& sink);
  void contacts(const thx_msgs::physics_contacts_t& m, const PoseLookup& poses, const StrikeSink& sink);
  // Every walk starts anew (a scene switch, lost messages).
  void reset();

  const PhysicsExcitationCounts& counts() const { return counts_; }

 private:
  struct PathState {
    bool has_texel = false;
    int i = 0, j = 0;
    Eigen::Vector3f normal{0, 0, 1};
    bool has_vn = false;
    double vn = 0.0;
  };
  // One strike (its body, times, pulse and micro fields set) at p along J (world frame).
  bool strike(BodyStrike s, const Eigen::Vector3d& p, const Eigen::Vector3d& J, const PoseLookup& poses,
              const StrikeSink& sink) const;
  bool strike(int body, std::int64_t utime, double delay_s, const Eigen::Vector3d& p, const Eigen::Vector3d& J,
              double pulse_s, const PoseLookup& poses, const StrikeSink& sink) const;
  void objectContact(const thx_msgs::physics_contacts_t& m, int k, const PoseLookup& poses, const StrikeSink& sink);
  void strikePair(int object, std::int64_t utime, const Eigen::Vector3d& p, const Eigen::Vector3d& dp,
                  const PoseLookup& poses, const StrikeSink& sink, std::size_t& counter);

  const SoundingScene& scene_;
  double min_normal_dot_;
  std::map<int, PathState> states_;
  // A lasting contact between two objects: where its roughness read is, the force it ended on.
  struct RubState {
    double distance_m = 0.0;
    bool moving = false;  // the previous report made a segment
    double force_n = 0.0;
  };
  std::map<std::pair<int, int>, RubState> rubs_;
  double last_sim_time_;
  ObjectContactOptions object_contacts_;
  PhysicsExcitationCounts counts_;
};

}  // namespace thx::audio
