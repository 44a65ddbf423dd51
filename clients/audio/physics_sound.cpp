#include "clients/audio/physics_sound.hpp"

#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <stdexcept>

#include <Eigen/Geometry>
#include <thx_msgs/hello_t.hpp>
#include <thx_msgs/log_reader.hpp>

#include "clients/audio/contact_pulse.hpp"
#include "clients/audio/meso_impulses.hpp"
#include "clients/audio/resonator_bank.hpp"
#include "clients/audio/scene_bodies.hpp"
#include "scenes/scene_frames.hpp"
#include "thx_msgs/protocol.hpp"

namespace thx::audio {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Eigen::Vector3d vec(const double (&a)[3]) { return {a[0], a[1], a[2]}; }

std::shared_ptr<const ModalBody> analysedBody(const TetMesh& mesh, const ElasticMaterial& material, const BodyOptions& o) {
  return std::make_shared<const ModalBody>(mesh, audibleModes(analyse(mesh, material, o.modal, o.analysis), material, o.audible));
}

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

struct Strike {
  std::int64_t sample;
  int scene, body;  // body: -1 the surface, else objects[] index
  std::vector<double> gains;
};

class Renderer {
 public:
  Renderer(const PhysicsStreams& s, const SoundingScene& first, const std::function<SoundingScene(const std::string&)>& scene_for,
           std::int64_t origin, const PhysicsSoundOptions& o)
      : streams_(s), scene_for_(scene_for), origin_(origin), o_(o) {
    scenes_.push_back(first);
    switches_.push_back({std::numeric_limits<std::int64_t>::min(), 0});
    std::string current = first.name;
    for (const auto& h : s.hellos) {
      if (h.scene_name.empty() || h.scene_name == current) continue;
      current = h.scene_name;
      switches_.push_back({h.utime, sceneIndex(current)});
    }
  }

  PhysicsRender run() {
    for (const auto& m : streams_.impacts) impact(m);
    for (const auto& m : streams_.contacts) contacts(m);
    return render();
  }

 private:
  struct Segment {
    std::int64_t from;
    int scene;
  };
  struct PathState {
    bool has_texel = false;
    int i = 0, j = 0;
    Eigen::Vector3f normal{0, 0, 1};
    bool has_vn = false;
    double vn = 0.0;
  };

  int sceneIndex(const std::string& name) {
    for (std::size_t k = 0; k < scenes_.size(); ++k)
      if (scenes_[k].name == name) return int(k);
    scenes_.push_back(scene_for_(name));
    return int(scenes_.size() - 1);
  }
  std::size_t segmentAt(std::int64_t utime) const {
    const auto it = std::upper_bound(switches_.begin(), switches_.end(), utime,
                                     [](std::int64_t t, const Segment& s) { return t < s.from; });
    return std::size_t(it - switches_.begin()) - 1;
  }
  std::int64_t sampleAt(std::int64_t utime, double delay_s = 0.0) const {
    return std::max<std::int64_t>(0, std::llround((double(utime - origin_) * 1e-6 + delay_s) * o_.sample_rate_hz));
  }

  // World -> body frame at `utime`: the newest pose at or before it, moved on by its velocities.
  bool objectFrame(std::size_t segment, int body, std::int64_t utime, Eigen::Isometry3d& world_to_body) const {
    const auto& poses = streams_.poses;
    auto it = std::upper_bound(poses.begin(), poses.end(), utime,
                               [](std::int64_t t, const thx_msgs::physics_poses_t& p) { return t < p.utime; });
    if (it == poses.begin()) return false;
    const thx_msgs::physics_poses_t& p = *(it - 1);
    if (p.utime < switches_[segment].from || body >= p.num_bodies) return false;
    const auto b = std::size_t(body);
    const double dt = double(utime - p.utime) * 1e-6;
    const Eigen::Vector3d c = vec(p.p_world[b]) + dt * vec(p.v_world[b]);
    Eigen::Quaterniond q(p.q_world[b][0], p.q_world[b][1], p.q_world[b][2], p.q_world[b][3]);
    const Eigen::Vector3d w = vec(p.w_world[b]);
    if (w.norm() * dt > 0) q = Eigen::Quaterniond(Eigen::AngleAxisd(w.norm() * dt, w.normalized())) * q;
    Eigen::Isometry3d body_to_world = Eigen::Isometry3d::Identity();
    body_to_world.linear() = q.normalized().toRotationMatrix();
    body_to_world.translation() = c;
    world_to_body = body_to_world.inverse();
    return true;
  }

