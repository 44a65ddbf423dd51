#pragma once
// A scene's sounding bodies as the physics client's streams strike them (physics_excitation.hpp's
// SoundingScene): the surface slab, the moving objects and the pen, meshed and analysed at the
// command line's settings. Shared by the offline render (offline/physics_sound.hpp) and the live
// scene (live/live_scene.hpp).
#include <memory>
#include <optional>
#include <string>

#include "clients/audio/analysis/audible_modes.hpp"
#include "clients/audio/analysis/modal_analysis.hpp"
#include "clients/audio/analysis/modal_body.hpp"
#include "clients/audio/analysis/scene_bodies.hpp"
#include "clients/audio/analysis/tet_mesh.hpp"
#include "clients/audio/synthesis/physics_excitation.hpp"
#include "clients/audio/synthesis/surface_sound.hpp"
#include "scenes/scene.hpp"

namespace thx::audio {

struct BodyOptions {
  std::optional<double> slab_thickness_m;  // overrides the scene's surface.thickness
  int slab_cells = kSlabCells;
  int slab_layers = kSlabLayers;
  std::optional<bool> clamp_slab;          // overrides the scene's surface.held
  ElementOrder object_order = ElementOrder::Quadratic;
  ModalSettings modal;
  AnalysisOptions analysis;
  AudibleOptions audible;
};

// The body options of a slab's settings (the command line's): its thickness, cells and support,
// and the same modal, cache and audible settings for every body.
BodyOptions bodyOptions(const SlabSettings& slab, ElementOrder object_order);

// Meshes and analyses the scene's moving objects (scene_bodies.hpp) and, unless `surface` is
// given, its surface slab. A mesh scene's surface must be given (SurfaceSound: the solid its mesh
// encloses), with its mesh's place in the world (SurfaceSound::mesh_to_world); without it the
// scene is refused by name.
SoundingScene soundingScene(const std::string& name, const scene::Scene& scene, bool relief, const BodyOptions& options,
                            std::shared_ptr<const ModalBody> surface = nullptr,
                            std::optional<Eigen::Isometry3d> surface_mesh_to_world = std::nullopt);

// The scrape's pen (buildPenSound) as the pen the physics client's impacts strike; a pen without
// audible modes (or --no-pen's empty one) leaves it silent there.
void setPenBody(SoundingScene& scene, const PenSound& pen);

}  // namespace thx::audio
