#pragma once
// One scene as the live client plays it: the surface's sound (texture, slab, modes), the
// SynthScene the callback plays and the excitation sources that feed it. Built whole in the feed
// thread at the start and on every scene switch; the SynthScene goes to the callback (LiveSynth),
// the rest stays with the feed.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "clients/audio/excitation.hpp"
#include "clients/audio/pen_meso_source.hpp"
#include "clients/audio/surface_sound.hpp"
#include "clients/audio/synth_scene.hpp"

namespace thx::audio {

struct LiveSceneSettings {
  SlabSettings slab;
  std::optional<double> pen_mass_kg;  // unset: the scene's simulated device mass
  std::size_t max_block = 4096;
  std::int64_t playout_delay_ns = 0;
};

struct LiveScene {
  std::uint32_t generation = 0;
  std::unique_ptr<SurfaceSound> sound;  // the sources point into it
  std::unique_ptr<SynthScene> synth;    // taken by LiveSynth::offerScene
  std::vector<std::unique_ptr<ExcitationSource>> sources;
  std::vector<ExcitationSource*> sourcePointers() const;
};

// The surface slab as body 0; the pen's meso impulses (hapticd's CONTACT) and the rolling and
// sliding objects' (the physics client's texel paths) as its sources.
std::unique_ptr<LiveScene> buildLiveScene(const std::string& scene_file, const LiveSceneSettings& settings,
                                          std::uint32_t generation);

// The surface's modes as a sounding body.
SoundingBody surfaceBody(const SurfaceSound& sound);

}  // namespace thx::audio
