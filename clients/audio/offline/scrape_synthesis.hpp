#pragma once
// The pen scraping the surface, offline (docs/audio.md §5): the pen tip's contact samples (one per
// servo tick, as hapticd's CONTACT stream records them) excite, on both sides of the contact, the
// surface body's modes (the slab's top-face node nearest the tip, or a mesh solid's surface node:
// scrape_sites.hpp) and the pen's own modes (at its tip):
//  - meso level: Eq. 5 impulses at every texel entered (normal maps, meso_impulses.hpp), or the
//    tick-to-tick change of the contact normal (relief maps, relief_impulses.hpp);
//  - micro level: fractal roughness read along the travelled distance, scaled by the normal
//    force, as a force sample by sample (fractal_roughness.hpp).
// The pen receives +J along the surface normal, the body -J. Deterministic: the same path gives
// the same samples.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "clients/audio/analysis/audible_modes.hpp"
#include "clients/audio/analysis/tet_mesh.hpp"
#include "clients/audio/synthesis/fractal_roughness.hpp"
#include "clients/audio/synthesis/pen_scrape.hpp"
#include "textures/sampling.hpp"
#include "textures/texture_map.hpp"

namespace thx::audio {

// The pen's own modes (nullptr in renderScrape: the slab alone sounds).
struct PenModes {
  const TetMesh* mesh = nullptr;  // the pen along its z axis, the tip at its lowest node
  const AudibleModes* modes = nullptr;
  int tip_node = 0;
  double tilt_deg = 30.0;  // the pen's axis from the surface normal
};

struct ScrapeOptions {
  double sample_rate_hz = 44100.0;
  double servo_hz = 1000.0;
  double pen_mass_kg = 0.045;       // the mass in Eq. 5 (the pen's effective mass, docs/audio.md §5)
  Eigen::Vector2d surface_size_m{0.2, 0.2};  // the texture spans this once (scene surface.size)
  MesoSource meso = MesoSource::TexelWalk;
  RoughnessOptions roughness;       // amplitude 0: no micro level
  double tail_s = 0.5;              // rendered after the last sample, for the ring-out
  std::optional<std::int64_t> origin_tick;  // the tick at sample 0 (unset: the path's first)
  double peak = 0.5;                // output normalised to this peak (unless silent)
  // A mesh scene: `slab` is the solid its mesh encloses, in the mesh's frame, placed in the world
  // by this; struck at its surface nodes along their outward normals (scrape_sites.hpp).
  std::optional<Eigen::Isometry3d> mesh_to_world;
};

struct ScrapeRender {
  std::vector<float> samples;
  std::size_t impulses = 0;       // meso impulses applied (texels entered, or relief ticks)
  std::size_t nonzero_impulses = 0;  // of which not exactly 0
  double raw_peak = 0.0;          // peak of the listeners' sum (docs/audio.md §9a) before normalising
  double raw_rms = 0.0;           // its RMS over the whole render
  double slab_peak = 0.0, pen_peak = 0.0;  // each body's share before normalising
  double micro_rms_n = 0.0;       // RMS micro force over the samples in contact
  std::size_t micro_samples = 0;  // the samples in contact that RMS is over
  std::vector<double> displacement;  // the listeners' sum before normalising
};

// The excitation alone, sample by sample (PenScrape's, pen_scrape.hpp): the impulse (N s, on the
// pen along n_g; the slab gets the opposite) applied at each sample, meso and micro (a force F
// contributes F/fs), and the surface body's node under the tip. A segment from tick a to tick b
// owns the samples after a's up to b's: its micro force over them, its meso impulses at b's.
// Both vectors have the render's length.
struct ScrapeExcitation {
  std::vector<double> impulse_ns;
  std::vector<int> slab_node;
  std::size_t impulses = 0, nonzero_impulses = 0;
  double micro_rms_n = 0.0;
  std::size_t micro_samples = 0;
};
ScrapeExcitation scrapeExcitation(const tex::TextureMap& map, const TetMesh& slab, std::span<const ScrapeSample> path,
                                  const ScrapeOptions& options);

// The options of the pen's PenScrape.
PenScrapeOptions penScrapeOptions(const ScrapeOptions& options);

// `slab` is the surface's body (slabMesh: top face at z = 0, centred on the origin; or a mesh
// scene's solid, options.mesh_to_world) and `modes` its audible modes (shapes over slab's DOFs). scrapeDisplacement leaves `samples` empty and the
// sum in `displacement`; normaliseScrape fills `samples`, raw_peak and raw_rms from it;
// renderScrape does both.
ScrapeRender scrapeDisplacement(const tex::TextureMap& map, const TetMesh& slab, const AudibleModes& modes,
                                std::span<const ScrapeSample> path, const ScrapeOptions& options,
                                const PenModes* pen = nullptr);
void normaliseScrape(ScrapeRender& render, double peak);
ScrapeRender renderScrape(const tex::TextureMap& map, const TetMesh& slab, const AudibleModes& modes,
                          std::span<const ScrapeSample> path, const ScrapeOptions& options,
                          const PenModes* pen = nullptr);

}  // namespace thx::audio
