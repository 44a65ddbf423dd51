// The hard cases of a textured mesh under the simulated PHANToM, wired as hapticd wires a mesh
// scene (in-process, lock-step; issue 28): V-grooves around a cylinder, the inside corner of a
// room, a 1 mm plate pressed at the device's peak force, and strokes grazing a sphere's
// silhouette. What each asserts is behaviour (no fault of the loop, the plate never pushed
// through, the corner's three faces held, the pen resting in a groove); how much the passivity
// controller and the safety stage acted is printed as [measured] (docs/meshes.md "Hard cases").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>

#include "device/sim_phantom.hpp"
#include "scenes/scene_loader.hpp"
#include "server/mesh_scene.hpp"
#include "server/prepared_scene.hpp"
#include "server/scene_device.hpp"
#include "server/servo_rig.hpp"
#include "tests/support/temp_dir.hpp"

namespace test_mesh_hard_cases {

using namespace thx;

namespace {

// A mesh scene as hapticd builds it: the mesh, the hand's heights, the simulated device, the
// prepared scene and the servo rig on its mesh renderer.
class MeshCase {
 public:
  MeshCase(const test::TempDir& dir, const std::string& name, const std::string& yaml) : path_(dir.file(name + ".yaml")) {
    std::ofstream(path_) << yaml;
    scene_ = scene::loadScene(path_);
    mesh_ = srv::buildMeshGeometry(scene_);
    height_ = srv::handSurfaceFor(scene_, *mesh_);
    srv::checkScriptOnMesh(scene_, *height_);
    device_ = srv::makeSceneDevice(scene_, "", "", /*lockstep=*/true, height_.get());
    prepared_ = srv::prepareScene(scene_, path_, {device_.device->spec()}, srv::ScenePolicy{}, mesh_);
    rig_ = std::make_unique<srv::ServoRig>(*device_.device, prepared_->surface.surface, prepared_->devices[0].wiring,
                                           prepared_->devices[0].mesh_renderer.get());
    device_.device->open();
  }
  ~MeshCase() { device_.device->close(); }

  // The whole script and 0.3 s after it, each tick's record to `on_tick`.
  void run(const std::function<void(const srv::TickRecord&)>& on_tick) {
    const auto ticks = std::int64_t((device_.sim->script().duration() + 0.3) * scene_.rates.servo_hz);
    for (std::int64_t k = 0; k < ticks; ++k) on_tick(rig_->tickAndDrain());
  }
  void report(const char* what) const {
    const srv::ServoCounters& c = rig_->servo().counters();
    std::printf("[measured] %-22s %llu ticks, %llu in contact, largest force %.2f N, passivity controller active in %llu ticks,"
                " faults %llu\n",
                what, (unsigned long long)c.ticks, (unsigned long long)c.contact_ticks, c.max_force_n,
                (unsigned long long)rig_->passivity().activeTicks(), (unsigned long long)c.faults);
  }
  const srv::Servo& servo() const { return rig_->servo(); }
  const Eigen::Isometry3d& meshToWorld() const { return mesh_->scene_mesh.mesh_to_world; }

