// Device addresses and the mode-A connection request (docs/vrpn.md §1), including the captured
// request datagram byte-exact both ways.
#include <gtest/gtest.h>

#include "device/vrpn/addressing.hpp"
#include "tests/vrpn/transcripts.hpp"

namespace test_addressing {

using namespace thx::vrpn;
using thx::vrpn::transcript::hex;
namespace tx = thx::vrpn::transcript;

namespace {

DeviceAddress addr(std::string device, std::string host, std::uint16_t port, ConnectMode mode) {
  return DeviceAddress{std::move(device), std::move(host), port, mode};
}

}  // namespace

TEST(Addressing, LocationForms) {
  using enum ConnectMode;
  const std::vector<std::pair<std::string, DeviceAddress>> cases = {
      {"Phantom0@localhost", addr("Phantom0", "localhost", 3883, kUdpLob)},
      {"Phantom0@10.0.0.2:38830", addr("Phantom0", "10.0.0.2", 38830, kUdpLob)},
      {"Phantom0@x-vrpn://host:4000", addr("Phantom0", "host", 4000, kUdpLob)},
      {"Phantom0@tcp://127.0.0.1:38830", addr("Phantom0", "127.0.0.1", 38830, kTcp)},
      {"Phantom0@tcp:127.0.0.1:38830", addr("Phantom0", "127.0.0.1", 38830, kTcp)},
      {"Phantom0@tcp://host", addr("Phantom0", "host", 3883, kTcp)},
      // Name before the first '@', location after the last.
      {"Dev@ice@host:1", addr("Dev", "host", 1, kUdpLob)},
  };
  for (const auto& [text, expected] : cases) {
    Result<DeviceAddress> a = parseDeviceAddress(text);
    ASSERT_TRUE(a) << text << ": " << a.error().reason;
    EXPECT_EQ(*a, expected) << text;
  }
}

TEST(Addressing, RefusedAddresses) {
  for (const char* text : {"Phantom0", "@host", "Phantom0@", "Phantom0@:3883", "Phantom0@host:", "Phantom0@host:0",
                           "Phantom0@host:65536", "Phantom0@host:12a", "Phantom0@host:-5", "Phantom0@tcp://",
                           "Phantom0@file:/tmp/log.vrpn", "Phantom0@x-vrsh://host/bin/server"}) {
    Result<DeviceAddress> a = parseDeviceAddress(text);
    ASSERT_FALSE(a) << text;
    EXPECT_EQ(a.error().code, ErrorCode::kBadAddress);
  }
}

TEST(Addressing, CapturedLobRequestBothWays) {
  const auto captured = hex(tx::kLobRequest);
  EXPECT_EQ(encodeLobRequest("127.0.0.1", 33309), captured);
  Result<LobRequest> r = parseLobRequest(captured);
  ASSERT_TRUE(r) << r.error().reason;
  EXPECT_EQ(*r, (LobRequest{"127.0.0.1", 33309}));
}

TEST(Addressing, LobRequestChecks) {
  auto bytes = [](std::string s) { return std::vector<std::uint8_t>(s.begin(), s.end()); };
  EXPECT_TRUE(parseLobRequest(bytes("myhost 1024")));  // NUL missing: the text ends with the datagram
  EXPECT_TRUE(parseLobRequest(bytes(std::string("h 2000\0junk", 11))));
  for (std::string bad : {"", "127.0.0.1", "127.0.0.1 1023", "127.0.0.1 65536", "127.0.0.1  4000", "127.0.0.1 40x0",
                          "host-name 4000", "127.0.0.1:4000", " 4000", "127.0.0.1 "}) {
    Result<LobRequest> r = parseLobRequest(bytes(bad));
    ASSERT_FALSE(r) << "'" << bad << "'";
    EXPECT_EQ(r.error().code, ErrorCode::kBadLobRequest);
  }
  EXPECT_FALSE(parseLobRequest(std::vector<std::uint8_t>(kMaxLobRequest + 1, '1')));
  std::string longest = std::string(kMaxLobRequest - 6, 'h') + " 4000";  // 255 bytes + NUL fits
  ASSERT_EQ(longest.size(), kMaxLobRequest - 1);
  EXPECT_TRUE(parseLobRequest(bytes(longest + '\0')));
  EXPECT_FALSE(parseLobRequest(bytes("h" + longest)));  // 256 bytes of text, no room for the NUL
}

}  // namespace test_addressing
