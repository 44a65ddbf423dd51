#pragma once
// modal-analyze's command line (kModalHelp is its --help text). parseModalOptions() throws
// UsageError naming the option, the value and what was expected.
#include <optional>
#include <string>
#include <vector>

#include "clients/audio/analysis/audible_modes.hpp"
#include "clients/audio/analysis/elastic_material.hpp"
#include "clients/audio/analysis/modal_analysis.hpp"
#include "clients/audio/analysis/modal_cache.hpp"
#include "clients/audio/analysis/scene_bodies.hpp"
#include "clients/audio/analysis/tet_mesh.hpp"

namespace thx::audio {

extern const char* const kModalHelp;

enum class ShapeKind { Box, Slab, Sphere, Cylinder, Mesh };

struct ModalOptions {
  bool help = false;
  std::string scene;  // --scene FILE: its surface slab and objects instead of one --shape
  std::optional<double> slab_thickness;  // overrides the scene's surface.thickness
  int slab_cells = kSlabCells;
  int slab_layers = kSlabLayers;
  std::string name;  // the object's name in messages (default: the shape)
  ShapeKind shape = ShapeKind::Box;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  // box edges / slab extent_x, extent_y, thickness
  double radius = 0.0, length = 0.0;
  std::vector<int> cells;
  std::string mesh;        // --mesh: a mesh file or a built-in shape's name
  double mesh_unit = 1.0;  // metres per file unit
  int segments = 48;       // a built-in shape's divisions around its axis
  double max_edge = 0.0;   // Gmsh's longest tetrahedron edge; 0 = from the surface
  ElementOrder order = ElementOrder::Quadratic;
  bool clamp_edges = false;  // a slab shape, or a scene's slab (overrides surface.held)
  ElasticMaterial material;
  ModalSettings settings;
  AudibleOptions audible;
  std::optional<std::string> cache_dir;  // resolved default unless --no-cache
  std::string csv;
  bool quiet = false;
};

ModalOptions parseModalOptions(const std::vector<std::string>& args);
// The mesh the options describe (ModalError on a bad shape); for --mesh, the surface's triangle
// count in *surface_triangles when given.
TetMesh buildMesh(const ModalOptions& options, std::size_t* surface_triangles = nullptr);

}  // namespace thx::audio
