#include "clients/visual/scene_objects.hpp"

#include "clients/visual/glyphs.hpp"
#include "clients/visual/pen_colours.hpp"
#include "scenes/scene_frames.hpp"

namespace thx::visual {
namespace {

constexpr double kPenTipRadius = 0.0015;  // m: big enough to see at the default camera distance
constexpr double kPenShaftRadius = 0.001;  // m: thinner than the ball, so the ball on the surface shows
constexpr double kPenShaftLength = 0.05;
constexpr double kHeldTipRadius = 0.6 * kPenTipRadius;  // m: the device's tip under a held proxy
constexpr double kLinkRadius = 0.0002;

Eigen::Vector3f albedoOf(const scene::Material& m) {
  if (m.name == "glass") return {0.55f, 0.75f, 0.85f};
  if (m.name == "steel" || m.name == "aluminium" || m.name == "iron" || m.name == "tin") return {0.7f, 0.7f, 0.72f};
  if (m.name == "wood") return {0.65f, 0.45f, 0.25f};
  if (m.name == "plastic" || m.name == "polycarbonate") return {0.2f, 0.45f, 0.8f};
  return {0.8f, 0.6f, 0.3f};
}

ObjectInstance instance(UnitShape shape, const Eigen::Isometry3d& pose, const Eigen::Vector3d& scale,
                        const Eigen::Vector3f& albedo) {
  ObjectInstance o;
  o.shape = shape;
  o.model = Eigen::Affine3d(pose.matrix()) * Eigen::Scaling(scale);
  o.pose = pose;
  o.albedo = albedo;
  return o;
}

}  // namespace

std::vector<ObjectInstance> objectsAtRest(const scene::Scene& scene) { return objectsAt(scene, {}); }

std::vector<ObjectInstance> objectsAt(const scene::Scene& scene, const std::vector<Eigen::Isometry3d>& poses) {
  std::vector<ObjectInstance> out;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const scene::SceneObject& o = scene.objects[i];
    const Eigen::Isometry3d pose = i < poses.size() ? poses[i] : scene::toIsometry(o.pose);
    const Eigen::Vector3f albedo = albedoOf(o.material);
    switch (o.shape) {
      case scene::Shape::Sphere:
        out.push_back(instance(UnitShape::Sphere, pose, Eigen::Vector3d::Constant(o.radius_m), albedo));
        if (o.texture) out.back().textured_object = int(i);
        break;
      case scene::Shape::Box:
        out.push_back(instance(UnitShape::Box, pose, o.size_m, albedo));
        out.back().letter = blockLetter(o.name);
        if (o.texture) out.back().textured_object = int(i);
        break;
      case scene::Shape::Cylinder:
        out.push_back(instance(UnitShape::Cylinder, pose, {o.radius_m, o.radius_m, o.length_m}, albedo));
        break;
      case scene::Shape::Capsule: {
        out.push_back(instance(UnitShape::Cylinder, pose, {o.radius_m, o.radius_m, o.length_m}, albedo));
        for (double end : {-0.5, 0.5}) {
          Eigen::Isometry3d cap = pose;
          cap.translate(Eigen::Vector3d(0, 0, end * o.length_m));
          out.push_back(instance(UnitShape::Sphere, cap, Eigen::Vector3d::Constant(o.radius_m), albedo));
        }
        break;
      }
    }
  }
  return out;
}

Eigen::Vector2d penRestPosition(const scene::Scene& scene, std::size_t device) {
  if (device >= scene::deviceCount(scene)) return Eigen::Vector2d::Zero();  // --device N beyond the scene's
  for (const scene::ScriptStep& step : scene::deviceAt(scene, device).script) {
    if (const auto* press = std::get_if<scene::PressStep>(&step)) return press->position_m;
    if (const auto* stroke = std::get_if<scene::StrokeStep>(&step)) return stroke->from_m;
    if (const auto* move = std::get_if<scene::MoveStep>(&step)) return move->to_m.head<2>();
  }
  return Eigen::Vector2d::Zero();
}

namespace {
// Under a held proxy: the device's tip a smaller ball (its ball colour) where it is, and a thin
// dark rod from it to the proxy (plane-local positions).
void appendHeldTip(std::vector<ObjectInstance>& out, const tex::TexturedSurface& surface,
                   const Eigen::Vector3d& tip_local, const Eigen::Vector3d& proxy_local, const PenColours& colours) {
  const Eigen::Vector3d link = proxy_local - tip_local;
  const Eigen::Isometry3d& plane = surface.mapping().plane_to_world;
  Eigen::Isometry3d tip = plane;
  tip.translate(tip_local);
  out.push_back(instance(UnitShape::Sphere, tip, Eigen::Vector3d::Constant(kHeldTipRadius), colours.ball));
  // The unit cylinder runs along z: turn z onto the link, centre it between tip and proxy.
  Eigen::Isometry3d rod = plane;
  rod.translate(0.5 * (tip_local + proxy_local));
  rod.rotate(Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), link));
  out.push_back(instance(UnitShape::Cylinder, rod, {kLinkRadius, kLinkRadius, link.norm()}, {0.1f, 0.1f, 0.1f}));
}
}  // namespace

