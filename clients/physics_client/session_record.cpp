#include "clients/physics_client/session_record.hpp"

#include <lcm/lcm-cpp.hpp>
#include <thx_msgs/log_reader.hpp>

#include <cmath>
#include <cstdint>
#include <memory>

#include "clients/physics_client/lcm_io.hpp"
#include "clients/physics_client/pen_path.hpp"
#include "thx_client/logged_devices.hpp"
#include "thx_msgs/protocol.hpp"

namespace thx::physclient {

SessionClock sessionClockOf(const std::string& session_path, int device) {
  const client::LoggedDevice pen = client::loggedDevice(session_path, device);
  thx_msgs::LogReader log(session_path);
  thx_msgs::LogRecord e;
  while (log.next(e)) {
    if (e.channel != "THX_DEVICE_STATE") continue;
    thx_msgs::device_state_t s;
    if (thx_msgs::try_decode(e.data.data(), e.data.size(), s) < 0)
      throw PenPathError(session_path + ": a THX_DEVICE_STATE event does not decode as device_state_t");
    if (pen.takes(s.device)) return {s.utime, e.timestamp_us};
  }
  throw PenPathError(session_path + ": no THX_DEVICE_STATE event" + deviceSuffix(device) +
                     "; expected a session log from `hapticd --record`");
}

std::int64_t RecordSink::utimeOf(double sim_time_s) const { return clock_.utime0_us + std::llround(sim_time_s * 1e6); }

template <class M>
void RecordSink::add(const char* channel, const M& m, double sim_time_s) {
  RecordedEvent e;
  e.timestamp_us = clock_.timestamp0_us + std::llround(sim_time_s * 1e6);
  e.channel = channel;
  e.data.resize(std::size_t(m.getEncodedSize()));
  m.encode(e.data.data(), 0, int(e.data.size()));
  events_.push_back(std::move(e));
}

void RecordSink::impacts(const PhysicsScene&, const std::vector<Impact>& impacts) {
  for (const Impact& i : impacts)
    add(thx_msgs::kChannelPhysicsImpact, makeImpact(i, ++impact_seq_, utimeOf(i.sim_time_s)), i.sim_time_s);
}

void RecordSink::poses(const PhysicsScene& scene, std::int64_t ref_tick, const Eigen::Vector3d& pen_force) {
  add(thx_msgs::kChannelPhysicsPoses, makePoses(scene, ref_tick, pen_force, ++pose_seq_, utimeOf(scene.simTime())),
      scene.simTime());
}

void RecordSink::contacts(const PhysicsScene& scene, const std::vector<LastingContact>& c, double window_s) {
  add(thx_msgs::kChannelPhysicsContacts, makeContacts(scene, c, window_s, ++contact_seq_, utimeOf(scene.simTime())),
      scene.simTime());
}

void writeCombinedLog(const std::string& session_path, const std::vector<RecordedEvent>& physics,
                      const std::string& out_path) {
  std::unique_ptr<thx_msgs::LogReader> in;
  if (!session_path.empty()) in = std::make_unique<thx_msgs::LogReader>(session_path);
  lcm::LogFile out(out_path, "w");
  if (!out.good()) throw thx::Error(thx::Error::Kind::Io, "--record " + out_path + ": cannot create the log file");
  std::int64_t eventnum = 0;
  auto write = [&](std::int64_t timestamp, const std::string& channel, const void* data, std::int32_t size) {
    lcm::LogEvent e{};
    e.eventnum = eventnum++;
    e.timestamp = timestamp;
    e.channel = channel;
    e.datalen = size;
    e.data = const_cast<void*>(data);  // LogFile only reads it
    if (out.writeEvent(&e) != 0)
      throw thx::Error(thx::Error::Kind::Io, "--record " + out_path + ": writing the log failed (disk full?)");
  };
  std::size_t next = 0;
  auto physicsBefore = [&](std::int64_t timestamp) {  // a session event goes first on a tie
    for (; next < physics.size() && physics[next].timestamp_us < timestamp; ++next)
      write(physics[next].timestamp_us, physics[next].channel, physics[next].data.data(),
            std::int32_t(physics[next].data.size()));
  };
  if (in)
    for (thx_msgs::LogRecord e; in->next(e);) {
      if (e.channel.rfind("THX_PHYSICS_", 0) == 0) continue;  // an earlier recording's: replaced
      physicsBefore(e.timestamp_us);
      write(e.timestamp_us, e.channel, e.data.data(), std::int32_t(e.data.size()));
    }
  for (; next < physics.size(); ++next)  // after the session's last event
    write(physics[next].timestamp_us, physics[next].channel, physics[next].data.data(),
          std::int32_t(physics[next].data.size()));
}

}  // namespace thx::physclient