  // Strikes `body` of the segment's scene with impulse J (world) at p (world); false if silent.
  bool strike(std::size_t segment, int body, std::int64_t sample, std::int64_t utime, const Eigen::Vector3d& p,
              const Eigen::Vector3d& J, double pulse_s) {
    const int si = switches_[segment].scene;
    const SoundingScene& sc = scenes_[std::size_t(si)];
    const ModalBody* mb = nullptr;
    Eigen::Vector3d point, direction;
    if (body == thx_msgs::physics_impact_t::BODY_SURFACE) {
      mb = sc.surface.get();
      point = sc.mapping.toLocal(p);
      direction = sc.mapping.directionToLocal(J);
      for (int a = 0; a < 2; ++a) {  // the slab is the texture's one span; the texture repeats
        const double size = sc.mapping.size_m[a];
        point[a] -= size * std::floor(point[a] / size + 0.5);
      }
      point.z() = std::clamp(point.z(), -sc.slab_thickness_m, 0.0);
    } else if (body >= 0 && std::size_t(body) < sc.objects.size() && sc.objects[std::size_t(body)]) {
      Eigen::Isometry3d to_body;
      if (!objectFrame(segment, body, utime, to_body)) return false;
      mb = sc.objects[std::size_t(body)].get();
      point = to_body * p;
      direction = to_body.linear() * J;
    }
    if (!mb || mb->size() == 0) return false;
    std::vector<double> g = mb->gainsAt(point, direction);
    if (pulse_s > 0)
      for (std::size_t i = 0; i < g.size(); ++i)
        g[i] *= halfSinePulseFactor(2.0 * std::numbers::pi * mb->modes().frequency_hz[i], pulse_s);
    if (std::all_of(g.begin(), g.end(), [](double x) { return x == 0.0; })) return false;
    strikes_.push_back({sample, si, body, std::move(g)});
    return true;
  }

  void impact(const thx_msgs::physics_impact_t& m) {
    if (!(m.impulse > 0.0)) return;
    const std::size_t seg = segmentAt(m.utime);
    const scene::Scene& scene = scenes_[std::size_t(switches_[seg].scene)].scene;
    double tau = 0.0;
    try {
      tau = hertzContactDuration(hertzSide(scene, m.body_a), hertzSide(scene, m.body_b), m.v_approach);
    } catch (const std::invalid_argument&) {
      tau = 0.0;  // no elastic side to set a duration (the pen on a rigid body): an ideal impulse
    }
    const std::int64_t sample = sampleAt(m.utime, 0.5 * tau);
    const Eigen::Vector3d J = m.impulse * vec(m.n_world), p = vec(m.p_world);
    const bool a = strike(seg, m.body_a, sample, m.utime, p, J, tau);
    const bool b = strike(seg, m.body_b, sample, m.utime, p, -J, tau);
    if (!a && !b) return;
    out_.strikes += std::size_t(a) + std::size_t(b);
    out_.min_contact_s = out_.impacts == 0 ? tau : std::min(out_.min_contact_s, tau);
    out_.max_contact_s = std::max(out_.max_contact_s, tau);
    ++out_.impacts;
  }

  // The object gains +dp at p, the surface -dp: both sides ring.
  void strikePair(std::size_t seg, int object, std::int64_t utime, const Eigen::Vector3d& p, const Eigen::Vector3d& dp,
                  std::size_t& counter) {
    const std::int64_t sample = sampleAt(utime);
    const bool s = strike(seg, thx_msgs::physics_impact_t::BODY_SURFACE, sample, utime, p, -dp, 0.0);
    const bool o = strike(seg, object, sample, utime, p, dp, 0.0);
    out_.strikes += std::size_t(s) + std::size_t(o);
    if (s || o) ++counter;
  }

