#pragma once
// bench_table1's offline memory of modal analysis: each solve runs in a fresh process (this
// program re-executed with --modal-child), so its peak resident set (wait4's ru_maxrss) is that
// solve's alone; an idle child (kind "idle": the same program, nothing solved) gives the baseline
// the table subtracts. Kinds, all of the scene's surface (size, thickness, material, held or free):
//   spring    the spring-mass lattice (clients/audio/analysis/spring_mass.hpp), SIZE nodes per side
//   fem-slab  the audio client's slab: Tet10, SIZE cells per side, LAYERS through the thickness
//   fem-mesh  a mesh's FEM: Tet4, SIZE cells per side (the mesh's (SIZE+1)² vertices on top),
//             kMeshLayers through the thickness (LAYERS is ignored)
// Every solve asks for kModes elastic modes at a 20 Hz shift, as the audio client does.
#include <string>
#include <vector>

namespace thx::bench::table1 {

inline constexpr int kModes = 40;  // the audio client's default (clients/audio/synthesis/surface_sound.hpp)
// One Tet4 cell through the thickness: the thinnest volume mesh with the mesh's vertices on top,
// so the meshes' memory is a lower bound. Pinned here, not taken from the audio client's default,
// because femMeshDofs counts DOFs without building the mesh and must agree with what is solved.
inline constexpr int kMeshLayers = 1;

struct ModalProbe {
  std::string kind;
  int size = 0;
  bool ok = false;
  std::string error;
  long peak_rss_kb = 0;       // the child's peak resident set
  int dofs = 0;               // free DOFs (the eigenproblem's dimension)
  int mesh_dofs = 0;          // rows of the impulse-to-modes matrix (every node's DOFs)
  int modes = 0;              // elastic modes found
  long long matrix_bytes = 0;  // mesh_dofs x modes x 8: the impulse-to-modes matrix
  double seconds = 0;         // the solve's wall clock
};

// The child's side: solves one case of the scene and prints one line for the parent. Returns
// the exit status.
int runModalChild(const std::string& scene_path, const std::string& kind, int size, int layers);

// The parent's side: re-executes `self` with --modal-child and reads the line back.
ModalProbe probeModal(const std::string& self, const std::string& scene_path, const std::string& kind, int size,
                      int layers);

// The number of free DOFs of the scene's fem-mesh at `cells` per side (without building it).
long long femMeshDofs(bool held, int cells);
long long femMeshNodeDofs(int cells);  // every node's DOFs (the matrix's rows)

// y = a x^b, least squares on log y against log x.
struct PowerFit {
  double a = 0, b = 0;
  double at(double x) const;
};
PowerFit fitPower(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace thx::bench::table1
