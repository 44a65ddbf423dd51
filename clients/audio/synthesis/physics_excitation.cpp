#include "clients/audio/synthesis/physics_excitation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <stdexcept>

#include <Eigen/Geometry>

#include "clients/audio/synthesis/contact_pulse.hpp"
#include "clients/audio/synthesis/meso_impulses.hpp"

namespace thx::audio {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Eigen::Vector3d vec(const double (&a)[3]) { return {a[0], a[1], a[2]}; }

// The Hertz description of one side of an impact (contact_pulse.hpp).
HertzSide hertzSide(const scene::Scene& scene, int body) {
  if (body == thx_msgs::physics_impact_t::BODY_SURFACE)
    return {scene.surface.material.youngs_modulus_pa, scene.surface.material.poisson_ratio, kInf, kInf};
  if (body < 0 || std::size_t(body) >= scene.objects.size()) return {};  // the pen: rigid, flat, kinematic
  const scene::SceneObject& o = scene.objects[std::size_t(body)];
  // A box strikes with an edge or corner more often than flat: half its shortest edge stands in
  // for the curvature radius there.
  const double radius = o.shape == scene::Shape::Box ? 0.5 * o.size_m.minCoeff() : o.radius_m;
  return {o.material.youngs_modulus_pa, o.material.poisson_ratio, radius, o.fixed ? kInf : o.mass_kg};
}

// World -> body frame at `utime`: the pose, moved on by its velocities.
Eigen::Isometry3d worldToBody(const thx_msgs::physics_poses_t& p, std::size_t b, std::int64_t utime) {
  const double dt = double(utime - p.utime) * 1e-6;
  const Eigen::Vector3d c = vec(p.p_world[b]) + dt * vec(p.v_world[b]);
  Eigen::Quaterniond q(p.q_world[b][0], p.q_world[b][1], p.q_world[b][2], p.q_world[b][3]);
  const Eigen::Vector3d w = vec(p.w_world[b]);
  if (w.norm() * dt > 0) q = Eigen::Quaterniond(Eigen::AngleAxisd(w.norm() * dt, w.normalized())) * q;
  Eigen::Isometry3d body_to_world = Eigen::Isometry3d::Identity();
  body_to_world.linear() = q.normalized().toRotationMatrix();
  body_to_world.translation() = c;
  return body_to_world.inverse();
}

}  // namespace

PhysicsExcitation::PhysicsExcitation(const SoundingScene& scene, double min_normal_dot, ObjectContactOptions object_contacts)
    : scene_(scene), min_normal_dot_(min_normal_dot), last_sim_time_(-kInf), object_contacts_(object_contacts) {}

void PhysicsExcitation::reset() {
  states_.clear();
  rubs_.clear();
  last_sim_time_ = -kInf;
}

bool PhysicsExcitation::strike(int body, std::int64_t utime, double delay_s, const Eigen::Vector3d& p,
                               const Eigen::Vector3d& J, double pulse_s, const PoseLookup& poses,
                               const StrikeSink& sink) const {
  BodyStrike s;
  s.body = body;
  s.utime = utime;
  s.delay_s = delay_s;
  s.pulse_s = pulse_s;
  return strike(s, p, J, poses, sink);
}

bool PhysicsExcitation::strike(BodyStrike s, const Eigen::Vector3d& p, const Eigen::Vector3d& J, const PoseLookup& poses,
                               const StrikeSink& sink) const {
  const int body = s.body;
  const std::int64_t utime = s.utime;
  if (body == thx_msgs::physics_impact_t::BODY_SURFACE && scene_.surface_mesh_to_world) {
    s.body = -1;
    s.modal = scene_.surface.get();
    const Eigen::Isometry3d to_mesh = scene_.surface_mesh_to_world->inverse();
    s.point = to_mesh * p;
    s.impulse = to_mesh.linear() * J;
  } else if (body == thx_msgs::physics_impact_t::BODY_SURFACE) {
    s.body = -1;
    s.modal = scene_.surface.get();
    s.point = scene_.mapping.toLocal(p);
    s.impulse = scene_.mapping.directionToLocal(J);
    for (int a = 0; a < 2; ++a) {  // the slab is the texture's one span; the texture repeats
      const double size = scene_.mapping.size_m[a];
      s.point[a] -= size * std::floor(s.point[a] / size + 0.5);
    }
    s.point.z() = std::clamp(s.point.z(), -scene_.slab_thickness_m, 0.0);
  } else if (body == thx_msgs::physics_impact_t::BODY_PEN) {
    if (!scene_.pen || scene_.pen->mesh().nodes.empty()) return false;
    s.modal = scene_.pen.get();
    s.point = scene_.pen->mesh().nodes.at(std::size_t(scene_.pen_tip_node));
    // Plane-local to the pen's frame: the surface normal becomes (sin tilt, 0, cos tilt).
    s.impulse = Eigen::AngleAxisd(scene_.pen_tilt_deg * std::numbers::pi / 180.0, Eigen::Vector3d::UnitY()) *
                scene_.mapping.directionToLocal(J);
  } else if (body >= 0 && std::size_t(body) < scene_.objects.size() && scene_.objects[std::size_t(body)]) {
    const thx_msgs::physics_poses_t* pose = poses ? poses(utime) : nullptr;
    if (!pose || body >= pose->num_bodies) return false;
    const Eigen::Isometry3d to_body = worldToBody(*pose, std::size_t(body), utime);
    s.modal = scene_.objects[std::size_t(body)].get();
    s.point = to_body * p;
    s.impulse = to_body.linear() * J;
  }
  if (!s.modal || s.modal->size() == 0) return false;
  return sink(s);
}

