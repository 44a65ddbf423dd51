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
// The objects at the physics client's poses (physics_poses_t: body i = objects[i], centre of
// mass, body frame -> world); objects without a pose (i >= poses.size()) at rest.
std::vector<ObjectInstance> objectsAt(const scene::Scene& scene, const std::vector<Eigen::Isometry3d>& poses);

// The pen's rest position on the surface (plane-local x, y): where the scene's hand script
// starts (its first press or stroke), else the plane's centre.
Eigen::Vector2d penRestPosition(const scene::Scene& scene);

// Tip at plane-local (x, y) on the surface (the relief depth there), shaft up the normal.
std::vector<ObjectInstance> penAt(const tex::TexturedSurface& surface, const Eigen::Vector3d& tip_local);
// The pen of device_state_t, plane-local: not held, penAt(tip). Held (the tip below the surface):
// the pen's ball (yellow) and shaft at the proxy on the surface, the device's tip a smaller red
// ball where it is (seen where the relief leaves it visible) and a thin dark rod between them.
std::vector<ObjectInstance> penWithProxy(const tex::TexturedSurface& surface, const Eigen::Vector3d& tip_local,
                                         const Eigen::Vector3d& proxy_local, bool proxy_held);
Eigen::Vector3d tipOnSurface(const tex::TexturedSurface& surface, const Eigen::Vector2d& xy_local);

}  // namespace thx::visual
