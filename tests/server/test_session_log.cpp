// Session logs (standard LCM log files) and the replay device: what is recorded comes back, the
// replay reproduces the recorded tick sequence, and bad files give errors that name the problem.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "device/device_specs.hpp"
#include "device/replay_device.hpp"
#include "server/session_log.hpp"

namespace test_session_log {

using namespace thx;
namespace fs = std::filesystem;

namespace {

std::string tempPath(const std::string& name) {
  return (fs::temp_directory_path() / ("thx_session_" + std::to_string(::getpid()) + "_" + name)).string();
}

srv::TickRecord tickAt(std::int64_t tick) {
  srv::TickRecord r;
  r.tick = tick;
  r.deadline_ns = tick * 1'000'000;
  r.p_world[0] = 0.001 * double(tick);
  r.p_world[2] = -0.0005;
  r.v_world[0] = 1.0;
  r.buttons = tick % 2 ? 1u : 0u;
  r.in_contact = tick % 3 == 0;
  r.depth_m = 1e-4 * double(tick);
  r.f_out[2] = 0.1 * double(tick);
  return r;
}

}  // namespace

TEST(SessionLog, WhatIsRecordedComesBackInOrder) {
  const std::string path = tempPath("roundtrip.lcm");
  {
    srv::SessionRecorder rec(path, true);
    for (std::int64_t t : {0, 1, 2, 5, 6}) rec.record(tickAt(t));  // ticks 3 and 4 were missed
    EXPECT_TRUE(rec.ok());
    EXPECT_EQ(rec.ticks(), 5u);
  }
  const std::vector<dev::ReplaySample> traj = srv::loadSessionTrajectory(path);
  ASSERT_EQ(traj.size(), 5u);
  EXPECT_EQ(traj[3].tick, 5);
  EXPECT_DOUBLE_EQ(traj[3].p_world.x(), 0.005);
  EXPECT_DOUBLE_EQ(traj[3].v_world.x(), 1.0);
  EXPECT_EQ(traj[3].buttons, 1u);
  const std::vector<thx_msgs::contact_t> contacts = srv::loadSessionContacts(path);
  ASSERT_EQ(contacts.size(), 5u);
  EXPECT_EQ(contacts[4].tick, 6);
  EXPECT_TRUE(contacts[4].in_contact);
  EXPECT_DOUBLE_EQ(contacts[4].depth, 6e-4);
  // It is a plain LCM log: the library's reader sees 10 events on our two channels, with
  // timestamps in µs since the epoch, one tick (1000 µs) apart between consecutive ticks.
  lcm::LogFile log(path, "r");
  ASSERT_TRUE(log.good());
  int events = 0;
  std::int64_t first = 0, second = 0;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    if (events == 0) first = e->timestamp;
    if (events == 2) second = e->timestamp;
    EXPECT_TRUE(e->channel == "THX_DEVICE_STATE" || e->channel == "THX_CONTACT") << e->channel;
    ++events;
  }
  EXPECT_EQ(events, 10);
  EXPECT_EQ(second - first, 1000);
  EXPECT_GT(first, std::int64_t(1'600'000'000) * 1'000'000);  // after 2020: a Unix-epoch time
  fs::remove(path);
}

TEST(SessionLog, AHelloIsRecordedOnTheTicksClockBeforeItsTick) {
  const std::string path = tempPath("hello.lcm");
  thx_msgs::hello_t a{}, b{};
  a.utime = tickAt(0).deadline_ns / 1000;
  a.scene_name = "flat";
  b.utime = tickAt(2).deadline_ns / 1000;
  b.scene_name = "grooves";
  {
    srv::SessionRecorder rec(path, true);
    rec.recordHello(a);
    for (std::int64_t t : {0, 1}) rec.record(tickAt(t));
    rec.recordHello(b);
    rec.record(tickAt(2));
    EXPECT_TRUE(rec.ok());
    EXPECT_EQ(rec.ticks(), 3u);  // hellos are not ticks
  }
  const std::vector<thx_msgs::hello_t> hellos = srv::loadSessionHellos(path);
  ASSERT_EQ(hellos.size(), 2u);
  EXPECT_EQ(hellos[0].scene_name, "flat");
  EXPECT_EQ(hellos[1].scene_name, "grooves");
  EXPECT_EQ(hellos[1].utime, 2000);
  EXPECT_EQ(srv::loadSessionTrajectory(path).size(), 3u);  // the readers skip the hellos
  // The events in order, each hello's timestamp that of the tick it precedes.
  lcm::LogFile log(path, "r");
  std::vector<std::string> channels;
  std::vector<std::int64_t> stamps;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    channels.push_back(e->channel);
    stamps.push_back(e->timestamp);
  }
  const std::vector<std::string> expected{"THX_HELLO",  "THX_DEVICE_STATE", "THX_CONTACT", "THX_DEVICE_STATE",
                                          "THX_CONTACT", "THX_HELLO",        "THX_DEVICE_STATE", "THX_CONTACT"};
  EXPECT_EQ(channels, expected);
  ASSERT_EQ(stamps.size(), 8u);
  EXPECT_EQ(stamps[0], stamps[1]);
  EXPECT_EQ(stamps[5], stamps[6]);
  EXPECT_EQ(stamps[6] - stamps[1], 2000);
  fs::remove(path);
}

TEST(SessionLog, LockstepReplayReproducesTheRecordedTicksAndGaps) {
  std::vector<dev::ReplaySample> samples;
  for (std::int64_t t : {10, 11, 12, 15, 16}) {
    dev::ReplaySample s;
    s.tick = t;
    s.p_world = Eigen::Vector3d(0.001 * double(t), 0, 0);
    samples.push_back(s);
  }
  dev::ReplayOptions o;
  o.lockstep = true;
  dev::ReplayDevice d(samples, dev::phantomDesktopSpec(), o);
  d.open();
  std::vector<std::int64_t> ticks, missed;
  for (int i = 0; i < 5; ++i) {
    const dev::DeviceState s = d.read();
    EXPECT_TRUE(s.valid);
    EXPECT_DOUBLE_EQ(s.p_world.x(), 0.001 * double(s.timing.tick));
    EXPECT_EQ(s.timing.deadline_ns, s.timing.tick * 1'000'000);
    ticks.push_back(s.timing.tick);
    missed.push_back(s.timing.missed);
    d.write(dev::DeviceCommand{});
  }
  EXPECT_EQ(ticks, (std::vector<std::int64_t>{10, 11, 12, 15, 16}));
  EXPECT_EQ(missed, (std::vector<std::int64_t>{0, 0, 0, 2, 0}));
  EXPECT_TRUE(d.finished());
  const dev::DeviceState after = d.read();
  EXPECT_FALSE(after.valid);  // past the end: the servo turns the force off
  EXPECT_EQ(after.timing.tick, 17);
  EXPECT_EQ(d.writes(), 5u);
  EXPECT_NEAR(d.durationS(), 0.007, 1e-12);
}

// Under a group's clock (several devices, readTick): the group's first tick plays the first sample,
// a tick the recording lacks holds the last sample (valid, at rest), a missed period of the group
// skips a sample, and past the end the reading is invalid.
TEST(SessionLog, ReplayUnderAGroupsClockFollowsTheGroupsTicks) {
  std::vector<dev::ReplaySample> samples;
  for (std::int64_t t : {10, 11, 12, 15, 16, 17, 18}) {
    dev::ReplaySample s;
    s.tick = t;
    s.p_world = Eigen::Vector3d(0.001 * double(t), 0, 0);
    s.v_world = Eigen::Vector3d(0.01, 0, 0);
    samples.push_back(s);
  }
  dev::ReplayDevice d(samples, dev::phantomDesktopSpec(), dev::ReplayOptions{});
  EXPECT_TRUE(d.sharesClock());
  d.open();
  std::vector<double> x;
  std::vector<bool> valid, moving;
  for (std::int64_t tick : {0, 1, 2, 3, 4, 5, 6, 8, 9}) {  // the group missed tick 7
    rt::TickTiming timing;
    timing.tick = tick;
    timing.missed = tick == 8 ? 1 : 0;
    const dev::DeviceState s = d.readTick(timing);
    EXPECT_EQ(s.timing.tick, tick);
    x.push_back(s.p_world.x());
    valid.push_back(s.valid);
    moving.push_back(s.v_world.x() != 0.0);
  }
  const std::vector<std::int64_t> played = {10, 11, 12, 12, 12, 15, 16, 18, 18};  // the recorded ticks shown
  for (std::size_t k = 0; k < played.size(); ++k) EXPECT_EQ(x[k], 0.001 * double(played[k])) << "group tick " << k;
  EXPECT_EQ(valid, (std::vector<bool>{true, true, true, true, true, true, true, true, false}));
  EXPECT_EQ(moving, (std::vector<bool>{true, true, true, false, false, true, true, true, false}));
  EXPECT_TRUE(d.finished());
}

TEST(SessionLog, BadFilesGiveErrorsThatNameTheProblem) {
  auto message = [](const std::string& path) {
    try {
      srv::loadSessionTrajectory(path);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("/nonexistent/x.lcm").find("cannot open as an LCM log file"), std::string::npos);

  const std::string text = tempPath("text.lcm");
  std::ofstream(text) << "not a log\n";
  const std::string m1 = message(text);
  EXPECT_NE(m1.find(text), std::string::npos) << m1;
  fs::remove(text);

  // A log with a THX_DEVICE_STATE event whose bytes are something else.
  const std::string wrong = tempPath("wrong.lcm");
  {
    lcm::LogFile log(wrong, "w");
    std::uint8_t junk[16] = {1, 2, 3};
    lcm::LogEvent e{};
    e.timestamp = 1;
    e.channel = "THX_DEVICE_STATE";
    e.datalen = sizeof junk;
    e.data = junk;
    log.writeEvent(&e);
  }
  const std::string m2 = message(wrong);
  EXPECT_NE(m2.find("event 1 (THX_DEVICE_STATE): does not decode as device_state_t"), std::string::npos) << m2;
  fs::remove(wrong);

  // One recorded by a build with another layout of device_state_t (its fingerprint before
  // proxy_world was added, docs/messages.md §6): said to be from another protocol version.
  const std::string older = tempPath("older.lcm");
  {
    lcm::LogFile log(older, "w");
    std::uint8_t bytes[196] = {0x91, 0x6e, 0xef, 0x9d, 0x70, 0x65, 0x8d, 0x17};
    lcm::LogEvent e{};
    e.timestamp = 1;
    e.channel = "THX_DEVICE_STATE";
    e.datalen = sizeof bytes;
    e.data = bytes;
    log.writeEvent(&e);
  }
  const std::string m3 = message(older);
  EXPECT_NE(m3.find("event 1 (THX_DEVICE_STATE): does not decode as device_state_t"), std::string::npos) << m3;
  EXPECT_NE(m3.find("another protocol version; record it again"), std::string::npos) << m3;
  fs::remove(older);

  // A log without device states (e.g. recorded with lcm-logger from other channels).
  const std::string other = tempPath("other.lcm");
  {
    lcm::LogFile log(other, "w");
    std::uint8_t byte = 0;
    lcm::LogEvent e{};
    e.channel = "SOMETHING_ELSE";
    e.datalen = 1;
    e.data = &byte;
    log.writeEvent(&e);
  }
  EXPECT_NE(message(other).find("no THX_DEVICE_STATE events"), std::string::npos) << message(other);
  fs::remove(other);

  EXPECT_THROW(dev::ReplayDevice({}, dev::phantomDesktopSpec(), {}), dev::DeviceError);
}

TEST(SessionLog, AnUnwritablePathIsRefusedAtOnce) {
  try {
    srv::SessionRecorder rec("/nonexistent/dir/s.lcm", true);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/s.lcm"), std::string::npos) << e.what();
  }
}

}  // namespace test_session_log
