#include "scenes/scene.hpp"

namespace thx::scene {

const char* toString(DeviceType type) {
  switch (type) {
    case DeviceType::Sim:
      return "sim";
    case DeviceType::Vrpn:
      return "vrpn";
  }
  return "?";
}

const char* toString(Shape shape) {
  switch (shape) {
    case Shape::Sphere:
      return "sphere";
    case Shape::Box:
      return "box";
    case Shape::Capsule:
      return "capsule";
    case Shape::Cylinder:
      return "cylinder";
  }
  return "?";
}

const char* toString(SlabSupport held) { return held == SlabSupport::Free ? "free" : "edges"; }

}  // namespace thx::scene
