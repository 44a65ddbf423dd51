#pragma once
// The pen scraping the surface, offline: the pen tip's texture path (one sample per servo tick,
// as hapticd's CONTACT stream records it) -> Eq. 5 meso impulses at every texel entered ->
// modal impulses on the surface slab's modes at the nearest top-face node -> the resonator bank.
// Deterministic: the same path gives the same samples.
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "clients/audio/audible_modes.hpp"
#include "clients/audio/pen_scrape.hpp"
#include "clients/audio/tet_mesh.hpp"
#include "textures/sampling.hpp"
#include "textures/texture_map.hpp"

namespace thx::audio {

struct ScrapeOptions {
  double sample_rate_hz = 44100.0;
  double servo_hz = 1000.0;
  double pen_mass_kg = 0.045;       // the mass in Eq. 5 (the pen's effective mass)
  Eigen::Vector2d surface_size_m{0.2, 0.2};  // the texture spans this once (scene surface.size)
  double tail_s = 0.5;              // rendered after the last sample, for the ring-out
  double peak = 0.5;                // output normalised to this peak (unless silent)
};

struct ScrapeRender {
  std::vector<float> samples;
  std::size_t impulses = 0;       // meso impulses applied
  double raw_peak = 0.0;          // peak of the modal displacement sum before normalising
};

// `slab` is the surface's mesh (slabMesh: top face at z = 0, centred on the origin) and `modes`
// its audible modes (shapes over slab's DOFs).
ScrapeRender renderScrape(const tex::TextureMap& map, const TetMesh& slab, const AudibleModes& modes,
                          std::span<const ScrapeSample> path, const ScrapeOptions& options);

}  // namespace thx::audio
