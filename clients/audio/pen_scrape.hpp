#pragma once
// The pen's scrape as meso impulses, one servo tick at a time, for the live client
// (pen_meso_source.hpp). The offline render (scrape_synthesis.cpp) walks the path itself with the
// same Eq. 5 and finds nodes with the same SlabTopFace, so on a normal map both strike the same
// nodes with the same impulses (the LivePipeline test compares them). Between two consecutive ticks
// in contact the tip's texture path is walked (Eq. 5, meso_impulses.hpp) at the velocity of that
// segment; each texel entered gives an impulse along the surface normal at the slab's top-face node
// nearest the tip. A lift, a gap in the ticks or a tick going backwards starts a new walk.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "clients/audio/meso_impulses.hpp"
#include "clients/audio/tet_mesh.hpp"
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
};

struct PenScrapeOptions {
  double servo_hz = 1000.0;
  double pen_mass_kg = 0.045;                // the mass in Eq. 5 (the pen's effective mass)
  Eigen::Vector2d surface_size_m{0.2, 0.2};  // the texture spans this once (scene surface.size)
};

// One impulse on the slab: at tick `tick` (the later end of the segment), on node `node`, along
// +z. The slab receives -J of Eq. 5 (the pen +J), as in the offline render (scrape_synthesis.hpp).
struct PenStrike {
  std::int64_t tick = 0;
  int node = 0;
  double impulse_ns = 0.0;
};

// The slab's top-face nodes (z = 0) and the one nearest to a point of the texture.
class SlabTopFace {
 public:
  // `slab` (slabMesh: top face at z = 0, centred on the origin) must outlive this.
  SlabTopFace(const TetMesh& slab, Eigen::Vector2d surface_size_m);
  // The top-face node nearest to texture coordinates uv (wrapped into the slab's one span).
  int nearest(tex::TexCoord uv) const;

 private:
  const TetMesh& slab_;
  Eigen::Vector2d size_;
  std::vector<int> top_;
};

class PenScrape {
 public:
  // `slab`: the surface's mesh (slabMesh: top face at z = 0, centred on the origin). Both must
  // outlive this.
  PenScrape(const tex::TextureMap& map, const TetMesh& slab, PenScrapeOptions options);

  // The next tick. emit(const PenStrike&) for each non-zero impulse; returns the texels entered
  // (impulses, zero ones included).
  template <class Emit>
  std::size_t next(const ScrapeSample& s, Emit&& emit) {
    std::size_t count = 0;
    if (have_previous_ && previous_.in_contact && s.in_contact && s.tick > previous_.tick) {
      const double dt = double(s.tick - previous_.tick) / options_.servo_hz;
      // Velocity in the texture's tangent frame: +x along u, +y along v.
      const Eigen::Vector3d v((s.uv.u - previous_.uv.u) * options_.surface_size_m.x() / dt,
                              (s.uv.v - previous_.uv.v) * options_.surface_size_m.y() / dt, 0);
      int node = -1;
      count = mesoImpulsesAlong(surface_, state_, previous_.uv, s.uv, v, [&](const MesoImpulse& m) {
        if (m.impulse.z() == 0.0) return;
        if (node < 0) node = top_.nearest(s.uv);
        emit(PenStrike{s.tick, node, -m.impulse.z()});
      });
    } else {
      state_ = {};  // lifted, or a gap: the next touch starts a new walk
    }
    previous_ = s;
    have_previous_ = true;
    return count;
  }
  // Forget the path so far (samples were lost).
  void reset();

 private:
  PenScrapeOptions options_;
  MesoSurface surface_;
  SlabTopFace top_;
  MesoState state_;
  ScrapeSample previous_;
  bool have_previous_ = false;
};

}  // namespace thx::audio
