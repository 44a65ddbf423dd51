#pragma once
// What the scene puts on the plane, as drawable instances: its objects at their rest poses (the
// scene file's poses) and the pen (tip sphere and shaft along the plane's normal, the tip resting
// on the surface the senses share).
#include <optional>
#include <vector>

#include "clients/visual/object_renderer.hpp"
#include "clients/visual/pen_view.hpp"
#include "scenes/scene.hpp"
#include "textures/textured_surface.hpp"

namespace thx::visual {

std::vector<ObjectInstance> objectsAtRest(const scene::Scene& scene);
// The objects at the physics client's poses (physics_poses_t: body i = objects[i], centre of
// mass, body frame -> world); objects without a pose (i >= poses.size()) at rest.
std::vector<ObjectInstance> objectsAt(const scene::Scene& scene, const std::vector<Eigen::Isometry3d>& poses);

// Device `device`'s pen's rest position on the surface (plane-local x, y): where its hand script
// starts (its first press or stroke), else (also for a device the scene lacks) the plane's centre.
Eigen::Vector2d penRestPosition(const scene::Scene& scene, std::size_t device = 0);

// The pens take device `device`'s colours (pen_colours.hpp: device 0's ball red, yellow held).
// Tip at plane-local (x, y) on the surface (the relief depth there), shaft up the normal.
std::vector<ObjectInstance> penAt(const tex::TexturedSurface& surface, const Eigen::Vector3d& tip_local, int device = 0);
// The pen of device_state_t, plane-local: not held, penAt(tip). Held (the tip below the surface):
// the pen's ball (held colour) and shaft at the proxy on the surface, the device's tip a smaller
// ball (ball colour) where it is (seen where the relief leaves it visible) and a thin dark rod
// between them.
std::vector<ObjectInstance> penWithProxy(const tex::TexturedSurface& surface, const Eigen::Vector3d& tip_local,
                                         const Eigen::Vector3d& proxy_local, bool proxy_held, int device = 0);
// Every pen of `pens` (world positions) as penWithProxy draws it, each in its device's colours;
// a device whose tool is a capsule in `scene` (docs/scenes.md "device.tool") as capsuleToolAt.
std::vector<ObjectInstance> pensAt(const tex::TexturedSurface& surface, const std::vector<PenView>& pens,
                                   const scene::Scene* scene = nullptr);
// A capsule tool (issue 30): its tip ball (the tool's radius) at the proxy, hapticd's tool tip (the
// held colour while the device's tip is elsewhere, which is then a smaller ball with a dark rod to
// it, as penWithProxy draws), its shaft of the tool's radius and length along the device
// orientation's +z: the device's, not the coupled tool's (the messages do not carry it).
std::vector<ObjectInstance> capsuleToolAt(const tex::TexturedSurface& surface, const PenView& pen,
                                          const scene::Tool& tool);
// The pens at rest, each resting on the surface where its hand script starts (penRestPosition):
// every device's of the scene, or `device`'s alone; the first of them at `first_xy` when given
// (--pen X,Y). A capsule tool stands upright with its ball on the surface.
std::vector<ObjectInstance> pensAtRest(const tex::TexturedSurface& surface, const scene::Scene& scene,
                                       std::optional<int> device, const std::optional<Eigen::Vector2d>& first_xy);
Eigen::Vector3d tipOnSurface(const tex::TexturedSurface& surface, const Eigen::Vector2d& xy_local);

}  // namespace thx::visual
