#include "server/session_log.hpp"

#include <lcm/lcm-cpp.hpp>
#include <time.h>

#include <cmath>
#include <stdexcept>

#include <thx_msgs/log_reader.hpp>
#include <thx_msgs/protocol.hpp>

#include "base/error.hpp"
#include "server/tick_messages.hpp"

namespace thx::srv {

namespace {

std::int64_t realtimeUs() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return std::int64_t(ts.tv_sec) * 1'000'000 + ts.tv_nsec / 1000;
}

template <class M>
void encodeInto(const M& m, std::vector<std::uint8_t>& out) {
  out.resize(std::size_t(m.getEncodedSize()));
  m.encode(out.data(), 0, int(out.size()));
}

bool finite(const double* v, int n) {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

}  // namespace

SessionRecorder::SessionRecorder(const std::string& path, bool simulated_device)
    : path_(path), simulated_(simulated_device), log_(std::make_unique<lcm::LogFile>(path, "w")) {
  if (!log_->good()) throw thx::Error(thx::Error::Kind::Io, "--record " + path + ": cannot create the log file");
}

SessionRecorder::~SessionRecorder() = default;

bool SessionRecorder::write(const char* channel, std::int64_t utime, const std::vector<std::uint8_t>& bytes) {
  lcm::LogEvent e{};
  e.timestamp = utime + unix_offset_us_;
  e.channel = channel;
  e.datalen = std::int32_t(bytes.size());
  e.data = const_cast<std::uint8_t*>(bytes.data());  // LogFile only reads it
  if (log_->writeEvent(&e) != 0) {
    error_ = path_ + ": writing the session log failed (disk full?); recording stopped";
    return false;
  }
  return true;
}

void SessionRecorder::record(const TickRecord& r, int device) {
  if (!ok()) return;
  thx_msgs::device_state_t d{};
  toDeviceState(r, simulated_, d);
  d.device = device;
  if (!have_offset_) {
    unix_offset_us_ = realtimeUs() - d.utime;
    have_offset_ = true;
  }
  encodeInto(d, buffer_);
  if (!write(kSessionDeviceChannel, d.utime, buffer_)) return;
  thx_msgs::contact_t c{};
  toContact(r, c);
  c.device = device;
  encodeInto(c, buffer_);
  if (!write(kSessionContactChannel, c.utime, buffer_)) return;
  if (device == 0) ++ticks_;
  if (ticks_ % 1000 == 0) std::fflush(log_->getFilePtr());  // a crash loses at most a second
}

void SessionRecorder::recordHello(const thx_msgs::hello_t& h) {
  if (!ok()) return;
  if (!have_offset_) {
    unix_offset_us_ = realtimeUs() - h.utime;
    have_offset_ = true;
  }
  encodeInto(h, buffer_);
  write(kSessionHelloChannel, h.utime, buffer_);
}

namespace {

// The devices a log's hellos name (the last hello's list; a log without a hello, or with a
// protocol-5 hello, holds one).
std::vector<std::string> loggedDeviceNames(const std::string& path) {
  std::vector<std::string> names;
  for (const thx_msgs::hello_t& h : loadSessionHellos(path)) {
    names.clear();
    std::string::size_type from = 0;
    while (from <= h.device_names.size() && !h.device_names.empty()) {
      const std::string::size_type comma = h.device_names.find(',', from);
      names.push_back(h.device_names.substr(from, comma == std::string::npos ? std::string::npos : comma - from));
      if (comma == std::string::npos) break;
      from = comma + 1;
    }
  }
  return names;
}

}  // namespace

std::vector<dev::ReplaySample> loadSessionTrajectory(const std::string& path, int device) {
  const std::vector<std::string> names = loggedDeviceNames(path);
  const bool several = names.size() > 1;
  if (device < 0 || (device > 0 && std::size_t(device) >= names.size())) {
    std::string listed;
    for (std::size_t i = 0; i < names.size(); ++i) listed += (i ? ", " : "") + std::to_string(i) + " " + names[i];
    throw thx::Error(thx::Error::Kind::Config, path + ": device " + std::to_string(device) + " is not in this log; it holds " +
                                                   (names.size() > 1 ? std::to_string(names.size()) + " devices: " + listed
                                                                     : std::string("one device (0)")));
  }
  std::vector<dev::ReplaySample> out;
  thx_msgs::forEachLogMessage<thx_msgs::device_state_t>(path, kSessionDeviceChannel, [&](const thx_msgs::device_state_t& d,
                                                                                          const thx_msgs::LogPosition& at) {
    if (several && d.device != device) return;
    const std::string where = at.where();
    if (!finite(d.p_world, 3) || !finite(d.q_world, 4) || !finite(d.v_world, 3) || !finite(d.w_world, 3))
      throw thx::Error(thx::Error::Kind::Config, where + ": tick " + std::to_string(d.tick) + " holds a non-finite value");
    if (!out.empty() && d.tick <= out.back().tick)
      throw thx::Error(thx::Error::Kind::Config, where + ": tick " + std::to_string(d.tick) + " after tick " +
                               std::to_string(out.back().tick) + "; expected increasing ticks");
    dev::ReplaySample s;
    s.tick = d.tick;
    s.p_world = Eigen::Vector3d(d.p_world[0], d.p_world[1], d.p_world[2]);
    s.q_world = Eigen::Quaterniond(d.q_world[0], d.q_world[1], d.q_world[2], d.q_world[3]);
    s.v_world = Eigen::Vector3d(d.v_world[0], d.v_world[1], d.v_world[2]);
    s.w_world = Eigen::Vector3d(d.w_world[0], d.w_world[1], d.w_world[2]);
    s.buttons = std::uint32_t(d.buttons);
    out.push_back(s);
  });
  if (out.empty()) throw thx::Error(thx::Error::Kind::Io, path + ": no " + kSessionDeviceChannel + " events; not a session log?");
  return out;
}

std::vector<thx_msgs::contact_t> loadSessionContacts(const std::string& path) {
  std::vector<thx_msgs::contact_t> out;
  thx_msgs::forEachLogMessage<thx_msgs::contact_t>(
      path, kSessionContactChannel, [&](const thx_msgs::contact_t& c, const thx_msgs::LogPosition&) { out.push_back(c); });
  return out;
}

std::vector<thx_msgs::hello_t> loadSessionHellos(const std::string& path) {
  std::vector<thx_msgs::hello_t> out;
  thx_msgs::forEachLogMessage<thx_msgs::hello_t>(
      path, kSessionHelloChannel, [&](const thx_msgs::hello_t& h, const thx_msgs::LogPosition&) { out.push_back(h); });
  return out;
}

}  // namespace thx::srv
