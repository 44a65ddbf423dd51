#pragma once
// The physics client's LCM side: its events as thx_msgs messages (physics_poses_t,
// physics_impact_t, physics_contacts_t, client_force_t), an EventSink that publishes them, and
// the reader of a recorded hapticd session (LCM log) as a pen path.
#include <cstdint>
#include <string>
#include <vector>

#include <thx_msgs/client_force_t.hpp>
#include <thx_msgs/physics_contacts_t.hpp>
#include <thx_msgs/physics_impact_t.hpp>
#include <thx_msgs/physics_poses_t.hpp>

#include "clients/physics_client/driver.hpp"
#include "clients/physics_client/pen_path.hpp"
#include "thx_client/client.hpp"

namespace lcm {
class LCM;
}

namespace thx::physclient {

std::int64_t monotonicUs();

thx_msgs::physics_poses_t makePoses(const PhysicsScene& scene, std::int64_t ref_tick, const Eigen::Vector3d& pen_force,
                                    std::int64_t seq, std::int64_t utime);
thx_msgs::physics_impact_t makeImpact(const Impact& impact, std::int64_t seq, std::int64_t utime);
// Up to MAX_CONTACTS entries (the rest counted in num_dropped), each with its whole texel path.
thx_msgs::physics_contacts_t makeContacts(const PhysicsScene& scene, const std::vector<LastingContact>& contacts,
                                          double window_s, std::int64_t seq, std::int64_t utime);

struct LcmSinkOptions {
  std::string client_id = "physics";
  std::string source = "physics";
  std::int64_t force_timeout_us = 50'000;  // hapticd drops our force this long after the last message
  bool send_force = true;                  // false: offline runs publish events only
  // Pen i's force goes to device devices[i] (client_force_t.device): the device it follows.
  std::vector<int> devices = {0};
  // Online: forces go where the kit sends requests (the server's control port, which no other
  // client listens on: a 1 kHz force on the bus would wake every client; docs/clients.md §6).
  // Null: on the sink's own LCM (offline, tests). Not owned.
  thx::client::Client* server = nullptr;
};

struct LcmSinkCounters {
  std::uint64_t forces = 0, poses = 0, impacts = 0, contacts = 0, publish_errors = 0;
};

// Publishes every event; `lcm` must outlive the sink.
class LcmSink final : public EventSink {
 public:
  LcmSink(lcm::LCM& lcm, LcmSinkOptions options);
  void penForce(const PhysicsScene&, int pen, const PenForce& f, std::int64_t ref_tick) override;
  void impacts(const PhysicsScene&, const std::vector<Impact>& impacts) override;
  void poses(const PhysicsScene& scene, std::int64_t ref_tick, const Eigen::Vector3d& pen_force) override;
  void contacts(const PhysicsScene& scene, const std::vector<LastingContact>& c, double window_s) override;
  // A zero force (release) for pen `pen`, e.g. at exit.
  void release(int pen, const Eigen::Vector3d& p_world);
  // Every pen's release, each at its tip in `scene`.
  void releaseAll(const PhysicsScene& scene);
  const LcmSinkCounters& counters() const { return counters_; }

 private:
  void sendForce(int pen, const Eigen::Vector3d& f, const Eigen::Vector3d& p, std::int64_t ref_tick);
  lcm::LCM& lcm_;
  LcmSinkOptions options_;
  LcmSinkCounters counters_;
  std::int64_t force_seq_ = 0, pose_seq_ = 0, impact_seq_ = 0, contact_seq_ = 0;
};

// The pen of a recorded hapticd session (`hapticd --record FILE`): its THX_DEVICE_STATE events of
// `device` (client::loggedDevice: every event of a one-device session; another device's pen is not
// this one's), decoded with try_decode, t = (tick - first tick) / servo_hz. Throws PenPathError
// naming the file, the event and the problem, thx::Error (Config) when the log names no such device.
std::vector<PenSample> loadSessionPen(const std::string& path, double servo_hz, int device = 0);
// The pens of `devices` (each as loadSessionPen's), on one clock: t = 0 at the first tick of any
// of them, so pens recorded under one servo clock stay in step.
std::vector<std::vector<PenSample>> loadSessionPens(const std::string& path, double servo_hz,
                                                    const std::vector<int>& devices);
// The devices a session log's hellos name (the hello naming the most; 1 for a log naming none or
// one): physics-client replays that many pens.
int loggedDeviceCount(const std::string& path);
// " of device N" for N > 0, "" for device 0: the words the session readers' errors add.
std::string deviceSuffix(int device);

}  // namespace thx::physclient
