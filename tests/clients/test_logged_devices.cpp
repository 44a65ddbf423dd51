// A recorded session's device-tagged messages as the offline replays take them
// (thx_client/logged_devices.hpp, docs/clients.md §3.4): a log whose hellos name one device, or
// that has no hello, is that device's whole, whatever its `device` fields hold (hapticd's
// recorder left them unset); a log of several devices gives the followed device's only; an index
// the log does not have is an error naming the log, the index and the recorded names.
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <string>
#include <utility>
#include <vector>
#include <thx_msgs/log_reader.hpp>
#include <thx_msgs/protocol.hpp>

#include "base/error.hpp"
#include "tests/clients/device_messages.hpp"
#include "tests/support/error_text.hpp"
#include "tests/support/temp_dir.hpp"
#include "thx_client/logged_devices.hpp"

namespace test_logged_devices {

using thx::client::LoggedDevice;
using thx::client::loggedDevice;

namespace {

// Writes a log: a hello naming `device_names` (none when null), then ticks 0..2 of every device
// index in `tagged`, as a recorder tags them.
void writeLog(const std::string& path, const char* device_names, const std::vector<int>& tagged) {
  lcm::LogFile log(path, "w");
  ASSERT_TRUE(log.good());
  std::int64_t eventnum = 0;
  auto write = [&](const std::string& channel, const auto& m) {
    std::vector<std::uint8_t> bytes(std::size_t(m.getEncodedSize()));
    m.encode(bytes.data(), 0, int(bytes.size()));
    lcm::LogEvent e{};
    e.eventnum = eventnum++;
    e.timestamp = 1000 * eventnum;
    e.channel = channel;
    e.datalen = std::int32_t(bytes.size());
    e.data = bytes.data();
    ASSERT_EQ(log.writeEvent(&e), 0);
  };
  if (device_names) {
    thx_msgs::hello_t h{};
    h.seq = 1;
    h.server_instance = 5;
    h.server_name = "hapticd@rec";
    h.device_names = device_names;
    write(thx_msgs::kChannelHello, h);
  }
  for (std::int64_t tick = 0; tick < 3; ++tick)
    for (int device : tagged) write("THX_DEVICE_STATE", thx::test::deviceState(device, tick));
}

using Taken = std::vector<std::pair<int, std::int64_t>>;

// The (device field, tick) of every state `pen` takes from the log, in log order.
Taken taken(const std::string& path, const LoggedDevice& pen) {
  Taken out;
  thx_msgs::forEachLogMessage<thx_msgs::device_state_t>(
      path, "THX_DEVICE_STATE", [&](const thx_msgs::device_state_t& s, const thx_msgs::LogPosition&) {
        if (pen.takes(s.device)) out.emplace_back(s.device, s.tick);
      });
  return out;
}

}  // namespace

TEST(LoggedDevices, AOneDeviceSessionIsTakenWholeWhateverItsDeviceFieldsHold) {
  thx::test::TempDir dir("thx_logged_devices");
  // 7: an unset field, as hapticd's recorder wrote it; the hello names one device.
  writeLog(dir.file("one.lcm"), "Phantom0", {7});
  const LoggedDevice pen = loggedDevice(dir.file("one.lcm"), 0);
  EXPECT_TRUE(pen.every);
  EXPECT_EQ(taken(dir.file("one.lcm"), pen), (Taken{{7, 0}, {7, 1}, {7, 2}}));
  writeLog(dir.file("no_hello.lcm"), nullptr, {3});  // a session written without a hello
  EXPECT_TRUE(loggedDevice(dir.file("no_hello.lcm"), 0).every);
}

TEST(LoggedDevices, ASessionOfTwoDevicesGivesTheFollowedDevicesOnly) {
  thx::test::TempDir dir("thx_logged_devices");
  writeLog(dir.file("two.lcm"), "left,right", {0, 1});
  const LoggedDevice left = loggedDevice(dir.file("two.lcm"), 0);
  EXPECT_FALSE(left.every);
  EXPECT_EQ(taken(dir.file("two.lcm"), left), (Taken{{0, 0}, {0, 1}, {0, 2}}));
  EXPECT_EQ(taken(dir.file("two.lcm"), loggedDevice(dir.file("two.lcm"), 1)), (Taken{{1, 0}, {1, 1}, {1, 2}}));
}

TEST(LoggedDevices, AnIndexTheSessionDoesNotHaveNamesTheLogAndItsDevices) {
  thx::test::TempDir dir("thx_logged_devices");
  writeLog(dir.file("two.lcm"), "left,right", {0, 1});
  EXPECT_EQ(thx::test::errorOf([&] { loggedDevice(dir.file("two.lcm"), 2); }),
            dir.file("two.lcm") + ": device 2 is not one of hapticd@rec's 2 devices: 0 left, 1 right (hello_t.device_names)");
  writeLog(dir.file("one.lcm"), "Phantom0", {0});
  EXPECT_EQ(thx::test::errorOf([&] { loggedDevice(dir.file("one.lcm"), 1); }),
            dir.file("one.lcm") + ": device 1 is not one of hapticd@rec's 1 device: 0 Phantom0 (hello_t.device_names)");
}

}  // namespace test_logged_devices
