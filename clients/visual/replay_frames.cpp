#include "clients/visual/replay_frames.hpp"

#include <algorithm>
#include <cmath>
#include <thx_msgs/device_state_t.hpp>
#include <thx_msgs/log_reader.hpp>
#include <thx_msgs/physics_poses_t.hpp>
#include <thx_msgs/protocol.hpp>

#include "base/error.hpp"
#include "clients/visual/live_view.hpp"

namespace thx::visual {

namespace {

struct State {
  std::int64_t tick, utime;
  PenView pen;
};

// One drawn device's recorded states, in tick order, and where the frames have got to in them.
struct Track {
  int device;
  std::vector<State> states;
  std::size_t k = 0;
};

struct Poses {
  std::int64_t utime;
  std::vector<Eigen::Isometry3d> bodies;
};

const char* const kExpectedLog = "; expected a session log (LCM log) from `hapticd --record`";

// Each device's states (one track taking every state when `devices` is empty).
std::vector<Track> readTracks(const std::string& log_path, const std::vector<int>& devices) {
  std::vector<Track> tracks;
  for (const int d : devices) tracks.push_back({d, {}});
  if (tracks.empty()) tracks.push_back({0, {}});
  std::sort(tracks.begin(), tracks.end(), [](const Track& a, const Track& b) { return a.device < b.device; });
  thx_msgs::forEachLogMessage<thx_msgs::device_state_t>(
      log_path, "THX_DEVICE_STATE", [&](const thx_msgs::device_state_t& s, const thx_msgs::LogPosition& at) {
        const auto track = devices.empty() ? tracks.begin()
                                           : std::find_if(tracks.begin(), tracks.end(),
                                                          [&](const Track& t) { return t.device == s.device; });
        if (track == tracks.end()) return;  // a pen not drawn
        if (!Eigen::Vector3d(s.p_world[0], s.p_world[1], s.p_world[2]).allFinite())
          throw Error(Error::Kind::Config, at.where() + ": p_world is not finite");
        if (!Eigen::Vector3d(s.proxy_world[0], s.proxy_world[1], s.proxy_world[2]).allFinite())
          throw Error(Error::Kind::Config, at.where() + ": proxy_world is not finite");
        PenView pen = penViewOf(s);
        pen.device = track->device;  // a one-device log's field is not read (logged_devices.hpp)
        std::vector<State>& states = track->states;
        if (!states.empty() && s.tick <= states.back().tick)
          throw Error(Error::Kind::Config, at.where() + ": tick " + std::to_string(s.tick) +
                                               " does not increase; expected a tick after " +
                                               std::to_string(states.back().tick));
        states.push_back({s.tick, s.utime, pen});
      });
  for (const Track& t : tracks) {
    if (t.states.empty())
      throw Error(Error::Kind::Config, log_path + ": no THX_DEVICE_STATE events" +
                                           (devices.empty() ? std::string() : " of device " + std::to_string(t.device)) +
                                           kExpectedLog);
  }
  return tracks;
}

std::vector<Poses> readPoses(const std::string& log_path) {
  std::vector<Poses> poses;
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
  return poses;
}

}  // namespace

std::vector<PenView> pensOf(const ReplayFrame& frame) {
  std::vector<PenView> pens{{frame.tip_world, frame.proxy_world, frame.proxy_held, frame.device, frame.q_world}};
  pens.insert(pens.end(), frame.other_pens.begin(), frame.other_pens.end());
  return pens;
}

std::vector<ReplayFrame> replayFrames(const std::string& log_path, double servo_hz, double rate_hz,
                                      const std::vector<int>& devices) {
  std::vector<Track> tracks;
  std::vector<Poses> poses;
  try {
    tracks = readTracks(log_path, devices);
    poses = readPoses(log_path);
  } catch (const thx_msgs::LogError& e) {
    throw Error(Error::Kind::Config, std::string(e.what()) + kExpectedLog);
  }

  std::int64_t first = tracks.front().states.front().tick, last = tracks.front().states.back().tick;
  for (const Track& t : tracks) {
    first = std::min(first, t.states.front().tick);
    last = std::max(last, t.states.back().tick);
  }
  std::vector<ReplayFrame> frames;
  const double duration_s = double(last - first) / servo_hz;
  std::size_t j = 0;
  for (long n = 0;; ++n) {
    const double t = double(n) / rate_hz;
    if (t > duration_s + 1e-12) break;
    // Each device's latest state at or before t (integer ticks: no rounding drift over long
    // sessions); a device whose first state comes later has no pen yet.
    const auto limit = first + std::int64_t(std::floor(t * servo_hz + 1e-9));
    ReplayFrame frame;
    frame.t_s = t;
    std::int64_t utime = 0;
    bool any = false;
    for (Track& track : tracks) {
      while (track.k + 1 < track.states.size() && track.states[track.k + 1].tick <= limit) ++track.k;
      const State& s = track.states[track.k];
      if (s.tick > limit) continue;
      if (!any) {
        frame.tick = s.tick;
        frame.tip_world = s.pen.tip_world;
        frame.proxy_world = s.pen.proxy_world;
        frame.proxy_held = s.pen.proxy_held;
        frame.device = s.pen.device;
        frame.q_world = s.pen.q_world;
      } else {
        frame.other_pens.push_back(s.pen);
      }
      utime = any ? std::max(utime, s.utime) : s.utime;
      any = true;
    }
    // The latest poses the physics client had published by the newest drawn device state's time.
    while (j < poses.size() && poses[j].utime <= utime) ++j;
    if (j > 0) frame.bodies = poses[j - 1].bodies;
    frames.push_back(std::move(frame));
  }
  return frames;
}

}  // namespace thx::visual
