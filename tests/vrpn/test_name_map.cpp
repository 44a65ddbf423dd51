// Name <-> id maps: our ids and the peer's are separate spaces joined by name (docs/vrpn.md §5).
#include <gtest/gtest.h>

#include <string>

#include "device/vrpn/limits.hpp"
#include "device/vrpn/name_map.hpp"

namespace test_name_map {

using namespace thx::vrpn;

TEST(NameMap, LocalIdsAreDenseStableAndIdempotent) {
  NameMap m;
  EXPECT_EQ(m.addLocal("a"), 0);
  EXPECT_EQ(m.addLocal("b"), 1);
  EXPECT_EQ(m.addLocal("a"), 0);
  EXPECT_EQ(m.localCount(), 2);
  EXPECT_EQ(m.findLocal("b"), 1);
  EXPECT_EQ(m.findLocal("c"), kNoId);
  EXPECT_EQ(m.localName(1), "b");
  EXPECT_EQ(m.localName(2), "");
  EXPECT_EQ(m.localName(-1), "");
}

TEST(NameMap, LocalNameViewsSurviveGrowth) {
  NameMap m;
  m.addLocal("first name, long enough not to fit a small-string buffer");
  const std::string_view v = m.localName(0);
  for (int i = 0; i < 500; ++i) m.addLocal("name " + std::to_string(i));
  EXPECT_EQ(v, "first name, long enough not to fit a small-string buffer");
}

TEST(NameMap, InvalidNamesAreRefused) {
  NameMap m;
  EXPECT_EQ(m.addLocal(""), kNoId);
  EXPECT_EQ(m.addLocal(std::string(kMaxNameLength + 1, 'x')), kNoId);
  EXPECT_EQ(m.addLocal(std::string("a\0b", 3)), kNoId);
  EXPECT_NE(m.addLocal(std::string(kMaxNameLength, 'x')), kNoId);
}

TEST(NameMap, AtMost2000LocalNames) {
  NameMap m;
  for (int i = 0; i < kMaxNames; ++i) ASSERT_EQ(m.addLocal("n" + std::to_string(i)), i);
  EXPECT_EQ(m.addLocal("one too many"), kNoId);
  EXPECT_EQ(m.addLocal("n5"), 5);
}

TEST(NameMap, RemoteIdsJoinLocalOnesByName) {
  NameMap m;
  m.addLocal("VRPN Control");
  const std::int32_t ours = m.addLocal("vrpn_Tracker Pos_Quat");
  ASSERT_TRUE(m.defineRemote(4, "vrpn_Tracker Pos_Quat"));
  EXPECT_EQ(m.toLocal(4), ours);
  EXPECT_EQ(m.remoteName(4), "vrpn_Tracker Pos_Quat");
  EXPECT_FALSE(m.remoteDescribed(3));
  EXPECT_EQ(m.toLocal(3), kNoId);
  EXPECT_EQ(m.toLocal(-7), kNoId);
  EXPECT_EQ(m.toLocal(100000), kNoId);
}

TEST(NameMap, RemoteNameWeDoNotKnowIsDescribedButUnmapped) {
  NameMap m;
  ASSERT_TRUE(m.defineRemote(0, "vrpn_Forwarder_Brain"));
  EXPECT_TRUE(m.remoteDescribed(0));
  EXPECT_EQ(m.toLocal(0), kNoId);
  // Registering the name later completes the join.
  const std::int32_t id = m.addLocal("vrpn_Forwarder_Brain");
  EXPECT_EQ(m.toLocal(0), id);
}

TEST(NameMap, EchoIsANoOpAndRedefinitionReplaces) {
  NameMap m;
  const std::int32_t a = m.addLocal("A");
  const std::int32_t b = m.addLocal("B");
  Result<bool> first = m.defineRemote(7, "A");
  ASSERT_TRUE(first);
  EXPECT_TRUE(*first);
  Result<bool> echo = m.defineRemote(7, "A");
  ASSERT_TRUE(echo);
  EXPECT_FALSE(*echo);
  EXPECT_EQ(m.toLocal(7), a);
  ASSERT_TRUE(m.defineRemote(7, "B"));
  EXPECT_EQ(m.toLocal(7), b);
  EXPECT_EQ(m.remoteName(7), "B");
}

TEST(NameMap, RemoteIdsOutOfRangeAreErrors) {
  NameMap m;
  for (std::int32_t id : {-1, kMaxNames, 0x7fffffff}) {
    Result<bool> r = m.defineRemote(id, "x");
    ASSERT_FALSE(r) << id;
    EXPECT_EQ(r.error().code, ErrorCode::kIdOutOfRange);
  }
  EXPECT_TRUE(m.defineRemote(kMaxNames - 1, "x"));
}

}  // namespace test_name_map
