// objects: the dynamic bodies physics simulates on the surface.
#include <algorithm>

#include "meshes/textured_ball_mesh.hpp"
#include "scenes/scene_frames.hpp"
#include "scenes/scene_sections.hpp"

namespace thx::scene::detail {

namespace {

// What each shape is measured by; any other dimension field is a mistake worth reporting.
std::vector<std::string> dimensionsOf(Shape shape) {
  switch (shape) {
    case Shape::Sphere:
      return {"radius"};
    case Shape::Box:
      return {"size"};
    case Shape::Capsule:
    case Shape::Cylinder:
      return {"radius", "length"};
  }
  return {};
}

std::string describeDimensions(Shape shape) {
  switch (shape) {
    case Shape::Sphere:
      return "sphere takes radius";
    case Shape::Box:
      return "box takes size: [x, y, z]";
    case Shape::Capsule:
      return "capsule takes radius and length (between the cap centres)";
    case Shape::Cylinder:
      return "cylinder takes radius and length";
  }
  return {};
}

void parseDimensions(const Field& field, SceneObject& object) {
  const std::vector<std::string> needed = dimensionsOf(object.shape);
  for (const char* key : {"radius", "size", "length"}) {
    const auto f = field.find(key);
    const bool wanted = std::find(needed.begin(), needed.end(), key) != needed.end();
    if (f && !wanted)
      f->fail("does not apply to shape " + std::string(toString(object.shape)), describeDimensions(object.shape), "");
    if (!wanted) continue;
    const Field value = field.at(key, describeDimensions(object.shape));
    if (std::string(key) == "radius") object.radius_m = value.number(positiveUpTo(1.0, "m"));
    if (std::string(key) == "length") object.length_m = value.number(positiveUpTo(10.0, "m"));
    if (std::string(key) == "size") object.size_m = value.vector3(positiveUpTo(10.0, "m"), "[x, y, z] edge lengths");
  }
}

// objects[].texture and texture_tile: a relief map on a box's faces or a ball's bump map (issue 29).
ObjectTexture parseObjectTexture(const Field& field, const SceneObject& object) {
  const Field texture = *field.find("texture");
  if (object.shape != Shape::Box && object.shape != Shape::Sphere)
    texture.fail("only a box or a sphere carries a texture", "no texture on a " + std::string(toString(object.shape)), "");
  ObjectTexture out;
  out.tile_m = object.shape == Shape::Box ? object.size_m.maxCoeff() : mesh::ballFaceArc(object.radius_m);
  const auto params = texture.find("params");
  const auto extent = params ? params->find("extent") : std::nullopt;
  if (auto tile = field.find("texture_tile"))
    out.tile_m = tile->number(positiveUpTo(10.0, "m"));
  else if (extent)
    out.tile_m = extent->number(positiveUpTo(10.0, "m"));
  // A generated texture spans one tile of the face, as the surface's spans surface.size.
  Surface face;
  face.size_m = Eigen::Vector2d::Constant(out.tile_m);
  out.source = parseTexture(texture, face, "texture_tile");
  return out;
}

SceneObject parseObject(const Field& field) {
  field.expectKeys({"name", "shape", "radius", "size", "length", "mass", "material", "position", "rpy_deg", "velocity",
                    "angular_velocity", "fixed", "texture", "texture_tile"});
  if (field.isNull()) field.fail("missing value", "a mapping with name, shape, its dimensions, mass and position");
  SceneObject object;
  object.name = field.at("name", "a unique object name").text();
  object.shape = field.at("shape", "one of: sphere, box, capsule, cylinder")
                     .choice<Shape>({{"sphere", Shape::Sphere},
                                     {"box", Shape::Box},
                                     {"capsule", Shape::Capsule},
                                     {"cylinder", Shape::Cylinder}});
  parseDimensions(field, object);
  if (auto f = field.find("fixed")) object.fixed = f->choice<bool>({{"false", false}, {"true", true}});
  if (object.fixed) {
    // A fixed obstacle never moves: a mass or a velocity would mean nothing.
    for (const char* key : {"mass", "velocity", "angular_velocity"})
      if (auto f = field.find(key))
        f->fail("does not apply to a fixed object", "no " + std::string(key) + " with fixed: true", "");
  } else {
    object.mass_kg = field.at("mass", "kilograms (or fixed: true for a static obstacle)")
                         .number(positiveUpTo(1000.0, "kg"));
  }
  object.material = *findMaterial("steel");
  if (auto m = field.find("material")) object.material = parseMaterial(*m);
  object.pose.position_m = field.at("position", "[x, y, z] in metres").vector3(closedRange(-100.0, 100.0, "m"));
  if (auto r = field.find("rpy_deg"))
    object.pose.rpy_deg = r->vector3(closedRange(-360.0, 360.0, "deg"), "[roll, pitch, yaw]");
  if (auto v = field.find("velocity")) object.velocity_m_per_s = v->vector3(closedRange(-100.0, 100.0, "m/s"));
  if (auto w = field.find("angular_velocity"))
    object.angular_velocity_rad_per_s = w->vector3(closedRange(-1000.0, 1000.0, "rad/s"));
  if (field.find("texture")) {
    object.texture = parseObjectTexture(field, object);
  } else if (auto tile = field.find("texture_tile")) {
    tile->fail("a texture tile without a texture", "texture: {generator: KIND, ...} or {file: PATH} beside it", "");
  }
  return object;
}

}  // namespace

std::vector<SceneObject> parseObjects(const std::optional<Field>& field, const Surface& surface) {
  std::vector<SceneObject> objects;
  if (!field) return objects;
  const std::vector<Field> items = field->items();
  const Eigen::Isometry3d world_to_plane = toIsometry(surface.pose).inverse();
  for (std::size_t i = 0; i < items.size(); ++i) {
    SceneObject object = parseObject(items[i]);
    for (std::size_t j = 0; j < objects.size(); ++j)
      if (objects[j].name == object.name)
        items[i].find("name")->fail("duplicate object name (also objects[" + std::to_string(j) + "], line " +
                                        std::to_string(items[j].find("name")->location().line) + ")",
                                    "a name no other object uses");
    // Below the plane is a mistake on a plane surface; on a mesh (a bowl's inside) it is normal.
    const double height = (world_to_plane * object.pose.position_m).z();
    if (height < 0.0 && !surface.mesh)
      items[i]
          .find("position")
          ->warn("object '" + object.name + "' starts " + formatNumber(-height) + " m below the surface plane");
    objects.push_back(std::move(object));
  }
  return objects;
}

}  // namespace thx::scene::detail
