#pragma once
// What a scene asks to be analysed: the surface slab (its thickness and how it is held from the
// scene's surface), every moving object, and the pen (device.pen: a cylinder), each as a Tet10
// structured mesh with its material from the scene. Fixed obstacles are skipped (they do not
// sound in this model). A capsule is meshed as a cylinder of its overall length (caps included).
#include <optional>
#include <string>
#include <vector>

#include "clients/audio/analysis/elastic_material.hpp"
#include "clients/audio/analysis/tet_mesh.hpp"
#include "scenes/scene.hpp"

namespace thx::audio {

// The shipped mesh sizes, Tet10: each body's first 30 (slab) or 20 (others) elastic modes within
// 1 % of a converged mesh, solved in well under 10 s and 300 MB (docs/audio.md §6).
inline constexpr int kSlabCells = 20;   // slab cells per side, in the plane
inline constexpr int kSlabLayers = 2;  // slab cells through the thickness
inline constexpr int kSphereCells = 6;  // per side of the sphere's mapped cube
inline constexpr int kBoxCellsShortest = 4;  // a box's cells on its shortest edge (cubes elsewhere)

struct SceneMeshOptions {
  std::optional<double> slab_thickness_m;  // overrides surface.thickness
  std::optional<bool> clamp_slab;          // overrides surface.held
  int slab_cells = kSlabCells;             // per side, in the plane
  int slab_layers = kSlabLayers;           // through the thickness
  bool pen = true;                         // the pen's body, last
  ElementOrder order = ElementOrder::Quadratic;
};

struct SceneBody {
  TetMesh mesh;  // mesh.name: "surface" or the object's name
  ElasticMaterial material;
  std::string note;  // how the shape was approximated, if it was
};

// The slab alone and the pen alone (mesh names "surface" and "pen"; the pen along z, centred on
// the origin, its tip the centre of its end face at z = -length/2).
SceneBody slabBody(const scene::Scene& scene, const SceneMeshOptions& options);
SceneBody penBody(const scene::Scene& scene, ElementOrder order = ElementOrder::Quadratic);
// The pen's tip node (the end-face node nearest the axis at z = -length/2).
int penTipNode(const TetMesh& pen);

std::vector<SceneBody> sceneBodies(const scene::Scene& scene, const SceneMeshOptions& options);

}  // namespace thx::audio
