#pragma once
// The pen's scrape, one servo tick at a time: shared by the offline render (scrape_synthesis.hpp)
// and the live client (pen_source.hpp), so both excite the same nodes with the same impulses and
// the same micro force. For two consecutive ticks in contact (a segment):
//  - meso level: on a normal map the tip's texture path is walked (Eq. 5, meso_impulses.hpp) at
//    the velocity of that segment, one impulse per texel entered; on a relief map the change of
//    the contact normal (relief_impulses.hpp), one impulse per tick;
//  - micro level: the segment's travelled distance and normal force at both ends (the force is
//    made from them by microForce, fractal_roughness.hpp: offline for the whole render, live in
//    the audio callback sample by sample).
// Everything of a segment acts at the surface body's node nearest the tip at its later tick
// (scrape_sites.hpp: the slab's top face, or a mesh solid's surface). A lift, a gap in the ticks
// or a tick going backwards starts a new walk; the travelled distance (where the roughness
// profile is read) keeps growing over the whole session.
// On a mesh (PenScrapeOptions::mesh_to_world) the surface curves under the tip:
//  - the distance travelled is the tip's on the surface (p_proj_world), not its uv's;
//  - a uv step of half a tile or more is a seam of the mesh's uv: the walk goes on from the same
//    place shifted by whole tiles (the texture wraps; the built-in shapes' seams are whole
//    tiles); what then remains longer than the tip could have moved at the stated scale (two
//    texels for rounding) is a seam of any other kind, or the tip crossing a lathe's pole, where
//    the walk starts again in the texel it lands in;
//  - a relief's previous contact normal is turned with the surface (the shortest rotation taking
//    the previous tick's geometric normal to this one's) before the change is taken, so the
//    surface's own curvature does not click, only the relief.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <thx_msgs/contact_t.hpp>

#include "clients/audio/analysis/tet_mesh.hpp"
#include "clients/audio/synthesis/meso_impulses.hpp"
#include "clients/audio/synthesis/relief_impulses.hpp"
#include "clients/audio/synthesis/scrape_sites.hpp"
#include "textures/sampling.hpp"
#include "textures/texture_map.hpp"

namespace thx::audio {

// One servo tick of hapticd's CONTACT stream, as the scrape needs it.
struct ScrapeSample {
  std::int64_t tick = 0;  // servo tick index
  bool in_contact = false;
  tex::TexCoord uv;  // unwrapped texture coordinates of the tip's projection
  double f_normal_n = 0.0;  // normal force pushing the pen out (micro level's loudness)
  // World frame (contact_t): base plane normal, contact normal (a relief's own), tip velocity.
  Eigen::Vector3d n_geom{0.0, 0.0, 1.0};
  Eigen::Vector3d n_contact{0.0, 0.0, 1.0};
  Eigen::Vector3d v_tangent{0.0, 0.0, 0.0};
  Eigen::Vector3d p_world{0.0, 0.0, 0.0};  // the tip projected onto the surface (p_proj_world)
};

// A CONTACT sample as the scrape needs it (the offline render and the live client read it alike).
ScrapeSample scrapeSample(const thx_msgs::contact_t& c);

enum class MesoSource {
  TexelWalk,       // a normal map: Eq. 5 at every texel entered, the texel's own normal
  ContactNormals,  // a relief map: the change of the contact's normal between ticks
};

struct PenScrapeOptions {
  double servo_hz = 1000.0;
  double pen_mass_kg = 0.045;                // the mass in Eq. 5 (the pen's effective mass)
  Eigen::Vector2d surface_size_m{0.2, 0.2};  // the texture spans this once (scene surface.size)
  MesoSource meso = MesoSource::TexelWalk;
  double min_normal_dot = 0.05;              // Eq. 5's floor of n_g . n
  // A mesh scene: the surface body is the solid its mesh encloses, in the mesh's frame, placed in
  // the world by this (scrape_sites.hpp); surface_size_m is then the metres per uv unit.
  std::optional<Eigen::Isometry3d> mesh_to_world;
};

// One meso impulse: at tick `tick` (the later end of the segment), at the surface body's node
// `node`. J (N s) acts on the pen along the surface normal; the body receives -J along the node's
// direction (scrape_sites.hpp: +z on the slab).
struct PenStrike {
  std::int64_t tick = 0;
  int node = 0;
  double impulse_ns = 0.0;
};

// One segment's micro level: from tick_a to tick_b the tip travelled from distance s0 to s1 (m,
// along the session's path) under a normal force going from f0 to f1 (N), at the body's node
// `node`. Its force acts on the samples after tick_a's up to tick_b's (microForce over them).
struct PenMicroSegment {
  std::int64_t tick_a = 0, tick_b = 0;
  int node = 0;
  double s0 = 0.0, s1 = 0.0, f0 = 0.0, f1 = 0.0;
};

class PenScrape {
 public:
  // `slab`: the surface's body (slabMesh: top face at z = 0, centred on the origin; or a mesh
  // scene's solid, options.mesh_to_world). Both must outlive this.
  PenScrape(const tex::TextureMap& map, const TetMesh& slab, PenScrapeOptions options);

