#pragma once
// Sessions as standard LCM log files: the format lcm-logger writes and lcm-logplayer plays
// (lcm::LogFile), so the usual LCM tools read them. Used by hapticd's publisher thread
// (`--record FILE`) and by the replay device (`--device replay:FILE`); never by the servo.
//
// A session log holds, for every servo tick and every device, one event on THX_DEVICE_STATE
// (device_state_t) and one on THX_CONTACT (contact_t), their `device` the device's index, in tick
// order (a tick's devices in index order), and hapticd's hello (THX_HELLO, hello_t: the
// scene it renders) before the first tick and before the first tick on each switched-to scene,
// its utime that tick's (so ticks from a hello's utime on belong to its scene). Event timestamps are microseconds since the Unix
// epoch (CLOCK_REALTIME at recording start + the tick's offset from the first tick), as
// lcm-logger writes them, so lcm-logplayer replays the session at its original pace.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <thx_msgs/contact_t.hpp>
#include <thx_msgs/hello_t.hpp>

#include "device/replay_device.hpp"
#include "server/tick_record.hpp"

namespace lcm {
class LogFile;
}

namespace thx::srv {

inline constexpr char kSessionDeviceChannel[] = "THX_DEVICE_STATE";
inline constexpr char kSessionContactChannel[] = "THX_CONTACT";
inline constexpr char kSessionHelloChannel[] = "THX_HELLO";

class SessionRecorder {
 public:
  // Creates (truncates) the log. Throws std::runtime_error naming the path if it cannot.
  SessionRecorder(const std::string& path, bool simulated_device);
  ~SessionRecorder();
  SessionRecorder(const SessionRecorder&) = delete;
  SessionRecorder& operator=(const SessionRecorder&) = delete;

  // Appends one tick of device `device` (hello_t.device_names' index). After a write error (disk
  // full) recording stops; ok() turns false and error() says why. Never throws.
  void record(const TickRecord& r, int device = 0);

  // Appends a hello (the scene from h.utime on, on the ticks' clock); like record(), never throws.
  void recordHello(const thx_msgs::hello_t& h);

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  std::uint64_t ticks() const { return ticks_; }  // device 0's ticks recorded
  const std::string& path() const { return path_; }

 private:
  bool write(const char* channel, std::int64_t utime, const std::vector<std::uint8_t>& bytes);

  std::string path_;
  bool simulated_;
  std::unique_ptr<lcm::LogFile> log_;
  std::int64_t unix_offset_us_ = 0;
  bool have_offset_ = false;
  std::uint64_t ticks_ = 0;
  std::string error_;
  std::vector<std::uint8_t> buffer_;
};

// The pen trajectory of device `device` in a session log (its THX_DEVICE_STATE events), for the
// replay device. A log whose hellos name one device (or that has no hello) is one device's whole:
// its `device` fields are not read (builds before this one left them unset). Throws
// std::runtime_error naming the file, the event number and the problem: unreadable file, no
// device states, a device the log does not hold (naming its devices), an event that does not
// decode, a non-finite value, ticks not increasing.
std::vector<dev::ReplaySample> loadSessionTrajectory(const std::string& path, int device = 0);

// Every THX_CONTACT event of a session log, in order (to compare sessions). Throws like above.
std::vector<thx_msgs::contact_t> loadSessionContacts(const std::string& path);
// Every THX_HELLO event of a session log, in order. Throws like above.
std::vector<thx_msgs::hello_t> loadSessionHellos(const std::string& path);

}  // namespace thx::srv
