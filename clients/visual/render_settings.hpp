#pragma once
// What a frame looks like, independent of where it goes (file or window): the surface mode, the
// relief search's step counts, the light. Angles are in the plane's frame.
#include <Eigen/Core>
#include <string>

namespace thx::visual {

enum class SurfaceMode { Normal, Relief, Mesh };

// How relief mode finds the view ray's hit: a linear then binary search with fixed step counts,
// or the walk over the max-mipmap (max_mipmap.hpp), exact and never skipping a thin wall.
enum class ReliefSearch { Linear, MaxMip };

struct ReliefSteps {
  int linear = 16;  // samples from the plane down to the maximum depth
  int binary = 6;   // halvings of the last interval
  int shadow = 8;   // samples towards the light; 0 = no self-shadowing (maxmip: > 0 = shadows)
  ReliefSearch search = ReliefSearch::Linear;
};

struct Lighting {
  double elevation_deg = 50.0;   // of the light above the plane
  double azimuth_deg = -135.0;   // where the light comes from, around the plane's normal
  double ambient = 0.15;
  double specular = 0.15;
};

struct RenderSettings {
  SurfaceMode mode = SurfaceMode::Relief;
  int mesh_n = 256;  // mesh mode: quads per side
  ReliefSteps steps;
  Lighting light;
  Eigen::Vector3f plane_albedo{0.75f, 0.72f, 0.68f};
  bool hit_buffer = false;  // fill the float (u, v, depth) attachment (tests)
};

// Unit vector towards the light in the plane's frame.
Eigen::Vector3d lightDirectionLocal(const Lighting& light);

// "normal", "relief", "mesh:N" (N in [1, 4096]); UsageError naming `option` and the value otherwise.
void parseMode(const std::string& option, const std::string& text, RenderSettings& settings);
std::string modeName(const RenderSettings& settings);
// "linear" or "maxmip"; UsageError naming `option` and the value otherwise.
ReliefSearch parseSearch(const std::string& option, const std::string& text);

}  // namespace thx::visual
