#pragma once
// What the scene puts on the plane, as drawable instances: its objects at their rest poses (the
// scene file's poses) and the pen (tip sphere and shaft along the plane's normal, the tip resting
// on the surface the senses share).
#include <optional>
#include <vector>

#include "clients/visual/object_renderer.hpp"
#include "scenes/scene.hpp"
#include "textures/textured_surface.hpp"

namespace thx::visual {

std::vector<ObjectInstance> objectsAtRest(const scene::Scene& scene);

// The pen's rest position on the surface (plane-local x, y): where the scene's hand script
// starts (its first press or stroke), else the plane's centre.
Eigen::Vector2d penRestPosition(const scene::Scene& scene);

// Tip at plane-local (x, y) on the surface (the relief depth there), shaft up the normal.
std::vector<ObjectInstance> penAt(const tex::TexturedSurface& surface, const Eigen::Vector3d& tip_local);
Eigen::Vector3d tipOnSurface(const tex::TexturedSurface& surface, const Eigen::Vector2d& xy_local);

}  // namespace thx::visual
