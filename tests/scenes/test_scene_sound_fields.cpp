// The scene fields the audio client analyses (docs/scenes.md): the surface slab's thickness, how
// it is held, its roughness; the pen (device.pen); the scene's own materials.
#include <gtest/gtest.h>

#include <ostream>
#include <string>
#include <vector>

#include "scenes/scene_loader.hpp"

namespace test_scene_sound_fields {

namespace {

using namespace thx::scene;

const std::string kHead = R"(version: 1
name: sound
)";

std::string surfaceWith(const std::string& extra) {
  return "surface:\n  size: [0.2, 0.2]\n  texture: {generator: bricks}\n" + extra;
}

// The error's full message, or "" when the scene loads.
std::string errorOf(const std::string& text) {
  try {
    parseScene(kHead + text, "s.yaml", "");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

// The slab's and the pen's fields as one comparable row.
struct SoundFields {
  double thickness;
  SlabSupport held;
  double beta, amplitude, spacing;
  double pen_radius, pen_length;
  std::string pen_material;
  double pen_tilt;
  bool operator==(const SoundFields&) const = default;
};

void PrintTo(const SoundFields& f, std::ostream* os) {
  *os << f.thickness << " " << toString(f.held) << " " << f.beta << " " << f.amplitude << " " << f.spacing << " "
      << f.pen_radius << " " << f.pen_length << " " << f.pen_material << " " << f.pen_tilt;
}

SoundFields soundFields(const Scene& s) {
  const Roughness& r = s.surface.roughness;
  const Pen& p = s.device.pen;
  return {s.surface.thickness_m, s.surface.held, r.beta, r.amplitude, r.spacing_m, p.radius_m, p.length_m,
          p.material.name, p.tilt_deg};
}

TEST(SceneSoundFields, DefaultsWhenLeftOut) {
  const Scene s = parseScene(kHead + surfaceWith(""), "s.yaml", "");
  EXPECT_EQ(soundFields(s), (SoundFields{0.01, SlabSupport::Free, 1.0, 0.03, 1e-5, 0.005, 0.12, "plastic", 30.0}));
  EXPECT_TRUE(s.custom_materials.empty());
  EXPECT_FALSE(s.audio.mute);
}

// audio.mute: how a study removes the sound by a scene switch (docs/scenes.md, audio).
TEST(SceneSoundFields, AudioMuteArrives) {
  EXPECT_TRUE(parseScene(kHead + "audio: {mute: true}\n" + surfaceWith(""), "s.yaml", "").audio.mute);
  EXPECT_FALSE(parseScene(kHead + "audio:\n  mute: false\n" + surfaceWith(""), "s.yaml", "").audio.mute);
  EXPECT_FALSE(parseScene(kHead + "audio: {}\n" + surfaceWith(""), "s.yaml", "").audio.mute);
}

TEST(SceneSoundFields, EveryValueArrives) {
  const Scene s = parseScene(kHead + R"(materials:
  - {name: oak, density: 700, youngs_modulus: 1.2e10, poisson_ratio: 0.3, rayleigh_alpha: 50, rayleigh_beta: 1e-6,
     friction: 0.4, restitution: 0.3}
)" + surfaceWith(R"(  material: oak
  thickness: 0.02
  held: edges
  roughness: {beta: 1.5, amplitude: 0.05, spacing: 2e-5}
device:
  pen: {radius: 0.004, length: 0.15, material: aluminium, tilt_deg: 45}
objects:
  - {name: ball, shape: sphere, radius: 0.01, mass: 0.01, material: oak, position: [0, 0, 0.01]}
)"),
                               "s.yaml", "");
  ASSERT_EQ(s.custom_materials.size(), 1u);
  const Material& oak = s.custom_materials[0];
  const std::vector<double> values = {oak.density_kg_per_m3, oak.youngs_modulus_pa, oak.poisson_ratio,
                                      oak.rayleigh_alpha_per_s, oak.rayleigh_beta_s, oak.friction, oak.restitution};
  EXPECT_EQ(values, (std::vector<double>{700, 1.2e10, 0.3, 50, 1e-6, 0.4, 0.3}));
  EXPECT_EQ(oak.name, "oak");
  // Used by name like the table's, by the surface and by an object.
  EXPECT_EQ(s.surface.material.name, "oak");
  EXPECT_EQ(s.surface.material.youngs_modulus_pa, 1.2e10);
  EXPECT_EQ(s.objects.at(0).material.name, "oak");
  EXPECT_EQ(soundFields(s), (SoundFields{0.02, SlabSupport::ClampedEdges, 1.5, 0.05, 2e-5, 0.004, 0.15, "aluminium", 45}));
}

TEST(SceneSoundFields, BadValuesNameTheFieldAndTheValue) {
  struct Case {
    std::string text;
    std::vector<std::string> contains;
  };
  const std::vector<Case> cases = {
      {surfaceWith("  thickness: -0.01\n"),
       {"s.yaml:6:14", "surface.thickness", "thickness must be positive", "(0, 1] m", "got '-0.01'"}},
      {surfaceWith("  held: glued\n"), {"surface.held", "one of: free, edges", "got 'glued'"}},
      {surfaceWith("  roughness: {beta: 5}\n"), {"surface.roughness.beta", "[0, 4]", "got '5'"}},
      {"materials:\n  - {name: jelly, density: 1000, youngs_modulus: 1e5, poisson_ratio: 0.5}\n" + surfaceWith(""),
       {"materials[0].poisson_ratio", "incompressible", "(-1, 0.5)", "got '0.5'"}},
      {"materials:\n  - {name: steel, density: 1000, youngs_modulus: 1e5, poisson_ratio: 0.3}\n" + surfaceWith(""),
       {"materials[0].name", "already in the materials table", "got 'steel'"}},
      {"materials:\n  - {name: x, density: 1, youngs_modulus: 1, poisson_ratio: 0.3}\n"
       "  - {name: x, density: 1, youngs_modulus: 1, poisson_ratio: 0.3}\n" +
           surfaceWith(""),
       {"materials[1].name", "defined twice"}},
      {"materials:\n  - {name: x, density: -1, youngs_modulus: 1, poisson_ratio: 0.3}\n" + surfaceWith(""),
       {"materials[0].density", "(0, 1e+05] kg/m^3", "got '-1'"}},
      {"materials:\n  - {name: x, density: 1, poisson_ratio: 0.3}\n" + surfaceWith(""),
       {"materials[0].youngs_modulus", "missing"}},
      {surfaceWith("  material: oak\n"), {"surface.material", "unknown material", "got 'oak'"}},
      {surfaceWith("device:\n  pen: {radius: 0.01, length: 0.01}\n"),
       {"device.pen", "shorter than it is wide", "length >= 2 x radius"}},
      {surfaceWith("device:\n  pen: {tilt_deg: 90}\n"), {"device.pen.tilt_deg", "[0, 89] deg", "got '90'"}},
      {surfaceWith("device:\n  pen: {shape: cone}\n"), {"device.pen.shape", "unknown field"}},
      {"audio: {mute: 1}\n" + surfaceWith(""), {"s.yaml:3:", "audio.mute", "one of: false, true", "got '1'"}},
      {"audio: {mute: yes please}\n" + surfaceWith(""), {"audio.mute", "got 'yes please'"}},
      {"audio: {gain: 0}\n" + surfaceWith(""), {"audio.gain", "unknown field"}},
      {"audio: true\n" + surfaceWith(""), {"audio", "mapping"}},
  };
  for (const Case& c : cases) {
    const std::string message = errorOf(c.text);
    ASSERT_FALSE(message.empty()) << c.text;
    for (const std::string& part : c.contains) EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

TEST(SceneSoundFields, CustomMaterialsStandBesideTheTable) {
  // Named before the table's in the unknown-material list, so a typo suggests it.
  const std::string message = errorOf("materials:\n  - {name: walnut, density: 650, youngs_modulus: 1e10, poisson_ratio: 0.3}\n" +
                                      surfaceWith("  material: walnit\n"));
  EXPECT_NE(message.find("did you mean 'walnut'?"), std::string::npos) << message;
  EXPECT_NE(message.find("copper, walnut"), std::string::npos) << message;
}

}  // namespace

}  // namespace test_scene_sound_fields
