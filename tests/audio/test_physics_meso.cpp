// Meso impulses of the physics client's rolling objects (clients/audio/physics_meso_source.hpp):
// Eq. 5 at every texel of a contact's texel path, the walk carried across messages and restarted
// when the body loses contact, the pen's entries and object-object contacts skipped.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "clients/audio/physics_meso_source.hpp"
#include "tests/audio/live_fixtures.hpp"

namespace thx::audio {
namespace {

using Contacts = thx_msgs::physics_contacts_t;

struct VectorSink final : ExcitationSink {
  std::vector<ExcitationEvent> events;
  void push(const ExcitationEvent& e) override { events.push_back(e); }
};

constexpr double kMass = 0.0056;
constexpr double kSpeed = 0.1;

// One message: body `body` on the surface, texel columns i0..i1 of row 5, entered 1 ms apart,
// the message's last step at sim_time 1.0 s covering 10 ms, utime 5 s.
Contacts rolling(const tex::TextureMap& map, std::int32_t body, int i0, int i1, std::int32_t body_b = Contacts::BODY_SURFACE) {
  Contacts m{};
  m.utime = 5'000'000;
  m.sim_time = 1.0;
  m.window = 0.01;
  m.n_geometric_world[2] = 1.0;
  m.num_contacts = 1;
  m.body_a[0] = body;
  m.body_b[0] = body_b;
  m.mass_a[0] = kMass;
  m.path_start[0] = 0;
  for (int i = i0; i <= i1; ++i) {
    thx_msgs::physics_texel_t t{};
    t.i = i;
    t.j = 5;
    t.t = 1.0 - 0.001 * (i1 - i);
    const Eigen::Vector3f n = map.normal(i % map.width(), 5).normalized();
    t.n_world[0] = n.x(), t.n_world[1] = n.y(), t.n_world[2] = n.z();
    t.v_world[0] = kSpeed;
    m.path.push_back(t);
  }
  m.num_texels[0] = std::int32_t(m.path.size());
  m.num_path = std::int32_t(m.path.size());
  return m;
}

// Eq. 5 by hand: on a column tilted to (0.2, 0, 1), -(v . n_s) / (n_g . n_s) = -0.1 * 0.2 = -0.02 m/s.
constexpr double kTilted = -kMass * kSpeed * 0.2;

TEST(PhysicsMeso, OneImpulsePerTexelEnteredWithEquationFivesValue) {
  const tex::TextureMap map = test::grooveMap();  // even columns tilted, odd ones flat
  PhysicsMesoSource source(map, test::liveSlab().mesh, {0.2, 0.2}, 3, 2'000'000);
  VectorSink sink;
  source.physicsContacts(rolling(map, 0, 10, 14), 77, sink);  // enters 11, 12, 13, 14
  EXPECT_EQ(source.texels(), 4u);
  ASSERT_EQ(sink.events.size(), 4u);
  const double expected[4] = {-kTilted, kTilted, -kTilted, kTilted};  // 10 tilted -> 11 flat -> 12 tilted ...
  for (int k = 0; k < 4; ++k) {
    const ExcitationEvent& e = sink.events[std::size_t(k)];
    EXPECT_NEAR(e.impulse[2], expected[k], 1e-4 * std::fabs(kTilted)) << k;  // the map keeps normals in float
    EXPECT_EQ(e.impulse[0], 0.0);
    EXPECT_EQ(e.generation, 3u);
    EXPECT_EQ(e.body, 0);
    EXPECT_EQ(e.receipt_ns, 77);
    EXPECT_EQ(e.source_ns, 5'000'000'000LL);
    // Entered at 1.0 - 0.001 (3 - k) s; sounds at utime - (sim_time - t) + window + delay.
    EXPECT_EQ(e.time_ns, 5'000'000'000LL - 1'000'000LL * (3 - k) + 10'000'000 + 2'000'000) << k;
  }
  // Texel 11's centre, u = 11.5 / 64, lies nearer the node at x = -0.05 than the one at -0.1 (4 x 4 cells, Tet10 grid 0.025 m).
  const auto& node = test::liveSlab().mesh.nodes[std::size_t(sink.events[0].node)];
  EXPECT_NEAR(node.x(), (11.5 / 64 - 0.5) * 0.2, 0.0125 + 1e-12);
  EXPECT_NEAR(node.z(), 0.0, 1e-12);
}

TEST(PhysicsMeso, TheWalkGoesOnAcrossMessagesAndRestartsAfterLosingContact) {
  const tex::TextureMap map = test::grooveMap();
  PhysicsMesoSource source(map, test::liveSlab().mesh, {0.2, 0.2}, 1, 0);
  VectorSink sink;
  source.physicsContacts(rolling(map, 2, 10, 11), 0, sink);  // enters 11
  source.physicsContacts(rolling(map, 2, 11, 12), 0, sink);  // still in 11, enters 12
  EXPECT_EQ(source.texels(), 2u);
  Contacts none{};
  none.num_contacts = 0;
  source.physicsContacts(none, 0, sink);                     // lost contact
  source.physicsContacts(rolling(map, 2, 13, 14), 0, sink);  // starts anew in 13, enters 14
  EXPECT_EQ(source.texels(), 3u);
  EXPECT_EQ(sink.events.size(), 3u);
}

TEST(PhysicsMeso, PenEntriesObjectPairsAndFlatMapsGiveNone) {
  const tex::TextureMap grooves = test::grooveMap();
  PhysicsMesoSource source(grooves, test::liveSlab().mesh, {0.2, 0.2}, 1, 0);
  VectorSink sink;
  source.physicsContacts(rolling(grooves, Contacts::BODY_PEN, 10, 14), 0, sink);  // CONTACT's job
  source.physicsContacts(rolling(grooves, 0, 10, 14, /*body_b=*/1), 0, sink);      // object on object
  EXPECT_EQ(source.texels(), 0u);
  const tex::TextureMap flat(64, 64, tex::Representation::Normal);
  PhysicsMesoSource on_flat(flat, test::liveSlab().mesh, {0.2, 0.2}, 1, 0);
  on_flat.physicsContacts(rolling(flat, 0, 10, 14), 0, sink);
  EXPECT_EQ(on_flat.texels(), 4u);
  EXPECT_TRUE(sink.events.empty());  // exactly zero impulses are not sent
}

}  // namespace
}  // namespace thx::audio
