#pragma once
// `physics-client --record FILE`: the physics streams of an offline run (poses, impacts, lasting
// contacts) written to an LCM log on the clock of the session that drove the pen. Replaying a
// recorded hapticd session (`--replay-log`), the output holds that session's events unchanged
// with the physics events interleaved by timestamp: one recorded session, the same bytes on
// every run, that the audio and visual clients can replay without real time.
//
// Clock: a physics event's `utime` is the session's first device-state utime plus the simulated
// time of the step (µs); its log timestamp is the session's first log timestamp plus the same.
// In a lock-step hapticd session utime is tick x period, so physics step k at 1 kHz carries the
// utime of tick k + 1 (the state after the step the pen pose of tick k drove). Without a session
// (CSV, script, no pen) both start at 0.
#include <cstdint>
#include <string>
#include <vector>

#include "clients/physics_client/driver.hpp"

namespace thx::physclient {

struct SessionClock {
  std::int64_t utime0_us = 0;      // utime of the session's first device state
  std::int64_t timestamp0_us = 0;  // its log event timestamp
};

// The clock of a session log (`hapticd --record`): its first THX_DEVICE_STATE event of `device`
// (the pen followed, client::loggedDevice: any event of a one-device session). Throws
// PenPathError naming the file when there is none.
SessionClock sessionClockOf(const std::string& session_path, int device = 0);

struct RecordedEvent {
  std::int64_t timestamp_us = 0;
  std::string channel;
  std::vector<std::uint8_t> data;
};

// Collects the physics events, encoded, with their session-clock timestamps.
class RecordSink final : public EventSink {
 public:
  explicit RecordSink(SessionClock clock) : clock_(clock) {}
  void impacts(const PhysicsScene&, const std::vector<Impact>& impacts) override;
  void poses(const PhysicsScene& scene, std::int64_t ref_tick, const Eigen::Vector3d& pen_force) override;
  void contacts(const PhysicsScene& scene, const std::vector<LastingContact>& c, double window_s) override;
  const std::vector<RecordedEvent>& events() const { return events_; }

 private:
  std::int64_t utimeOf(double sim_time_s) const;
  template <class M>
  void add(const char* channel, const M& m, double sim_time_s);
  SessionClock clock_;
  std::vector<RecordedEvent> events_;
  std::int64_t pose_seq_ = 0, impact_seq_ = 0, contact_seq_ = 0;
};

// Writes `out_path`: the events of `session_path` (empty: none; its own THX_PHYSICS_* events, from
// an earlier recording, are left out) and `physics`, ordered by timestamp (a session event first
// on a tie, each side in its own order). Throws thx::Error
// naming the file when it cannot read or write.
void writeCombinedLog(const std::string& session_path, const std::vector<RecordedEvent>& physics,
                      const std::string& out_path);

}  // namespace thx::physclient
