// hapticd on a scene whose surface is a textured mesh (surface.mesh; issue 28), as a user runs it
// (separate processes, lock-step): the shipped bowl of bricks is stroked with contact and no fault;
// its recorded contacts say where on the mesh they are (triangle, barycentric coordinates, tangent
// frame) and the recording replays with the same contacts; a script that presses beside the
// mesh, the paper's loop and a mesh over its bound are refused by name.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <fstream>

#include "server/session_log.hpp"
#include "tests/support/hapticd_harness.hpp"

namespace test_hapticd_mesh_scene {

using thx_msgs::contact_t;

namespace {

class HapticdMeshScene : public thx::test::HapticdProcessTest {
 protected:
  thx::test::ProcRun hapticd(const std::string& args) {
    return run(args + " --lockstep --no-lcm --no-mlock --flight-dir '" + path("") + "'");
  }
  std::string writeScene(const std::string& name, const std::string& text) {
    const std::string file = path(name + ".yaml");
    std::ofstream(file) << text;
    return file;
  }
};

Eigen::Vector3d v3(const double (&a)[3]) { return {a[0], a[1], a[2]}; }

const char* kBowlSurface =
    "version: 1\nname: bowl\nsurface:\n  size: [0.04, 0.04]\n"
    "  texture: {generator: bricks, size: 64, params: {extent: 0.04}}\n"
    "  pose: {position: [0, 0, -0.04]}\n";

}  // namespace

TEST_F(HapticdMeshScene, TheBowlOfBricksIsStrokedWithContactNoFaultAndReplays) {
  const thx::test::ProcRun r = hapticd("--scene scenes/brick_bowl.yaml --stats-json '" + path("s.json") +
                                       "' --record '" + path("rec.lcm") + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string json = thx::test::slurp(path("s.json"));
  EXPECT_EQ(thx::test::jsonNumber(json, "faults"), 0) << json;
  EXPECT_GT(thx::test::jsonNumber(json, "contact_ticks"), 3000) << json;
  EXPECT_LT(thx::test::jsonNumber(json, "max_force_n"), 4.0) << json;

  // The bowl at 128 segments has 27,392 triangles (scene-info).
  const std::vector<contact_t> rec = thx::srv::loadSessionContacts(path("rec.lcm"));
  std::size_t in_contact = 0, away = 0;
  for (const contact_t& c : rec) {
    if (c.in_contact) {
      ++in_contact;
      ASSERT_GE(c.triangle, 0) << "tick " << c.tick;
    }
    if (c.triangle < 0) {  // no face holds the pen: no place on the mesh, no frame
      ++away;
      EXPECT_EQ(c.triangle, -1) << "tick " << c.tick;
      EXPECT_EQ(v3(c.n_geom_world).norm() + v3(c.tangent_world).norm(), 0.0) << "tick " << c.tick;
      continue;
    }
    ASSERT_LT(c.triangle, 27392) << "tick " << c.tick;
    const Eigen::Vector3d b = v3(c.barycentric), n = v3(c.n_geom_world), t = v3(c.tangent_world),
                          bt = v3(c.bitangent_world);
    EXPECT_NEAR(b.sum(), 1.0, 1e-9) << "tick " << c.tick;
    EXPECT_GE(b.minCoeff(), -1e-9) << "tick " << c.tick;
    for (const Eigen::Vector3d* axis : {&n, &t, &bt}) EXPECT_NEAR(axis->norm(), 1.0, 1e-9) << "tick " << c.tick;
    EXPECT_NEAR(n.dot(t), 0.0, 1e-9) << "tick " << c.tick;
    EXPECT_NEAR(n.dot(bt), 0.0, 1e-9) << "tick " << c.tick;
  }
  EXPECT_GT(in_contact, 3000u);
  EXPECT_GT(away, 3000u);  // the hand hovers above the rim between its steps

  // The recording replays with the same contacts, where on the mesh included.
  ASSERT_EQ(hapticd("--scene scenes/brick_bowl.yaml --device replay:'" + path("rec.lcm") + "' --record '" +
                    path("replay.lcm") + "'")
                .status,
            0);
  const std::vector<contact_t> rep = thx::srv::loadSessionContacts(path("replay.lcm"));
  ASSERT_GE(rep.size(), rec.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < rec.size(); ++i) {
    const contact_t &a = rec[i], &b = rep[i];
    if (a.in_contact != b.in_contact || a.triangle != b.triangle || a.f_normal != b.f_normal ||
        v3(a.barycentric) != v3(b.barycentric) || v3(a.tangent_world) != v3(b.tangent_world))
      ++differing;
  }
  EXPECT_EQ(differing, 0u) << "of " << rec.size() << " ticks";
}

TEST_F(HapticdMeshScene, WhatAMeshSceneCannotDoIsRefusedByName) {
  // A press beside the bowl (12 cm across): nothing under it to press on.
  const std::string beside = writeScene(
      "beside", std::string(kBowlSurface) +
                    "  mesh: {generator: bowl, size: 0.06, segments: 32}\ndevice:\n  script:\n"
                    "    - hold: {duration: 0.1}\n    - press: {position: [0.08, 0.0], force: 1.0, duration: 0.2}\n");
  thx::test::ProcRun r = hapticd("--scene '" + beside + "'");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("device.script[1]: no part of the mesh lies under [0.08, 0]"), std::string::npos) << r.err;

  r = hapticd("--scene scenes/brick_bowl.yaml --paper-loop");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--paper-loop"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("surface.mesh"), std::string::npos) << r.err;

  const std::string big =
      writeScene("big", std::string(kBowlSurface) + "  mesh: {generator: bowl, size: 0.06, max_triangles: 1000}\n");
  r = hapticd("--scene '" + big + "'");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("big.yaml:7:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("more than the limit of 1000"), std::string::npos) << r.err;
}

}  // namespace test_hapticd_mesh_scene