 private:
  std::string path_;
  scene::Scene scene_;
  std::shared_ptr<const srv::MeshGeometry> mesh_;
  std::unique_ptr<srv::MeshSurfaceHeight> height_;
  srv::SceneDevice device_;
  std::unique_ptr<srv::PreparedScene> prepared_;
  std::unique_ptr<srv::ServoRig> rig_;
};

Eigen::Vector3d v3(const double (&a)[3]) { return {a[0], a[1], a[2]}; }

// The scene's head: a 2 cm texture tile and the mesh; then the device with `script` (YAML lines).
std::string sceneText(const std::string& mesh, const std::string& texture, const std::string& script,
                      const std::string& surface_pose = "{position: [0, 0, -0.03]}") {
  return "version: 1\nname: hard case\nsurface:\n  size: [0.02, 0.02]\n  pose: " + surface_pose + "\n  mesh: " + mesh +
         "\n  texture: " + texture +
         "\ndevice:\n  type: sim\n  model: phantom_desktop\n  stiffness_fraction: 0.6\n  damping: 1.0\n  script:\n" + script;
}

constexpr std::uint32_t kLoopFaults = srv::kFaultInvalidReading | srv::kFaultMissedTicks | srv::kFaultNonFiniteForce;

}  // namespace

// 90° V-grooves 1 mm deep along a cylinder's axis, the cylinder on its side: a press into the
// groove under the top, then a stroke round the tube across a dozen grooves. At the press the pen
// rests on the groove's floor with both walls held, as on the plane.
TEST(MeshHardCases, VGroovesAroundACylinder) {
  const test::TempDir dir("mesh_hard_grooves");
  // Valleys every 2.09 mm around (9 tiles of 10 periods on the 3 cm radius); one lies on the top
  // line, u = 4.5 tiles round from the seam.
  MeshCase c(dir, "grooves",
             sceneText("{generator: cylinder, size: 0.03, segments: 96, pose: {position: [-0.03, 0, 0], rpy_deg: [0, 90, 0]}}",
                       "{generator: vvalley, size: 400, params: {extent: 0.02, angle_deg: 90, period: 0.002}}",
                       "    - hold: {duration: 0.2}\n"
                       "    - press: {position: [0.0, 0.0], force: 1.0, duration: 0.8}\n"
                       "    - stroke: {from: [0.0, -0.012], to: [0.0, 0.012], speed: 0.03, force: 1.0}\n"));
  std::uint32_t loop_faults = 0;
  int resting = 0, two_walls = 0;
  double lateral_at_rest = 0.0;
  std::int64_t k = 0;
  c.run([&](const srv::TickRecord& r) {
    loop_faults |= r.faults & kLoopFaults;
    // The press's last 0.3 s (device time 1.0-1.3 s: a 0.2 s hold, the 0.2 s descent, the 0.1 s
    // push ramp, then 0.8 s of press).
    if (r.in_contact && k >= 1000 && k < 1300) {
      ++resting;
      if (r.num_planes >= 2) ++two_walls;
      lateral_at_rest = std::max(lateral_at_rest, std::fabs(r.f_out[1]));
    }
    ++k;
  });
  c.report("V-grooves, cylinder");
  EXPECT_EQ(loop_faults, 0u);
  ASSERT_GT(resting, 250);
  EXPECT_EQ(two_walls, resting);  // both walls of the groove held throughout the rest
  EXPECT_LT(lateral_at_rest, 0.3);  // at the floor: the walls' pushes cancel (1 N down, 45° walls)
  EXPECT_GT(c.servo().counters().contact_ticks, 1500u);
}

// The inside corner of a room turned so that the corner points down: a press on its axis pushes
// the pen into the corner, where three faces meet at right angles and all three hold it.
TEST(MeshHardCases, InsideCornerOfARoom) {
  const test::TempDir dir("mesh_hard_corner");
  // rpy [45, -35.26, 0] takes the room's (1, 1, 1) diagonal to +z: its (-, -, -) corner lowest.
  MeshCase c(dir, "corner",
             sceneText("{generator: room, size: 0.02, segments: 64, pose: {rpy_deg: [45, -35.26438968, 0]}}",
                       "{generator: bricks, size: 128, params: {extent: 0.02, brick_length: 0.01, brick_height: 0.005, mortar: 0.001, mortar_depth: 0.0004}}",
                       "    - hold: {duration: 0.2}\n"
                       "    - press: {position: [0.0, 0.0], force: 1.0, duration: 1.0}\n",
                       "{position: [0, 0, 0.0]}"));
  std::uint32_t loop_faults = 0;
  int three_faces = 0, pressed = 0;
  Eigen::Vector3d f_rest = Eigen::Vector3d::Zero();
  c.run([&](const srv::TickRecord& r) {
    loop_faults |= r.faults & kLoopFaults;
    if (r.in_contact && r.f_normal_n > 0.5) {
      ++pressed;
      if (r.num_planes == 3) ++three_faces;
      f_rest = v3(r.f_out);
    }
  });
  c.report("inside corner, room");
  std::printf("[measured] inside corner: three faces held in %d of %d pressed ticks\n", three_faces, pressed);
  EXPECT_EQ(loop_faults, 0u);
  ASSERT_GT(pressed, 300);
  EXPECT_GT(three_faces, pressed * 9 / 10);
  // Held in the corner, the force holds the hand's push: along the corner's axis, up.
  EXPECT_GT(f_rest.z(), 0.5);
  EXPECT_LT(f_rest.head<2>().norm(), 0.25 * f_rest.z());
}

// A 1 mm plate pressed from above at the device's peak force (7.9 N for 0.1 s): the pen goes far
// below the plate, and every contact stays on the top face, its force pushing up (the god object
// stays on the side the pen came from). The safety stage's continuous-force budget runs out, as
// it does for the same press on the plane: the device cannot sustain 7.9 N (docs/stability.md,
// cannot-hold), and the hand pushes the pen on down; a fault of the safety stage, not of the loop.
TEST(MeshHardCases, ThinPlateAtThePeakForce) {
  const test::TempDir dir("mesh_hard_plate");
  MeshCase c(dir, "plate",
             sceneText("{generator: plate, size: 0.02, segments: 64}", "{generator: sine, size: 128, params: {extent: 0.02, amplitude: 0.0001, period: 0.005}}",
                       "    - hold: {duration: 0.2}\n"
                       "    - press: {position: [0.004, -0.003], force: 7.9, duration: 0.1}\n"));
  std::uint32_t loop_faults = 0, faults = 0;
  double deepest = 0.0, least_up = 1e9, least_normal_z = 1.0;
  int in_contact = 0;
  const double top_world = c.meshToWorld().translation().z() + 0.0005;
  c.run([&](const srv::TickRecord& r) {
    loop_faults |= r.faults & kLoopFaults;
    faults |= r.faults;
    if (!r.in_contact) return;
    ++in_contact;
    deepest = std::max(deepest, top_world - r.p_world[2]);
    least_up = std::min(least_up, r.f_render[2]);
    least_normal_z = std::min(least_normal_z, r.n_geom_world[2]);
  });
  c.report("thin plate, 7.9 N");
  std::printf("[measured] thin plate: the pen %.1f mm below the top face at most (the plate is 1 mm thick)\n", deepest * 1e3);
  EXPECT_EQ(loop_faults, 0u);
  EXPECT_EQ(faults & srv::kFaultForceBudget, srv::kFaultForceBudget);  // 7.9 N is beyond what the device sustains
  ASSERT_GT(in_contact, 300);
  EXPECT_GT(deepest, 0.005);          // far below the plate's bottom face,
  EXPECT_GE(least_up, 0.0);           // and the force never pushed it down:
  EXPECT_GT(least_normal_z, 0.999);   // every contact on the top face
}

// Strokes along a sphere's side where its surface is 72° to 79° from level (the pole turned away
// so the texture is not squeezed there), the hand pushing down: the pen is pressed hard against a
// steep wall and slides. No fault of the loop, the force within the device's peak.
TEST(MeshHardCases, StrokesGrazingASpheresSilhouette) {
  const test::TempDir dir("mesh_hard_silhouette");
  MeshCase c(dir, "silhouette",
             sceneText("{generator: sphere, size: 0.03, segments: 96, pose: {rpy_deg: [0, 90, 0]}}",
                       "{generator: pebbles, size: 256, params: {extent: 0.02, spacing: 0.004, radius: 0.0015, height: 0.0003}}",
                       "    - hold: {duration: 0.2}\n"
                       "    - stroke: {from: [-0.008, 0.0285], to: [0.008, 0.0285], speed: 0.03, force: 0.5}\n"
                       "    - stroke: {from: [0.0, 0.02], to: [0.0, 0.0295], speed: 0.02, force: 0.5}\n"));
  std::uint32_t loop_faults = 0;
  double largest = 0.0;
  c.run([&](const srv::TickRecord& r) {
    loop_faults |= r.faults & kLoopFaults;
    largest = std::max(largest, v3(r.f_out).norm());
  });
  c.report("silhouette, sphere");
  EXPECT_EQ(loop_faults, 0u);
  EXPECT_GT(c.servo().counters().contact_ticks, 500u);
  EXPECT_LE(largest, 7.9 + 1e-9);
}

}  // namespace test_mesh_hard_cases
