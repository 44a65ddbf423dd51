#include "clients/visual/replay_frames.hpp"

#include <cmath>
#include <thx_msgs/device_state_t.hpp>
#include <thx_msgs/log_reader.hpp>
#include <thx_msgs/physics_poses_t.hpp>
#include <thx_msgs/protocol.hpp>

#include "base/error.hpp"
#include "clients/visual/live_view.hpp"

namespace thx::visual {

std::vector<ReplayFrame> replayFrames(const std::string& log_path, double servo_hz, double rate_hz,
                                      std::optional<int> device) {
  struct State {
    std::int64_t tick, utime;
    Eigen::Vector3d p, proxy;
    bool held;
  };
  struct Poses {
    std::int64_t utime;
    std::vector<Eigen::Isometry3d> bodies;
  };
  std::vector<State> states;
  std::vector<Poses> poses;
  try {
    thx_msgs::forEachLogMessage<thx_msgs::device_state_t>(
        log_path, "THX_DEVICE_STATE", [&](const thx_msgs::device_state_t& s, const thx_msgs::LogPosition& at) {
          if (device && s.device != *device) return;  // another pen
          const Eigen::Vector3d p(s.p_world[0], s.p_world[1], s.p_world[2]);
          const Eigen::Vector3d proxy(s.proxy_world[0], s.proxy_world[1], s.proxy_world[2]);
          if (!p.allFinite()) throw Error(Error::Kind::Config, at.where() + ": p_world is not finite");
          if (!proxy.allFinite()) throw Error(Error::Kind::Config, at.where() + ": proxy_world is not finite");
          if (!states.empty() && s.tick <= states.back().tick)
            throw Error(Error::Kind::Config, at.where() + ": tick " + std::to_string(s.tick) +
                                                 " does not increase; expected a tick after " +
                                                 std::to_string(states.back().tick));
          states.push_back({s.tick, s.utime, p, proxy, (s.flags & thx_msgs::device_state_t::FLAG_PROXY_HELD) != 0});
        });
    thx_msgs::forEachLogMessage<thx_msgs::physics_poses_t>(
        log_path, thx_msgs::kChannelPhysicsPoses, [&](const thx_msgs::physics_poses_t& m, const thx_msgs::LogPosition& at) {
          const std::string problem = posesProblem(m);
          if (!problem.empty()) throw Error(Error::Kind::Config, at.where() + ": " + problem);
          Poses entry{m.utime, bodiesOf(m)};
          if (!poses.empty() && entry.utime < poses.back().utime)
            throw Error(Error::Kind::Config, at.where() + ": utime " + std::to_string(entry.utime) +
                                                 " goes back; expected poses in time order");
          poses.push_back(std::move(entry));
        });
  } catch (const thx_msgs::LogError& e) {
    throw Error(Error::Kind::Config, std::string(e.what()) + "; expected a session log (LCM log) from `hapticd --record`");
  }
  if (states.empty())
    throw Error(Error::Kind::Config, log_path + ": no THX_DEVICE_STATE events" +
                                         (device ? " of device " + std::to_string(*device) : std::string()) +
                                         "; expected a session log (LCM log) from `hapticd --record`");

  std::vector<ReplayFrame> frames;
  const std::int64_t first = states.front().tick;
  const double duration_s = double(states.back().tick - first) / servo_hz;
  std::size_t k = 0, j = 0;
  for (long n = 0;; ++n) {
    const double t = double(n) / rate_hz;
    if (t > duration_s + 1e-12) break;
    // The latest state at or before t (integer ticks: no rounding drift over long sessions).
    const auto limit = first + std::int64_t(std::floor(t * servo_hz + 1e-9));
    while (k + 1 < states.size() && states[k + 1].tick <= limit) ++k;
    ReplayFrame frame{states[k].tick, t, states[k].p, states[k].proxy, states[k].held, {}};
    // The latest poses the physics client had published by this device state's time.
    while (j < poses.size() && poses[j].utime <= states[k].utime) ++j;
    if (j > 0) frame.bodies = poses[j - 1].bodies;
    frames.push_back(std::move(frame));
  }
  return frames;
}

}  // namespace thx::visual
