#pragma once
// One scene as the live client plays it: the surface's sound (texture, slab, modes), the pen's
// and the moving objects' modes, the SynthScene the callback plays and the excitation sources
// that feed it. Built whole in the feed thread at the start and on every scene switch; the
// SynthScene goes to the callback (LiveSynth), the rest stays with the feed.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "clients/audio/live/pen_source.hpp"
#include "clients/audio/live/physics_source.hpp"
#include "clients/audio/synthesis/excitation.hpp"
#include "clients/audio/synthesis/surface_sound.hpp"
#include "clients/audio/synthesis/synth_scene.hpp"

namespace thx::audio {

struct LiveSceneSettings {
  SlabSettings slab;
  int device = 0;                     // the pen played: this device's pen (device.pen) and mass
  bool every_device = false;          // every device's pen, each its own (else `device`'s alone)
  std::optional<double> pen_mass_kg;  // unset: each device's simulated mass
  bool pen_modes = true;              // the pen's own modes sound (else the slab and objects only)
  bool micro = true;                  // the micro level (the scene's surface.roughness)
  bool object_contacts = true;        // two objects rubbing (the micro level too: needs `micro`)
  ElementOrder object_order = ElementOrder::Quadratic;  // the moving objects' meshes
  std::size_t max_block = 4096;
  std::int64_t playout_delay_ns = 0;
  // How a mesh scene's surface body is made (surface_sound.hpp; the audio-client program hands in
  // Gmsh's); without it a mesh scene is refused by name.
  MeshBodyBuilder mesh_body;
};

struct LiveScene {
  std::uint32_t generation = 0;
  std::unique_ptr<SurfaceSound> sound;     // the sources point into it
  std::unique_ptr<SoundingScene> physics;  // the surface and the moving objects as ModalBodies
  std::unique_ptr<SynthScene> synth;       // taken by LiveSynth::offerScene
  std::vector<std::unique_ptr<ExcitationSource>> sources;  // the pens', in `devices` order, then the physics client's
  std::vector<int> devices;        // the devices whose pens are played, ascending
  std::vector<int> pen_bodies;     // by `devices` index: the pen's SynthScene body (-1: no pen modes)
  std::vector<int> object_bodies;  // by objects[] index (-1: fixed, or no audible mode)
  std::vector<ExcitationSource*> sourcePointers() const;
};

// Bodies: the surface slab (0), the pens (settings.device's `pen`, or with every_device each
// device's in index order, when it has audible modes; a scene without settings.device is a Config
// error naming it), each moving object with audible modes. Sources: each pen (hapticd's CONTACT:
// meso or relief impulses and the micro level on the slab and that pen, with its device's mass)
// and the physics client's streams (impacts, texel paths, relief momentum changes on the slab and
// the objects; an impact with the pen rings the first pen played). A muted scene (audio.mute) has the same
// bodies, no sources and a muted SynthScene: the callback plays zeros while it is current.
std::unique_ptr<LiveScene> buildLiveScene(const std::string& scene_file, const LiveSceneSettings& settings,
                                          std::uint32_t generation);

// The surface's modes as a sounding body.
SoundingBody surfaceBody(const SurfaceSound& sound);
// Any body's modes as a sounding body.
SoundingBody soundingBody(std::string name, const AudibleModes& modes);

}  // namespace thx::audio
