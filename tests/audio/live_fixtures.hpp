#pragma once
// Shared by the live-audio and scrape tests: a small steel slab with its modes, a grooved normal map, a
// straight scrape as hapticd's CONTACT batches, and a fake clock for the callback's cost.
#include <cstdint>
#include <vector>

#include <thx_msgs/contact_batch_t.hpp>

#include "clients/audio/analysis/audible_modes.hpp"
#include "clients/audio/analysis/scene_bodies.hpp"
#include "clients/audio/analysis/tet_mesh.hpp"
#include "clients/audio/synthesis/synth_scene.hpp"
#include "rt/clock.hpp"
#include "tests/audio/modal_fixtures.hpp"
#include "textures/texture_map.hpp"

namespace thx::audio::test {

struct LiveSlab {
  TetMesh mesh = slabMesh("surface", 0.2, 0.2, 0.01, {4, 4, 1}, ElementOrder::Quadratic, false);
  AudibleModes modes;
  LiveSlab() {
    ModalSettings s;
    s.elastic_modes = 10;
    AudibleOptions a;
    a.sample_rate_hz = 48000.0;
    modes = audibleModes(analyse(mesh, steel(), s), steel(), a);
  }
  SoundingBody body() const { return SoundingBody{"surface", modes.frequency_hz, modes.decay_per_s, modes.shapes}; }
};

inline const LiveSlab& liveSlab() {
  static const LiveSlab s;
  return s;
}

// A steel pen, 12 cm x r 5 mm, Tet10 2 x 2 x 6 cells: 3 audible modes, the first bending pair
// at 3126 Hz (Euler-Bernoulli: 3121 Hz).
struct LivePen {
  TetMesh mesh = cylinderMesh("pen", 0.005, 0.12, 2, 6, ElementOrder::Quadratic);
  AudibleModes modes;
  int tip = 0;
  LivePen() {
    ModalSettings s;
    s.elastic_modes = 8;
    modes = audibleModes(analyse(mesh, steel(), s), steel(), AudibleOptions{});
    tip = penTipNode(mesh);
  }
  SoundingBody body() const { return SoundingBody{"pen", modes.frequency_hz, modes.decay_per_s, modes.shapes}; }
};

inline const LivePen& livePen() {
  static const LivePen p;
  return p;
}

// Grooves along v: every other texel column tilted.
inline tex::TextureMap grooveMap() {
  tex::TextureMap map(64, 64, tex::Representation::Normal);
  for (int i = 0; i < 64; i += 2)
    for (int j = 0; j < 64; ++j) map.setNormal(i, j, Eigen::Vector3f(0.2f, 0.0f, 1.0f));
  return map;
}

// The pen at speed m/s along u over a 0.2 m surface from u = 0.3, utime = tick ms, pressing with
// force_n (growing by 1 % a tick, so the micro level's force ramps within each segment).
inline thx_msgs::contact_t penSample(std::int64_t tick, std::int64_t first, double speed, double force_n = 0.0) {
  thx_msgs::contact_t c{};
  c.tick = tick;
  c.utime = tick * 1000;
  c.in_contact = true;
  c.uv[0] = 0.3 + speed / 0.2 * double(tick - first) / 1000.0;
  c.uv[1] = 0.41;
  c.f_normal = force_n * (1.0 + 0.01 * double(tick - first));
  c.n_geom_world[2] = 1.0;
  c.n_sampled_world[2] = 1.0;
  c.v_tangent_world[0] = speed;
  return c;
}

// Ticks [first, first + ticks) in batches of `per_batch`, seq 1, 2, ...
inline std::vector<thx_msgs::contact_batch_t> penBatches(std::int64_t first, int ticks, int per_batch, double speed,
                                                        double force_n = 0.0) {
  std::vector<thx_msgs::contact_batch_t> out;
  for (int k = 0; k < ticks; k += per_batch) {
    thx_msgs::contact_batch_t b{};
    b.seq = std::int64_t(out.size()) + 1;
    b.server_instance = 7;
    for (int t = k; t < std::min(ticks, k + per_batch); ++t) b.samples.push_back(penSample(first + t, first, speed, force_n));
    b.num_samples = std::int32_t(b.samples.size());
    b.next_tick = first + k + b.num_samples;
    b.utime = (b.next_tick - 1) * 1000;
    out.push_back(b);
  }
  return out;
}

// A clock for the callback's cost: each reading advances it by `step_ns`, so a block (two
// readings) costs exactly step_ns; the test sets it before each block.
class SteppingClock final : public rt::Clock {
 public:
  std::int64_t nowNs() override { return now_ += step_ns; }
  void sleepUntilNs(std::int64_t t_ns) override { now_ = std::max(now_, t_ns); }
  std::int64_t step_ns = 0;

 private:
  std::int64_t now_ = 0;
};

}  // namespace thx::audio::test
