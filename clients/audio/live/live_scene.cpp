#include "clients/audio/live/live_scene.hpp"

#include <filesystem>
#include <string>

#include "base/error.hpp"
#include "clients/audio/synthesis/sounding_scene.hpp"

namespace thx::audio {

std::vector<ExcitationSource*> LiveScene::sourcePointers() const {
  std::vector<ExcitationSource*> out;
  for (const auto& s : sources) out.push_back(s.get());
  return out;
}

SoundingBody soundingBody(std::string name, const AudibleModes& modes) {
  return SoundingBody{std::move(name), modes.frequency_hz, modes.decay_per_s, modes.shapes};
}

SoundingBody surfaceBody(const SurfaceSound& sound) { return soundingBody(sound.slab.name, sound.modes); }

std::unique_ptr<LiveScene> buildLiveScene(const std::string& scene_file, const LiveSceneSettings& s,
                                          std::uint32_t generation) {
  auto live = std::make_unique<LiveScene>();
  live->generation = generation;
  live->sound = std::make_unique<SurfaceSound>(buildSurfaceSound(scene_file, s.slab, {}, s.mesh_body));
  const SurfaceSound& sound = *live->sound;
  if (s.every_device) {
    for (std::size_t d = 0; d < scene::deviceCount(sound.scene); ++d) live->devices.push_back(int(d));
  } else {
    if (s.device < 0 || std::size_t(s.device) >= scene::deviceCount(sound.scene))
      throw Error(Error::Kind::Config, scene_file + ": no device " + std::to_string(s.device) + " (the scene has " +
                                           std::to_string(scene::deviceCount(sound.scene)) + ")");
    live->devices.push_back(s.device);
  }
  std::vector<SoundingBody> bodies;
  bodies.push_back(surfaceBody(sound));

  // Each pen played: its device's pen (device.pen) as a body of its own.
  std::vector<PenSourceBodies> pens(live->devices.size());
  std::vector<PenSound> pen_sounds(live->devices.size());
  for (std::size_t i = 0; i < live->devices.size(); ++i) {
    if (!s.pen_modes) break;
    const int d = live->devices[i];
    pen_sounds[i] = buildPenSound(scene::sceneForDevice(sound.scene, std::size_t(d)), s.slab);
    const PenSound& p = pen_sounds[i];
    if (p.modes.size() == 0) continue;
    pens[i].pen_body = int(bodies.size());
    pens[i].tip_node = p.tip_node;
    pens[i].tilt_deg = p.tilt_deg;
    bodies.push_back(soundingBody(live->devices.size() == 1 ? "pen" : "pen " + std::to_string(d), p.modes));
  }
  for (const PenSourceBodies& pen : pens) live->pen_bodies.push_back(pen.pen_body);

  // The moving objects, meshed and analysed as the offline render does (sounding_scene.hpp).
  const BodyOptions bo = bodyOptions(s.slab, s.object_order);
  live->physics = std::make_unique<SoundingScene>(soundingScene(std::filesystem::path(scene_file).stem().string(), sound.scene,
                                                                sound.map().isRelief(), bo,
                                                                std::make_shared<const ModalBody>(sound.slab, sound.modes),
                                                                sound.mesh_to_world));
  setPenBody(*live->physics, pen_sounds.front());  // impacts with the pen ring the first pen's body
  for (const auto& object : live->physics->objects) {
    if (!object || object->size() == 0) {
      live->object_bodies.push_back(-1);
      continue;
    }
    live->object_bodies.push_back(int(bodies.size()));
    bodies.push_back(soundingBody(object->mesh().name, object->modes()));
  }

  const RoughnessOptions roughness = sceneRoughness(sound.scene);
  const bool micro = s.micro && roughness.amplitude > 0.0;
  ObjectContactOptions rubs;
  rubs.enabled = micro && s.object_contacts;  // the same profile as the pens' micro level
  live->synth = std::make_unique<SynthScene>(std::move(bodies), s.slab.sample_rate_hz, s.max_block, generation,
                                             micro ? std::make_shared<const RoughnessProfile>(roughness) : nullptr);
  if (sound.scene.audio.mute) {  // audio.mute: no sources, the callback plays zeros (live_synth.hpp)
    live->synth->setMuted(true);
    return live;
  }
  for (std::size_t i = 0; i < live->devices.size(); ++i) {
    const scene::Scene pen_scene = scene::sceneForDevice(sound.scene, std::size_t(live->devices[i]));
    PenScrapeOptions po;
    po.servo_hz = sound.scene.rates.servo_hz;
    po.pen_mass_kg = s.pen_mass_kg ? *s.pen_mass_kg : pen_scene.device.sim.device_mass_kg;
    po.surface_size_m = sound.scene.surface.size_m;
    po.meso = sound.map().isRelief() ? MesoSource::ContactNormals : MesoSource::TexelWalk;
    po.mesh_to_world = sound.mesh_to_world;  // a mesh scene: the pen strikes its solid's surface
    pens[i].micro = micro;
    live->sources.push_back(std::make_unique<PenSource>(sound.map(), sound.slab, po, pens[i], generation, s.playout_delay_ns));
  }
  live->sources.push_back(std::make_unique<PhysicsSource>(*live->physics, live->object_bodies, generation,
                                                          s.playout_delay_ns, pens.front().pen_body, rubs));
  return live;
}

}  // namespace thx::audio
