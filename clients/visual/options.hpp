#pragma once
// visual-client's command line (kHelp is the --help text). parseOptions() throws UsageError
// naming the option, the value and what was expected.
#include <optional>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "clients/visual/camera.hpp"
#include "clients/visual/render_settings.hpp"
#include "scenes/scene.hpp"

namespace thx::visual {

extern const char* const kHelp;

struct Options {
  bool help = false;
  std::string scene;
  std::string screenshot;  // --screenshot FILE
  int frames = 0;          // --frames N (with --out DIR)
  std::string out_dir;
  std::string frame_format = "png";
  int png_level = 1;
  int width = 640, height = 360;
  RenderSettings render;
  CameraPlacement camera;
  bool distance_given = false;
  double orbit_deg_per_frame = 0.0;  // --orbit; default 360 / N
  bool orbit_given = false;
  std::optional<Eigen::Vector2d> pen_xy;  // --pen X,Y
  bool no_pen = false;
  bool no_objects = false;
  bool quiet = false;
  std::string replay_log;  // --replay-log FILE (with --out DIR)
  double replay_rate_hz = 30.0;  // --rate: replay frames per recorded second, or the live loop's rate
  bool live = false;              // --live (with --out DIR or --window)
  std::string lcm_url;            // --lcm-url (default thx_msgs::kDefaultLcmUrl)
  double connect_timeout_s = 3.0; // --connect-timeout
  std::optional<int> device;      // --device N: draw device N's pen alone (live, --replay-log); else every device's
  double duration_s = 0.0;        // --duration (live; 0: until --frames or Ctrl-C)
  std::string scenes_dir = "scenes";  // --scenes-dir: where a scene switch's name is found
  bool allow_different_scene = false;  // --allow-different-scene: draw --scene whatever hapticd runs
  bool verbose = false;           // --verbose
  bool window = false;   // --window
  int window_frames = 0;  // --window-frames N
  std::string window_screenshot;  // --window-screenshot FILE
  std::string surface_mesh;       // --surface-mesh SHAPE (meshes/builtin_shapes.hpp): drawn instead of the plane
  double surface_mesh_tile_m = 0.0;  // --surface-mesh-tile M; 0: the scene's plane's width
};

Options parseOptions(const std::vector<std::string>& args);
// The camera of the command line; --distance defaults to 1.25 x the plane's larger side.
CameraPlacement cameraPlacement(const Options& o, const scene::Scene& scene);
// --surface-mesh's size and tile for the scene: radius 0.25 x the plane's larger side; tile
// --surface-mesh-tile, else the plane's width (the texture at the scale the scene gives it).
double surfaceMeshSize(const scene::Scene& scene);
double surfaceMeshTile(const Options& o, const scene::Scene& scene);

}  // namespace thx::visual
