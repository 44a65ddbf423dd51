#pragma once
// What a scene asks to be analysed: the surface slab and every moving object, each as a Tet10
// structured mesh with its material from the scene. Fixed obstacles are skipped (they do not
// sound in this model). A capsule is meshed as a cylinder of its overall length (caps included).
#include <string>
#include <vector>

#include "clients/audio/elastic_material.hpp"
#include "clients/audio/tet_mesh.hpp"
#include "scenes/scene.hpp"

namespace thx::audio {

struct SceneMeshOptions {
  double slab_thickness_m = 0.01;  // the scene format has no thickness yet
  int slab_cells = 16;             // per side, 1 through the thickness
  bool clamp_slab = false;
  ElementOrder order = ElementOrder::Quadratic;
};

struct SceneBody {
  TetMesh mesh;  // mesh.name: "surface" or the object's name
  ElasticMaterial material;
  std::string note;  // how the shape was approximated, if it was
};

std::vector<SceneBody> sceneBodies(const scene::Scene& scene, const SceneMeshOptions& options);

}  // namespace thx::audio
