#include "clients/audio/live_scene.hpp"

#include "clients/audio/physics_meso_source.hpp"

namespace thx::audio {

std::vector<ExcitationSource*> LiveScene::sourcePointers() const {
  std::vector<ExcitationSource*> out;
  for (const auto& s : sources) out.push_back(s.get());
  return out;
}

SoundingBody surfaceBody(const SurfaceSound& sound) {
  return SoundingBody{sound.slab.name, sound.modes.frequency_hz, sound.modes.decay_per_s, sound.modes.shapes};
}

std::unique_ptr<LiveScene> buildLiveScene(const std::string& scene_file, const LiveSceneSettings& s,
                                          std::uint32_t generation) {
  auto live = std::make_unique<LiveScene>();
  live->generation = generation;
  live->sound = std::make_unique<SurfaceSound>(buildSurfaceSound(scene_file, s.slab));
  const SurfaceSound& sound = *live->sound;
  std::vector<SoundingBody> bodies;
  bodies.push_back(surfaceBody(sound));
  live->synth = std::make_unique<SynthScene>(std::move(bodies), s.slab.sample_rate_hz, s.max_block, generation);
  PenScrapeOptions po;
  po.servo_hz = sound.scene.rates.servo_hz;
  po.pen_mass_kg = s.pen_mass_kg ? *s.pen_mass_kg : sound.scene.device.sim.device_mass_kg;
  po.surface_size_m = sound.scene.surface.size_m;
  live->sources.push_back(
      std::make_unique<PenMesoSource>(sound.map(), sound.slab, po, generation, s.playout_delay_ns));
  live->sources.push_back(std::make_unique<PhysicsMesoSource>(sound.map(), sound.slab, po.surface_size_m, generation,
                                                              s.playout_delay_ns));
  return live;
}

}  // namespace thx::audio
