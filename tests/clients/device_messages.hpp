#pragma once
// Stream messages of one device, as a protocol-6 hapticd with several devices sends them on one
// subscriber's channel: each tagged with `device`, ticks shared by all devices (one servo clock),
// batch seqs counted per device. The device's pen is at x = 0.1 m × device, so a test can tell
// whose pen a value is.
#include <cstdint>

#include <thx_msgs/contact_batch_t.hpp>
#include <thx_msgs/contact_t.hpp>
#include <thx_msgs/device_state_t.hpp>
#include <thx_msgs/servo_stats_t.hpp>

namespace thx::test {

inline double penX(int device) { return 0.1 * device; }

// A message of `device` stamped with `tick`'s time (1 kHz servo).
template <class M>
M ofDevice(int device, std::int64_t tick) {
  M m{};
  m.device = device;
  m.utime = tick * 1000;
  return m;
}

inline thx_msgs::device_state_t deviceState(int device, std::int64_t tick) {
  auto m = ofDevice<thx_msgs::device_state_t>(device, tick);
  m.tick = tick;
  m.p_world[0] = penX(device);
  return m;
}

inline thx_msgs::contact_t contactSample(int device, std::int64_t tick) {
  auto m = ofDevice<thx_msgs::contact_t>(device, tick);
  m.tick = tick;
  m.p_proj_world[0] = penX(device);
  return m;
}

// Batch `seq` of `device`: ticks first_tick .. first_tick + 9, from server `instance`.
inline thx_msgs::contact_batch_t contactBatch(int device, std::int64_t seq, std::int64_t first_tick,
                                              std::int64_t instance = 11) {
  thx_msgs::contact_batch_t b{};
  b.device = device;
  b.seq = seq;
  b.server_instance = instance;
  for (std::int64_t t = first_tick; t < first_tick + 10; ++t) b.samples.push_back(contactSample(device, t));
  b.num_samples = 10;
  b.next_tick = first_tick + 10;
  b.utime = b.samples.back().utime;
  return b;
}

inline thx_msgs::servo_stats_t servoStats(int device, std::int64_t ticks) {
  auto m = ofDevice<thx_msgs::servo_stats_t>(device, ticks);
  m.ticks = ticks;
  return m;
}

}  // namespace thx::test
