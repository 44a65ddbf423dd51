#include "clients/visual/replay_frames.hpp"

#include <cmath>
#include <thx_msgs/device_state_t.hpp>
#include <thx_msgs/log_reader.hpp>

#include "base/error.hpp"

namespace thx::visual {

std::vector<ReplayFrame> replayFrames(const std::string& log_path, double servo_hz, double rate_hz) {
  struct State {
    std::int64_t tick;
    Eigen::Vector3d p;
  };
  std::vector<State> states;
  try {
    thx_msgs::forEachLogMessage<thx_msgs::device_state_t>(
        log_path, "THX_DEVICE_STATE", [&](const thx_msgs::device_state_t& s, const thx_msgs::LogPosition& at) {
          const Eigen::Vector3d p(s.p_world[0], s.p_world[1], s.p_world[2]);
          if (!p.allFinite()) throw Error(Error::Kind::Config, at.where() + ": p_world is not finite");
          if (!states.empty() && s.tick <= states.back().tick)
            throw Error(Error::Kind::Config, at.where() + ": tick " + std::to_string(s.tick) +
                                                 " does not increase; expected a tick after " +
                                                 std::to_string(states.back().tick));
          states.push_back({s.tick, p});
        });
  } catch (const thx_msgs::LogError& e) {
    throw Error(Error::Kind::Config, std::string(e.what()) + "; expected a session log (LCM log) from `hapticd --record`");
  }
  if (states.empty())
    throw Error(Error::Kind::Config,
                log_path + ": no THX_DEVICE_STATE events; expected a session log (LCM log) from `hapticd --record`");

  std::vector<ReplayFrame> frames;
  const std::int64_t first = states.front().tick;
  const double duration_s = double(states.back().tick - first) / servo_hz;
  std::size_t k = 0;
  for (long n = 0;; ++n) {
    const double t = double(n) / rate_hz;
    if (t > duration_s + 1e-12) break;
    // The latest state at or before t (integer ticks: no rounding drift over long sessions).
    const auto limit = first + std::int64_t(std::floor(t * servo_hz + 1e-9));
    while (k + 1 < states.size() && states[k + 1].tick <= limit) ++k;
    frames.push_back({states[k].tick, t, states[k].p});
  }
  return frames;
}

}  // namespace thx::visual