  // The next tick. strike(const PenStrike&) for each non-zero meso impulse, micro(const
  // PenMicroSegment&) once per segment in contact; returns the meso impulses made (texels entered
  // or relief ticks, zero ones included).
  template <class Strike, class Micro>
  std::size_t next(const ScrapeSample& s, Strike&& strike, Micro&& micro) {
    std::size_t count = 0;
    if (have_previous_ && previous_.in_contact && s.in_contact && s.tick > previous_.tick) {
      const ScrapeSample& a = previous_;
      const int node = sites_.nearest(s.uv, s.p_world);
      tex::TexCoord from = a.uv;
      bool seam = false;
      double step_m = 0.0;
      if (sites_.onMesh()) {
        from.u += std::round(s.uv.u - a.uv.u);
        from.v += std::round(s.uv.v - a.uv.v);
        step_m = (s.p_world - a.p_world).norm();
        seam = !withinReach(from, s.uv, step_m);
      } else {
        step_m = Eigen::Vector2d((s.uv.u - a.uv.u) * options_.surface_size_m.x(),
                                 (s.uv.v - a.uv.v) * options_.surface_size_m.y()).norm();
      }
      // The micro segment first: it starts at tick a, the meso impulses fall at tick b (the live
      // queue is in time order).
      micro(PenMicroSegment{a.tick, s.tick, node, distance_m_, distance_m_ + step_m, a.f_normal_n, s.f_normal_n});
      distance_m_ += step_m;
      if (options_.meso == MesoSource::TexelWalk) {
        if (seam) {
          state_ = {};  // the walk starts again where the tip landed
        } else {
          const double dt = double(s.tick - a.tick) / options_.servo_hz;
          // Velocity in the texture's tangent frame: +x along u, +y along v.
          const Eigen::Vector3d v((s.uv.u - from.u) * options_.surface_size_m.x() / dt,
                                  (s.uv.v - from.v) * options_.surface_size_m.y() / dt, 0);
          count = mesoImpulsesAlong(surface_, state_, from, s.uv, v, [&](const MesoImpulse& m) {
            if (m.impulse.z() != 0.0) strike(PenStrike{s.tick, node, m.impulse.z()});
          });
        }
      } else {
        ReliefTick before = reliefTick(a);
        if (a.n_geom != s.n_geom)  // a curved surface: turn the previous normal with it
          before.contact_normal = Eigen::Quaterniond::FromTwoVectors(a.n_geom, s.n_geom) * a.n_contact;
        const double j = reliefImpulse(before, reliefTick(s), options_.pen_mass_kg, options_.min_normal_dot);
        count = 1;
        if (j != 0.0) strike(PenStrike{s.tick, node, j});
      }
    } else {
      state_ = {};  // lifted, or a gap: the next touch starts a new walk
    }
    previous_ = s;
    have_previous_ = true;
    return count;
  }
  // Forget the path so far (samples were lost).
  void reset();
  const ScrapeSites& sites() const { return sites_; }

 private:
  static ReliefTick reliefTick(const ScrapeSample& s) { return {s.in_contact, s.n_geom, s.n_contact, s.v_tangent}; }
  // Whether a uv step from `from` to `to` fits a tip that moved `moved_m` on the surface.
  bool withinReach(tex::TexCoord from, tex::TexCoord to, double moved_m) const;

  PenScrapeOptions options_;
  MesoSurface surface_;
  ScrapeSites sites_;
  MesoState state_;
  ScrapeSample previous_;
  bool have_previous_ = false;
  double distance_m_ = 0.0;
};

}  // namespace thx::audio