  void contacts(const thx_msgs::physics_contacts_t& m) {
    const std::size_t seg = segmentAt(m.utime);
    // A new scene, or a gap in the reports (no contact lasted meanwhile): every walk starts anew.
    if (seg != last_segment_ || m.sim_time - m.window > last_sim_time_ + 1e-9) states_.clear();
    last_segment_ = seg;
    last_sim_time_ = m.sim_time;
    const SoundingScene& sc = scenes_[std::size_t(switches_[seg].scene)];
    const Eigen::Vector3d ng = vec(m.n_geometric_world).normalized();
    std::set<int> present;
    const int n = std::clamp(m.num_contacts, 0, int(thx_msgs::physics_contacts_t::MAX_CONTACTS));
    for (int k = 0; k < n; ++k) {
      const int a = m.body_a[k];
      if (m.body_b[k] != thx_msgs::physics_contacts_t::BODY_SURFACE || a < 0 || !(m.mass_a[k] > 0.0)) continue;
      present.insert(a);
      PathState& st = states_[a];
      const Eigen::Vector3d p = vec(m.p_world[k]);
      if (sc.relief) {
        // The relief's geometry is in the physics already: what it does to the object's normal
        // momentum between two reports is the impulse (the static support is not a change).
        const double vn = vec(m.v_world[k]).dot(ng);
        if (st.has_vn && vn != st.vn) strikePair(seg, a, m.utime, p, m.mass_a[k] * (vn - st.vn) * ng, out_.relief_impulses);
        st.has_vn = true;
        st.vn = vn;
        continue;
      }
      const MesoSurface surface{nullptr, tex::Address::Wrap, ng, m.mass_a[k], o_.min_normal_dot};
      const int end = std::min(m.path_start[k] + m.num_texels[k], m.num_path);
      for (int e = std::max(0, m.path_start[k]); e < end; ++e) {
        const thx_msgs::physics_texel_t& t = m.path[std::size_t(e)];
        if (st.has_texel && t.i == st.i && t.j == st.j) continue;  // not entered: still in it
        const Eigen::Vector3f ns = vec(t.n_world).cast<float>();
        if (st.has_texel) {
          const Eigen::Vector3d v = vec(t.v_world);
          const Eigen::Vector3d dp = mesoMomentum(surface, ns, v) - mesoMomentum(surface, st.normal, v);
          if (dp.squaredNorm() > 0.0)
            strikePair(seg, a, m.utime + std::llround((t.t - m.sim_time) * 1e6), p, dp, out_.meso_impulses);
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

  PhysicsRender render() {
    std::stable_sort(strikes_.begin(), strikes_.end(), [](const Strike& x, const Strike& y) {
      return std::tie(x.scene, x.body, x.sample) < std::tie(y.scene, y.body, y.sample);
    });
    std::int64_t last = 0;
    for (const Strike& s : strikes_) last = std::max(last, s.sample);
    const std::size_t total = strikes_.empty() ? 0 : std::size_t(last) + std::size_t(std::ceil(o_.tail_s * o_.sample_rate_hz)) + 1;
    out_.samples.assign(total, 0.0);
    std::vector<double> buffer;
    for (std::size_t k = 0; k < strikes_.size();) {
      const SoundingScene& sc = scenes_[std::size_t(strikes_[k].scene)];
      const ModalBody& body = strikes_[k].body < 0 ? *sc.surface : *sc.objects[std::size_t(strikes_[k].body)];
      if (std::find(out_.scenes.begin(), out_.scenes.end(), sc.name) == out_.scenes.end()) out_.scenes.push_back(sc.name);
      ResonatorBank bank(o_.sample_rate_hz, body.size());
      if (!bank.setModes(body.modes().frequency_hz, body.modes().decay_per_s))
        throw std::runtime_error(sc.name + ": a mode of " + body.mesh().name + " is not below Nyquist at " +
                                 std::to_string(o_.sample_rate_hz) + " Hz");
      buffer.assign(total, 0.0);
      std::size_t end = k;
      while (end < strikes_.size() && strikes_[end].scene == strikes_[k].scene && strikes_[end].body == strikes_[k].body) ++end;
      std::size_t done = 0;
      for (; k < end; ++k) {
        const Strike& s = strikes_[k];
        const std::size_t until = std::min(std::size_t(s.sample), total);
        if (until > done) bank.render(std::span<double>(buffer).subspan(done, until - done));
        done = std::max(done, until);
        bank.strike(s.gains);
      }
      if (total > done) bank.render(std::span<double>(buffer).subspan(done, total - done));
      for (std::size_t i = 0; i < total; ++i) out_.samples[i] += buffer[i];
    }
    return std::move(out_);
  }

  const PhysicsStreams& streams_;
  const std::function<SoundingScene(const std::string&)>& scene_for_;
  std::int64_t origin_;
  PhysicsSoundOptions o_;
  std::vector<SoundingScene> scenes_;
  std::vector<Segment> switches_;
  std::vector<Strike> strikes_;
  std::map<int, PathState> states_;
  std::size_t last_segment_ = 0;
  double last_sim_time_ = -kInf;
  PhysicsRender out_;
};

}  // namespace

SoundingScene soundingScene(const std::string& name, const scene::Scene& scene, bool relief, const BodyOptions& o,
                            std::shared_ptr<const ModalBody> surface) {
  SoundingScene s;
  s.name = name;
  s.scene = scene;
  s.mapping = scene::planeMapping(scene.surface);
  s.relief = relief;
  s.slab_thickness_m = o.slab_thickness_m.value_or(scene.surface.thickness_m);
  if (surface) {
    s.surface = std::move(surface);
  } else {
    SceneMeshOptions so;
    so.slab_thickness_m = o.slab_thickness_m;
    so.clamp_slab = o.clamp_slab;
    so.slab_cells = o.slab_cells;
    SceneBody slab = slabBody(scene, so);
    slab.mesh.name = "surface (" + slab.material.name + ")";
    s.surface = analysedBody(slab.mesh, slab.material, o);
  }
  SceneMeshOptions mo;
  mo.order = o.object_order;
  mo.slab_cells = 1;  // sceneBodies' slab is not used: the surface is above
  mo.pen = false;     // the pen is not a physics body (its own modes sound in the scrape)
  const std::vector<SceneBody> bodies = sceneBodies(scene, mo);
  std::size_t next = 1;
  for (const scene::SceneObject& obj : scene.objects) {
    if (obj.fixed) {
      s.objects.push_back(nullptr);
      continue;
    }
    const SceneBody& b = bodies[next++];
    s.objects.push_back(analysedBody(b.mesh, b.material, o));
  }
  return s;
}

std::int64_t PhysicsStreams::firstUtime() const {
  std::int64_t t = std::numeric_limits<std::int64_t>::max();
  if (!poses.empty()) t = std::min(t, poses.front().utime);
  if (!impacts.empty()) t = std::min(t, impacts.front().utime);
  if (!contacts.empty()) t = std::min(t, contacts.front().utime);
  return t == std::numeric_limits<std::int64_t>::max() ? 0 : t;
}

PhysicsStreams readPhysicsStreams(const std::string& path) {
  PhysicsStreams s;
  lcm::LogFile log(path, "r");
  if (!log.good()) throw thx_msgs::LogError(path + ": cannot open as an LCM log file");
  long n = 0;
  auto decode = [&](const lcm::LogEvent& e, auto& m) {
    if (e.datalen < 0 || thx_msgs::try_decode(e.data, std::size_t(e.datalen), m) < 0)
      throw thx_msgs::LogError(thx_msgs::LogPosition{path, n, e.channel, e.timestamp}.where() + ": does not decode as " +
                               std::decay_t<decltype(m)>::getTypeName() + " (wrong type or corrupt)");
  };
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    ++n;
    if (e->channel == thx_msgs::kChannelPhysicsPoses) {
      decode(*e, s.poses.emplace_back());
    } else if (e->channel == thx_msgs::kChannelPhysicsImpact) {
      decode(*e, s.impacts.emplace_back());
    } else if (e->channel == thx_msgs::kChannelPhysicsContacts) {
      decode(*e, s.contacts.emplace_back());
    } else if (e->channel == thx_msgs::kChannelHello) {
      thx_msgs::hello_t h;
      decode(*e, h);
      s.hellos.push_back({h.utime, h.scene_name});
    }
  }
  // Poses are looked up by time.
  std::stable_sort(s.poses.begin(), s.poses.end(), [](const auto& a, const auto& b) { return a.utime < b.utime; });
  return s;
}

std::vector<float> mixSessionSound(std::span<const float> scrape, double scrape_scale, std::span<const double> physics,
                                   double peak) {
  std::vector<double> sum(std::max(scrape.size(), physics.size()), 0.0);
  for (std::size_t n = 0; n < scrape.size(); ++n) sum[n] += double(scrape[n]) * scrape_scale;
  for (std::size_t n = 0; n < physics.size(); ++n) sum[n] += physics[n];
  double raw_peak = 0.0;
  for (double x : sum) raw_peak = std::max(raw_peak, std::fabs(x));
  const double gain = raw_peak > 0 ? peak / raw_peak : 0.0;
  std::vector<float> out(sum.size());
  for (std::size_t n = 0; n < sum.size(); ++n) out[n] = float(sum[n] * gain);
  return out;
}

PhysicsRender renderPhysicsStreams(const PhysicsStreams& streams, const SoundingScene& first,
                                   const std::function<SoundingScene(const std::string&)>& scene_for,
                                   std::int64_t origin_utime, const PhysicsSoundOptions& options) {
  return Renderer(streams, first, scene_for, origin_utime, options).run();
}

}  // namespace thx::audio
