#include "clients/physics_client/lcm_io.hpp"

#include <lcm/lcm-cpp.hpp>
#include <thx_msgs/log_reader.hpp>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "rt/clock.hpp"
#include "thx_client/devices.hpp"
#include "thx_client/logged_devices.hpp"
#include "thx_msgs/protocol.hpp"

namespace thx::physclient {

namespace {
void put3(double (&dst)[3], const Eigen::Vector3d& v) {
  for (int k = 0; k < 3; ++k) dst[k] = v[k];
}
std::int32_t clampInt(long long v) {
  return std::int32_t(std::clamp<long long>(v, INT32_MIN, INT32_MAX));
}
}  // namespace

std::int64_t monotonicUs() { return rt::monotonicNowNs() / 1000; }

thx_msgs::physics_poses_t makePoses(const PhysicsScene& scene, std::int64_t ref_tick, const Eigen::Vector3d& pen_force,
                                    std::int64_t seq, std::int64_t utime) {
  thx_msgs::physics_poses_t m{};
  m.utime = utime;
  m.seq = seq;
  m.step = scene.steps();
  m.sim_time = scene.simTime();
  m.ref_tick = ref_tick;
  const std::vector<BodyState> bodies = scene.bodies();
  const std::size_t n = std::min<std::size_t>(bodies.size(), thx_msgs::physics_poses_t::MAX_BODIES);
  m.num_bodies = std::int32_t(n);
  for (std::size_t i = 0; i < n; ++i) {
    const BodyState& b = bodies[i];
    put3(m.p_world[i], b.p_world);
    m.q_world[i][0] = b.q_world.w();
    m.q_world[i][1] = b.q_world.x();
    m.q_world[i][2] = b.q_world.y();
    m.q_world[i][3] = b.q_world.z();
    put3(m.v_world[i], b.v_world);
    put3(m.w_world[i], b.w_world);
  }
  put3(m.pen_p_world, scene.penTip());
  put3(m.pen_f_world, pen_force);
  return m;
}

thx_msgs::physics_impact_t makeImpact(const Impact& i, std::int64_t seq, std::int64_t utime) {
  thx_msgs::physics_impact_t m{};
  m.utime = utime;
  m.seq = seq;
  m.step = i.step;
  m.sim_time = i.sim_time_s;
  m.body_a = i.body_a;
  m.body_b = i.body_b;
  m.impulse = i.impulse_ns;
  m.v_approach = i.v_approach_m_per_s;
  put3(m.p_world, i.p_world);
  put3(m.n_world, i.n_world);
  m.on_surface = i.on_surface ? 1 : 0;
  m.texel_i = i.on_surface ? clampInt(i.texel_i) : 0;
  m.texel_j = i.on_surface ? clampInt(i.texel_j) : 0;
  return m;
}

thx_msgs::physics_contacts_t makeContacts(const PhysicsScene& scene, const std::vector<LastingContact>& contacts,
                                          double window_s, std::int64_t seq, std::int64_t utime) {
  using M = thx_msgs::physics_contacts_t;
  M m{};
  m.utime = utime;
  m.seq = seq;
  m.step = scene.steps();
  m.sim_time = scene.simTime();
  m.window = window_s;
  put3(m.n_geometric_world, scene.surface().mapping().geometricNormalWorld());
  const std::size_t n = std::min<std::size_t>(contacts.size(), M::MAX_CONTACTS);
  m.num_contacts = std::int32_t(n);
  m.num_dropped = std::int32_t(contacts.size() - n);
  for (std::size_t k = 0; k < n; ++k) {
    const LastingContact& c = contacts[k];
    m.body_a[k] = c.body_a;
    m.body_b[k] = c.body_b;
    m.mass_a[k] = c.mass_a_kg;
    put3(m.p_world[k], c.p_world);
    put3(m.n_world[k], c.n_world);
    put3(m.v_slip_world[k], c.v_slip_world);
    put3(m.v_world[k], c.v_world);
    // Mean over the whole window (a pair touching in part of it had zero force the rest).
    m.f_normal[k] = window_s > 0 ? c.impulse_sum_ns / window_s : c.meanNormalForceN();
    m.path_start[k] = std::int32_t(m.path.size());
    m.num_texels[k] = std::int32_t(c.path.size());
    m.texels_dropped[k] = clampInt(c.path_dropped);
    for (const Texel& t : c.path) {
      thx_msgs::physics_texel_t e{};
      e.i = clampInt(t.i);
      e.j = clampInt(t.j);
      e.t = t.t_s;
      put3(e.n_world, t.n_world);
      put3(e.v_world, t.v_world);
      m.path.push_back(e);
    }
  }
  m.num_path = std::int32_t(m.path.size());
  return m;
}

LcmSink::LcmSink(lcm::LCM& lcm, LcmSinkOptions options) : lcm_(lcm), options_(std::move(options)) {}

void LcmSink::sendForce(int pen, const Eigen::Vector3d& f, const Eigen::Vector3d& p, std::int64_t ref_tick) {
  if (!options_.send_force) return;
  thx_msgs::client_force_t m{};
  m.utime = monotonicUs();
  m.seq = ++force_seq_;
  m.ref_tick = ref_tick;
  m.timeout_us = options_.force_timeout_us;
  m.client_id = options_.client_id;
  m.source = options_.source;
  m.device = options_.devices.at(std::size_t(pen));
  put3(m.f_world, f);
  put3(m.p_world, p);
  const int rc = options_.server ? options_.server->sendToServer(thx_msgs::kChannelClientForce, m)
                                 : lcm_.publish(thx_msgs::kChannelClientForce, &m);
  if (rc != 0) ++counters_.publish_errors;
  ++counters_.forces;
}

void LcmSink::penForce(const PhysicsScene& scene, int pen, const PenForce& f, std::int64_t ref_tick) {
  sendForce(pen, f.sent_world, scene.penTip(pen), ref_tick);
}

void LcmSink::release(int pen, const Eigen::Vector3d& p_world) { sendForce(pen, Eigen::Vector3d::Zero(), p_world, -1); }

void LcmSink::releaseAll(const PhysicsScene& scene) {
  for (int pen = 0; pen < scene.penCount() && std::size_t(pen) < options_.devices.size(); ++pen)
    release(pen, scene.penTip(pen));
}

void LcmSink::impacts(const PhysicsScene&, const std::vector<Impact>& impacts) {
  for (const Impact& i : impacts) {
    const thx_msgs::physics_impact_t m = makeImpact(i, ++impact_seq_, monotonicUs());
    if (lcm_.publish(thx_msgs::kChannelPhysicsImpact, &m) != 0) ++counters_.publish_errors;
    ++counters_.impacts;
  }
}

void LcmSink::poses(const PhysicsScene& scene, std::int64_t ref_tick, const Eigen::Vector3d& pen_force) {
  const thx_msgs::physics_poses_t m = makePoses(scene, ref_tick, pen_force, ++pose_seq_, monotonicUs());
  if (lcm_.publish(thx_msgs::kChannelPhysicsPoses, &m) != 0) ++counters_.publish_errors;
  ++counters_.poses;
}

void LcmSink::contacts(const PhysicsScene& scene, const std::vector<LastingContact>& c, double window_s) {
  const thx_msgs::physics_contacts_t m = makeContacts(scene, c, window_s, ++contact_seq_, monotonicUs());
  if (lcm_.publish(thx_msgs::kChannelPhysicsContacts, &m) != 0) ++counters_.publish_errors;
  ++counters_.contacts;
}

std::string deviceSuffix(int device) { return device == 0 ? "" : " of device " + std::to_string(device); }

std::vector<PenSample> loadSessionPen(const std::string& path, double servo_hz, int device) {
  return loadSessionPens(path, servo_hz, {device}).front();
}

std::vector<std::vector<PenSample>> loadSessionPens(const std::string& path, double servo_hz,
                                                    const std::vector<int>& devices) {
  std::vector<std::vector<PenSample>> out(devices.size());
  std::int64_t first_tick = 0;
  bool any = false;
  try {
    std::vector<client::LoggedDevice> pens;
    for (int d : devices) pens.push_back(client::loggedDevice(path, d));
    thx_msgs::forEachLogMessage<thx_msgs::device_state_t>(path, "THX_DEVICE_STATE", [&](const thx_msgs::device_state_t& s,
                                                                                       const thx_msgs::LogPosition& at) {
      for (std::size_t k = 0; k < pens.size(); ++k) {
        if (!pens[k].takes(s.device)) continue;  // another device's pen
        std::vector<PenSample>& pen = out[k];
        const Eigen::Vector3d p(s.p_world[0], s.p_world[1], s.p_world[2]);
        if (!p.allFinite()) throw PenPathError(at.where() + ": p_world is not finite");
        if (!any) first_tick = s.tick, any = true;
        if (!pen.empty() && s.tick <= pen.back().tick)
          throw PenPathError(at.where() + ": tick " + std::to_string(s.tick) + " does not increase; expected ticks after " +
                             std::to_string(pen.back().tick));
        PenSample ps;
        ps.tick = s.tick;
        ps.t_s = double(s.tick - first_tick) / servo_hz;
        ps.p_world = p;
        const Eigen::Quaterniond q(s.q_world[0], s.q_world[1], s.q_world[2], s.q_world[3]);
        if (!q.coeffs().allFinite()) throw PenPathError(at.where() + ": q_world is not finite");
        if (q.norm() > 1e-6) ps.q_world = q.normalized();  // zero: upright, as a pen without one
        pen.push_back(ps);
      }
    });
  } catch (const thx_msgs::LogError& e) {
    throw PenPathError(std::string(e.what()) + "; expected an LCM log from `hapticd --record`");
  }
  for (std::size_t k = 0; k < out.size(); ++k)
    if (out[k].size() < 2)
      throw PenPathError(path + ": " + std::to_string(out[k].size()) + " device states" + deviceSuffix(devices[k]) +
                         "; expected a session log with at least 2 THX_DEVICE_STATE events");
  return out;
}

int loggedDeviceCount(const std::string& path) {
  std::size_t most = 1;
  try {
    thx_msgs::forEachLogMessage<thx_msgs::hello_t>(
        path, thx_msgs::kChannelHello,
        [&](const thx_msgs::hello_t& h, const thx_msgs::LogPosition&) { most = std::max(most, client::deviceNames(h).size()); });
  } catch (const thx_msgs::LogError& e) {
    throw PenPathError(std::string(e.what()) + "; expected an LCM log from `hapticd --record`");
  }
  return int(most);
}

}  // namespace thx::physclient