void PhysicsExcitation::impact(const thx_msgs::physics_impact_t& m, const PoseLookup& poses, const StrikeSink& sink) {
  if (!(m.impulse > 0.0)) return;
  double tau = 0.0;
  try {
    tau = hertzContactDuration(hertzSide(scene_.scene, m.body_a), hertzSide(scene_.scene, m.body_b), m.v_approach);
  } catch (const thx::Error&) {
    tau = 0.0;  // no elastic side to set a duration (the pen on a rigid body): an ideal impulse
  }
  const Eigen::Vector3d J = m.impulse * vec(m.n_world), p = vec(m.p_world);
  const bool a = strike(m.body_a, m.utime, 0.5 * tau, p, J, tau, poses, sink);
  const bool b = strike(m.body_b, m.utime, 0.5 * tau, p, -J, tau, poses, sink);
  if (!a && !b) return;
  counts_.strikes += std::size_t(a) + std::size_t(b);
  counts_.min_contact_s = counts_.impacts == 0 ? tau : std::min(counts_.min_contact_s, tau);
  counts_.max_contact_s = std::max(counts_.max_contact_s, tau);
  ++counts_.impacts;
  counts_.object_impacts += m.body_a >= 0 && m.body_b >= 0;
}

// The object gains +dp at p, the surface -dp: both sides ring.
void PhysicsExcitation::strikePair(int object, std::int64_t utime, const Eigen::Vector3d& p, const Eigen::Vector3d& dp,
                                   const PoseLookup& poses, const StrikeSink& sink, std::size_t& counter) {
  const bool s = strike(thx_msgs::physics_impact_t::BODY_SURFACE, utime, 0.0, p, -dp, 0.0, poses, sink);
  const bool o = strike(object, utime, 0.0, p, dp, 0.0, poses, sink);
  counts_.strikes += std::size_t(s) + std::size_t(o);
  if (s || o) ++counter;
}

// Two objects rubbing: the roughness force over the report's window, read along the contact's
// travel (object_contact.hpp), +n on a and -n on b at the contact point, each in its own frame.
void PhysicsExcitation::objectContact(const thx_msgs::physics_contacts_t& m, int k, const PoseLookup& poses,
                                      const StrikeSink& sink) {
  const int a = m.body_a[k], b = m.body_b[k];
  RubState& st = rubs_[{a, b}];
  const Eigen::Vector3d p = vec(m.p_world[k]), n = vec(m.n_world[k]).normalized();
  const auto tangential = [&](const Eigen::Vector3d& v) -> Eigen::Vector3d { return v - v.dot(n) * n; };
  // b's material at the contact point, from its newest pose (none: at rest, a fixed obstacle).
  Eigen::Vector3d vb = Eigen::Vector3d::Zero();
  const thx_msgs::physics_poses_t* pose = poses ? poses(m.utime) : nullptr;
  if (pose && b < pose->num_bodies) {
    const std::size_t i = std::size_t(b);
    vb = vec(pose->v_world[i]) + vec(pose->w_world[i]).cross(p - vec(pose->p_world[i]));
  }
  const ContactTravel t = contactTravel(tangential(vec(m.v_slip_world[k])).norm(), tangential(vec(m.v_world[k]) - vb).norm(),
                                        object_contacts_);
  const double force = t.weight * std::max(0.0, m.f_normal[k]);
  // A window longer than the physics client's slowest contact rate (1 Hz), or values that are not
  // finite, are not a contact this can read (the bytes come from the network).
  const bool readable = std::isfinite(t.speed_m_per_s) && std::isfinite(force) && m.window > 0.0 && m.window <= 1.0;
  if (!readable || !(t.speed_m_per_s > 0.0) || !(force > 0.0)) {
    st.moving = false;  // at rest (or no push): exactly silent, and the next motion fades in
    return;
  }
  BodyStrike s;
  s.micro = true;
  s.utime = m.utime - std::llround(m.window * 1e6);
  s.end_utime = m.utime;
  s.s0 = st.distance_m;
  s.s1 = st.distance_m + t.speed_m_per_s * m.window;
  s.f0 = st.moving ? st.force_n : 0.0;  // a contact that starts moving fades in over its first window
  s.f1 = force;
  st.distance_m = s.s1;
  st.moving = true;
  st.force_n = force;
  BodyStrike on_a = s, on_b = s;
  on_a.body = a;
  on_b.body = b;
  const bool sa = strike(on_a, p, n, poses, sink);
  const bool sb = strike(on_b, p, -n, poses, sink);
  counts_.strikes += std::size_t(sa) + std::size_t(sb);
  if (sa || sb) ++counts_.object_contact_segments;
}

