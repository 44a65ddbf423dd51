#pragma once
// Shared by the physics-sound and live tests: the marble scene with its marble made a 10 cm steel
// ball (audible modes) on a small slab, the ball's pose, an impact, a texel path; two audible
// balls apart from the surface and their poses.
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <thx_msgs/physics_contacts_t.hpp>
#include <thx_msgs/physics_impact_t.hpp>
#include <thx_msgs/physics_poses_t.hpp>

#include "clients/audio/offline/physics_sound.hpp"
#include "clients/audio/synthesis/sounding_scene.hpp"
#include "scenes/scene_loader.hpp"

namespace thx::audio::test {

using thx_msgs::physics_contacts_t;
using thx_msgs::physics_impact_t;

// The marble scene with the marble made a 10 cm steel ball, so that it has audible modes
// (T2 about 12.5 kHz, docs/audio.md §8.3), on a small slab.
inline const SoundingScene& testScene() {
  static const SoundingScene s = [] {
    thx::scene::Scene scene = thx::scene::loadScene(std::string(THX_SOURCE_DIR) + "/scenes/marble_rolling_bricks.yaml");
    auto& ball = scene.objects.at(0);
    ball.radius_m = 0.1;
    ball.material = *thx::scene::findMaterial("steel");
    ball.mass_kg = ball.material.density_kg_per_m3 * 4.0 / 3.0 * std::numbers::pi * 1e-3;
    BodyOptions o;
    o.slab_cells = 4;
    o.slab_layers = 1;  // small and fast in the sanitizer tree
    o.object_order = ElementOrder::Linear;
    o.modal.elastic_modes = 16;
    return soundingScene("marble_rolling_bricks", scene, false, o);
  }();
  return s;
}

inline thx_msgs::physics_poses_t ballPose(std::int64_t utime) {
  thx_msgs::physics_poses_t p{};
  p.utime = utime;
  p.num_bodies = 1;
  p.p_world[0][2] = 0.1;
  p.q_world[0][0] = 1.0;
  return p;
}

inline physics_impact_t impact(std::int64_t utime, double v) {
  physics_impact_t m{};
  m.utime = utime;
  m.body_a = 0;
  m.body_b = physics_impact_t::BODY_SURFACE;
  m.impulse = 1e-3;
  m.v_approach = v;
  m.p_world[0] = 0.013;
  m.p_world[1] = -0.021;
  m.n_world[2] = 1.0;
  return m;
}

// A contacts message: the ball on the surface at (0.02, 0, 0), its texel path with these normals
// (columns first_i, first_i + 1, ... of row 0) entered evenly over the last millisecond at 0.3 m/s.
inline physics_contacts_t pathMessage(std::int64_t utime, double sim_time, const std::vector<Eigen::Vector3d>& normals, int first_i) {
  physics_contacts_t m{};
  m.utime = utime;
  m.sim_time = sim_time;
  m.window = 1e-3;
  m.n_geometric_world[2] = 1.0;
  m.num_contacts = 1;
  m.body_a[0] = 0;
  m.body_b[0] = physics_contacts_t::BODY_SURFACE;
  m.mass_a[0] = 0.1;
  m.p_world[0][0] = 0.02;
  m.path_start[0] = 0;
  m.num_texels[0] = int(normals.size());
  m.num_path = int(normals.size());
  for (std::size_t k = 0; k < normals.size(); ++k) {
    thx_msgs::physics_texel_t t{};
    t.i = first_i + int(k);
    t.t = sim_time - 1e-3 + 1e-3 * double(k + 1) / double(normals.size());
    for (int a = 0; a < 3; ++a) t.n_world[a] = normals[k][a];
    t.v_world[0] = 0.3;
    m.path.push_back(t);
  }
  return m;
}

// Two audible balls floating apart from the surface: a steel ball of 10 cm (body 0, at the origin)
// and one of 13 cm (body 1, on +x), so their loudest modes lie apart (Tet4, 16 modes each; audible:
// 13.6-14.9 kHz and 10.5-14.7 kHz; a sphere's frequencies go as 1/r).
inline const SoundingScene& twoBalls() {
  static const SoundingScene s = [] {
    thx::scene::Scene scene = testScene().scene;
    thx::scene::SceneObject big = scene.objects.at(0);
    big.name = "big";
    big.radius_m = 0.13;
    big.mass_kg = big.material.density_kg_per_m3 * 4.0 / 3.0 * std::numbers::pi * std::pow(0.13, 3);
    scene.objects.push_back(big);
    BodyOptions o;
    o.object_order = ElementOrder::Linear;
    o.modal.elastic_modes = 16;
    return soundingScene("two_balls", scene, false, o, testScene().surface);
  }();
  return s;
}

constexpr double kGap = 0.23;  // between the centres: the balls touch at x = 0.1

inline thx_msgs::physics_poses_t twoBallPoses() {
  thx_msgs::physics_poses_t p{};
  p.num_bodies = 2;
  for (int b = 0; b < 2; ++b) {
    p.p_world[b][2] = 0.3;
    p.q_world[b][0] = 1.0;
  }
  p.p_world[1][0] = kGap;
  return p;
}

// A contacts report of the two balls touching at (0.1, 0, 0.3), n from ball 1 to ball 0 (-x),
// over the millisecond before `utime`: ball 0's contact point slips at `slip` relative to ball 1's,
// its centre moves at `v_a`, the normal force is `f_normal`.
inline physics_contacts_t rubMessage(std::int64_t utime, const Eigen::Vector3d& slip, const Eigen::Vector3d& v_a,
                                     double f_normal) {
  physics_contacts_t m{};
  m.utime = utime;
  m.sim_time = double(utime) * 1e-6;
  m.window = 1e-3;
  m.n_geometric_world[2] = 1.0;
  m.num_contacts = 1;
  m.body_a[0] = 0;
  m.body_b[0] = 1;
  m.mass_a[0] = twoBalls().scene.objects.at(0).mass_kg;
  m.p_world[0][0] = 0.1;
  m.p_world[0][2] = 0.3;
  m.n_world[0][0] = -1.0;
  for (int a = 0; a < 3; ++a) {
    m.v_slip_world[0][a] = slip[a];
    m.v_world[0][a] = v_a[a];
  }
  m.f_normal[0] = f_normal;
  return m;
}

}  // namespace thx::audio::test