std::vector<ObjectInstance> penWithProxy(const tex::TexturedSurface& surface, const Eigen::Vector3d& tip_local,
                                         const Eigen::Vector3d& proxy_local, bool proxy_held, int device) {
  if (!proxy_held || (proxy_local - tip_local).norm() <= 0.0) return penAt(surface, tip_local, device);
  // Held: the pen rests on the proxy (its ball in the held colour), the device's tip a smaller ball below.
  const PenColours colours = penColours(device);
  std::vector<ObjectInstance> out = penAt(surface, proxy_local, device);
  out.front().albedo = colours.held;
  appendHeldTip(out, surface, tip_local, proxy_local, colours);
  return out;
}

namespace {
// Device `device`'s capsule tool in `scene`, if it has one.
const scene::Tool* capsuleToolOf(const scene::Scene* scene, int device) {
  if (scene == nullptr || device < 0 || std::size_t(device) >= scene::deviceCount(*scene)) return nullptr;
  const scene::Tool& tool = scene::deviceAt(*scene, std::size_t(device)).tool;
  return tool.shape == scene::ToolShape::Capsule ? &tool : nullptr;
}
}  // namespace

std::vector<ObjectInstance> capsuleToolAt(const tex::TexturedSurface& surface, const PenView& pen,
                                          const scene::Tool& tool) {
  const PenColours colours = penColours(pen.device);
  const bool held = pen.proxy_held && (pen.proxy_world - pen.tip_world).norm() > 0.0;
  Eigen::Isometry3d ball = Eigen::Isometry3d::Identity();
  ball.translation() = pen.proxy_world;
  Eigen::Isometry3d shaft = Eigen::Isometry3d::Identity();
  shaft.linear() = pen.q_world.toRotationMatrix();
  shaft.translation() = pen.proxy_world + pen.q_world * Eigen::Vector3d(0, 0, 0.5 * tool.length_m);
  std::vector<ObjectInstance> out{
      instance(UnitShape::Sphere, ball, Eigen::Vector3d::Constant(tool.radius_m), held ? colours.held : colours.ball),
      instance(UnitShape::Cylinder, shaft, {tool.radius_m, tool.radius_m, tool.length_m}, {0.25f, 0.25f, 0.3f})};
  if (held) appendHeldTip(out, surface, surface.toLocal(pen.tip_world), surface.toLocal(pen.proxy_world), colours);
  return out;
}

std::vector<ObjectInstance> pensAt(const tex::TexturedSurface& surface, const std::vector<PenView>& pens,
                                   const scene::Scene* scene) {
  std::vector<ObjectInstance> out;
  for (const PenView& p : pens) {
    const scene::Tool* tool = capsuleToolOf(scene, p.device);
    const std::vector<ObjectInstance> pen =
        tool ? capsuleToolAt(surface, p, *tool)
             : penWithProxy(surface, surface.toLocal(p.tip_world), surface.toLocal(p.proxy_world), p.proxy_held, p.device);
    out.insert(out.end(), pen.begin(), pen.end());
  }
  return out;
}

std::vector<ObjectInstance> pensAtRest(const tex::TexturedSurface& surface, const scene::Scene& scene,
                                       std::optional<int> device, const std::optional<Eigen::Vector2d>& first_xy) {
  std::vector<int> devices{device.value_or(0)};
  for (int i = 1; !device && i < int(scene::deviceCount(scene)); ++i) devices.push_back(i);
  std::vector<ObjectInstance> out;
  for (const int i : devices) {
    const Eigen::Vector2d xy = first_xy && i == devices.front() ? *first_xy : penRestPosition(scene, std::size_t(i));
    std::vector<ObjectInstance> pen;
    if (const scene::Tool* tool = capsuleToolOf(&scene, i)) {
      PenView upright;  // the ball resting on the surface, the shaft up its normal
      upright.device = i;
      upright.q_world = Eigen::Quaterniond(surface.mapping().plane_to_world.linear());
      upright.tip_world = upright.proxy_world =
          surface.mapping().plane_to_world * (tipOnSurface(surface, xy) + Eigen::Vector3d(0, 0, tool->radius_m));
      pen = capsuleToolAt(surface, upright, *tool);
    } else {
      pen = penAt(surface, tipOnSurface(surface, xy), i);
    }
    out.insert(out.end(), pen.begin(), pen.end());
  }
  return out;
}

Eigen::Vector3d tipOnSurface(const tex::TexturedSurface& surface, const Eigen::Vector2d& xy_local) {
  return {xy_local.x(), xy_local.y(), surface.at(xy_local.x(), xy_local.y()).height_m};
}

std::vector<ObjectInstance> penAt(const tex::TexturedSurface& surface, const Eigen::Vector3d& tip_local, int device) {
  const Eigen::Isometry3d& plane = surface.mapping().plane_to_world;
  Eigen::Isometry3d tip = plane;
  tip.translate(tip_local);
  Eigen::Isometry3d shaft = tip;
  shaft.translate(Eigen::Vector3d(0, 0, kPenTipRadius + kPenShaftLength / 2));
  return {instance(UnitShape::Sphere, tip, Eigen::Vector3d::Constant(kPenTipRadius), penColours(device).ball),
          instance(UnitShape::Cylinder, shaft, {kPenShaftRadius, kPenShaftRadius, kPenShaftLength},
                   {0.25f, 0.25f, 0.3f})};
}

}  // namespace thx::visual