void PhysicsExcitation::contacts(const thx_msgs::physics_contacts_t& m, const PoseLookup& poses,
                                 const StrikeSink& sink) {
  // A gap in the reports (no contact lasted meanwhile): every walk starts anew.
  if (m.sim_time - m.window > last_sim_time_ + 1e-9) {
    states_.clear();
    rubs_.clear();
  }
  last_sim_time_ = m.sim_time;
  const Eigen::Vector3d ng = vec(m.n_geometric_world).normalized();
  std::set<int> present;
  std::set<std::pair<int, int>> rubbing;
  const int n = std::clamp(m.num_contacts, 0, int(thx_msgs::physics_contacts_t::MAX_CONTACTS));
  // Two objects first: their segments start a window before the report, before its texels.
  for (int k = 0; k < n && object_contacts_.enabled; ++k) {
    if (m.body_a[k] < 0 || m.body_b[k] < 0) continue;
    rubbing.insert({m.body_a[k], m.body_b[k]});
    objectContact(m, k, poses, sink);
  }
  for (auto it = rubs_.begin(); it != rubs_.end();)  // a contact that ended
    it = rubbing.count(it->first) ? std::next(it) : rubs_.erase(it);
  for (int k = 0; k < n; ++k) {
    const int a = m.body_a[k];
    if (m.body_b[k] != thx_msgs::physics_contacts_t::BODY_SURFACE || a < 0 || !(m.mass_a[k] > 0.0)) continue;
    present.insert(a);
    PathState& st = states_[a];
    const Eigen::Vector3d p = vec(m.p_world[k]);
    if (scene_.relief) {
      // The relief's geometry is in the physics already: what it does to the object's normal
      // momentum between two reports is the impulse (the static support is not a change).
      const double vn = vec(m.v_world[k]).dot(ng);
      if (st.has_vn && vn != st.vn) strikePair(a, m.utime, p, m.mass_a[k] * (vn - st.vn) * ng, poses, sink, counts_.relief_impulses);
      st.has_vn = true;
      st.vn = vn;
      continue;
    }
    const MesoSurface surface{nullptr, tex::Address::Wrap, ng, m.mass_a[k], min_normal_dot_};
    const int end = std::min({m.path_start[k] + m.num_texels[k], m.num_path, int(m.path.size())});
    for (int e = std::max(0, m.path_start[k]); e < end; ++e) {
      const thx_msgs::physics_texel_t& t = m.path[std::size_t(e)];
      if (st.has_texel && t.i == st.i && t.j == st.j) continue;  // not entered: still in it
      const Eigen::Vector3f ns = vec(t.n_world).cast<float>();
      if (st.has_texel) {
        const Eigen::Vector3d v = vec(t.v_world);
        const Eigen::Vector3d dp = mesoMomentum(surface, ns, v) - mesoMomentum(surface, st.normal, v);
        if (dp.squaredNorm() > 0.0)
          strikePair(a, m.utime + std::llround((t.t - m.sim_time) * 1e6), p, dp, poses, sink, counts_.meso_impulses);
      }
      st.has_texel = true;
      st.i = t.i;
      st.j = t.j;
      st.normal = ns;
    }
  }
  for (auto it = states_.begin(); it != states_.end();)  // a contact that ended
    it = present.count(it->first) ? std::next(it) : states_.erase(it);
}

}  // namespace thx::audio
