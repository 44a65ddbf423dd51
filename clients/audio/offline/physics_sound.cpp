#include "clients/audio/offline/physics_sound.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <stdexcept>

#include <Eigen/Geometry>
#include <thx_msgs/hello_t.hpp>
#include <thx_msgs/log_reader.hpp>

#include "clients/audio/analysis/scene_bodies.hpp"
#include "clients/audio/synthesis/contact_pulse.hpp"
#include "clients/audio/synthesis/fractal_roughness.hpp"
#include "clients/audio/synthesis/meso_impulses.hpp"
#include "clients/audio/synthesis/resonator_bank.hpp"
#include "clients/audio/synthesis/surface_sound.hpp"
#include "scenes/scene_frames.hpp"
#include "thx_msgs/protocol.hpp"

namespace thx::audio {
namespace {

struct Strike {
  std::int64_t sample;
  int scene, body;  // body: -1 the surface, -2 the pen, else objects[] index
  std::vector<double> gains;
};

// A micro-level force segment (two objects rubbing): its force samples, each struck as
// gains x force / fs on the samples after `start` (as the scrape's micro level, scrape_synthesis.cpp).
struct ForceSegment {
  std::int64_t start;
  int scene, body;
  std::vector<double> gains;  // per unit force
  std::vector<double> force;  // N, on samples start + 1 ...
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
    ObjectContactOptions oc = o_.object_contacts;
    for (const SoundingScene& sc : scenes_) {
      const RoughnessOptions r = sceneRoughness(sc.scene);
      oc.enabled = o_.object_contacts.enabled && r.amplitude > 0.0;
      excitations_.push_back(std::make_unique<PhysicsExcitation>(sc, o_.min_normal_dot, oc));
      profiles_.push_back(oc.enabled ? std::make_unique<RoughnessProfile>(r) : nullptr);
    }
    for (const auto& m : streams_.impacts) {
      const std::size_t seg = segmentAt(m.utime);
      excitations_[std::size_t(switches_[seg].scene)]->impact(m, poseLookup(seg), sink(seg));
    }
    for (const auto& m : streams_.contacts) {
      const std::size_t seg = segmentAt(m.utime);
      PhysicsExcitation& x = *excitations_[std::size_t(switches_[seg].scene)];
      if (seg != last_segment_) x.reset();  // a new scene: every walk starts anew
      last_segment_ = seg;
      x.contacts(m, poseLookup(seg), sink(seg));
    }
    bool first = true;
    for (const auto& x : excitations_) {
      const PhysicsExcitationCounts& c = x->counts();
      out_.impacts += c.impacts;
      out_.meso_impulses += c.meso_impulses;
      out_.relief_impulses += c.relief_impulses;
      out_.strikes += c.strikes;
      out_.object_impacts += c.object_impacts;
      out_.object_contact_segments += c.object_contact_segments;
      if (c.impacts == 0) continue;
      out_.min_contact_s = first ? c.min_contact_s : std::min(out_.min_contact_s, c.min_contact_s);
      out_.max_contact_s = std::max(out_.max_contact_s, c.max_contact_s);
      first = false;
    }
    return render();
  }

 private:
  struct Segment {
    std::int64_t from;
    int scene;
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

  // The newest pose at or before a time, within the segment's scene.
  PoseLookup poseLookup(std::size_t segment) const {
    return [this, segment](std::int64_t utime) -> const thx_msgs::physics_poses_t* {
      const auto& poses = streams_.poses;
      auto it = std::upper_bound(poses.begin(), poses.end(), utime,
                                 [](std::int64_t t, const thx_msgs::physics_poses_t& p) { return t < p.utime; });
      if (it == poses.begin() || (it - 1)->utime < switches_[segment].from) return nullptr;
      return &*(it - 1);
    };
  }

  // Each mode's gain at the strike's point, times the Hertz pulse factor; kept unless all 0.
  StrikeSink sink(std::size_t segment) {
    return [this, segment](const BodyStrike& b) {
      std::vector<double> g = b.modal->gainsAt(b.point, b.impulse);
      if (b.micro) return forceSegment(segment, b, std::move(g));
      if (b.pulse_s > 0)
        for (std::size_t i = 0; i < g.size(); ++i)
          g[i] *= halfSinePulseFactor(2.0 * std::numbers::pi * b.modal->modes().frequency_hz[i], b.pulse_s);
      if (std::all_of(g.begin(), g.end(), [](double x) { return x == 0.0; })) return false;
      strikes_.push_back({sampleAt(b.utime, b.delay_s), switches_[segment].scene, b.body, std::move(g)});
      return true;
    };
  }

  // A segment's force samples from the scene's roughness profile (microForce); kept unless all 0.
  bool forceSegment(std::size_t segment, const BodyStrike& b, std::vector<double> gains) {
    const int scene = switches_[segment].scene;
    const RoughnessProfile* profile = profiles_[std::size_t(scene)].get();
    const std::int64_t start = sampleAt(b.utime), end = sampleAt(b.end_utime);
    if (!profile || end <= start || std::all_of(gains.begin(), gains.end(), [](double x) { return x == 0.0; })) return false;
    std::vector<double> force(std::size_t(end - start), 0.0);
    microForce(*profile, b.s0, b.s1, b.f0, b.f1, force);
    if (std::all_of(force.begin(), force.end(), [](double x) { return x == 0.0; })) return false;
    segments_.push_back({start, scene, b.body, std::move(gains), std::move(force)});
    return true;
  }

  PhysicsRender render() {
    std::stable_sort(strikes_.begin(), strikes_.end(), [](const Strike& x, const Strike& y) {
      return std::tie(x.scene, x.body, x.sample) < std::tie(y.scene, y.body, y.sample);
    });
    std::stable_sort(segments_.begin(), segments_.end(), [](const ForceSegment& x, const ForceSegment& y) {
      return std::tie(x.scene, x.body, x.start) < std::tie(y.scene, y.body, y.start);
    });
    std::int64_t last = 0;
    for (const Strike& s : strikes_) last = std::max(last, s.sample);
    for (const ForceSegment& s : segments_) last = std::max(last, s.start + std::int64_t(s.force.size()));
    const bool any = !strikes_.empty() || !segments_.empty();
    const std::size_t total = any ? std::size_t(last) + std::size_t(std::ceil(o_.tail_s * o_.sample_rate_hz)) + 1 : 0;
    out_.samples.assign(total, 0.0);
    std::vector<double> buffer;
    std::size_t k = 0, g = 0;
    while (k < strikes_.size() || g < segments_.size()) {
      // The next body (in scene, body order) with strikes or force segments.
      const bool from_strike = g == segments_.size() ||
                               (k < strikes_.size() && std::tie(strikes_[k].scene, strikes_[k].body) <=
                                                           std::tie(segments_[g].scene, segments_[g].body));
      const int scene = from_strike ? strikes_[k].scene : segments_[g].scene;
      const int id = from_strike ? strikes_[k].body : segments_[g].body;
      const SoundingScene& sc = scenes_[std::size_t(scene)];
      const ModalBody& body = id == -1 ? *sc.surface : id == -2 ? *sc.pen : *sc.objects[std::size_t(id)];
      if (std::find(out_.scenes.begin(), out_.scenes.end(), sc.name) == out_.scenes.end()) out_.scenes.push_back(sc.name);
      ResonatorBank bank(o_.sample_rate_hz, body.size());
      if (!bank.setModes(body.modes().frequency_hz, body.modes().decay_per_s))
        throw std::runtime_error(sc.name + ": a mode of " + body.mesh().name + " is not below Nyquist at " +
                                 std::to_string(o_.sample_rate_hz) + " Hz");
      buffer.assign(total, 0.0);
      const auto same = [&](const auto& x) { return x.scene == scene && x.body == id; };
      std::size_t k_end = k, g_end = g;
      while (k_end < strikes_.size() && same(strikes_[k_end])) ++k_end;
      while (g_end < segments_.size() && same(segments_[g_end])) ++g_end;
      renderBody(bank, std::span<const Strike>(strikes_).subspan(k, k_end - k),
                 std::span<const ForceSegment>(segments_).subspan(g, g_end - g), buffer);
      k = k_end;
      g = g_end;
      for (std::size_t i = 0; i < total; ++i) out_.samples[i] += buffer[i];
    }
    return std::move(out_);
  }

  // One body's strikes (each before the sample it falls on) and force segments (sample by sample
  // while one runs: every sample first strikes the sum of gains x force / fs, then is rendered).
  void renderBody(ResonatorBank& bank, std::span<const Strike> strikes, std::span<const ForceSegment> segments,
                  std::vector<double>& buffer) const {
    const std::size_t total = buffer.size();
    std::vector<const ForceSegment*> active;
    std::vector<double> g(bank.size(), 0.0);
    std::size_t done = 0, k = 0, s = 0;
    const auto firstOwned = [](const ForceSegment& x) { return std::size_t(x.start) + 1; };
    while (done < total) {
      for (; k < strikes.size() && std::size_t(strikes[k].sample) <= done; ++k) bank.strike(strikes[k].gains);
      for (; s < segments.size() && firstOwned(segments[s]) <= done; ++s) active.push_back(&segments[s]);
      if (active.empty()) {
        std::size_t until = total;
        if (k < strikes.size()) until = std::min(until, std::size_t(strikes[k].sample));
        if (s < segments.size()) until = std::min(until, firstOwned(segments[s]));
        bank.render(std::span<double>(buffer).subspan(done, until - done));
        done = until;
        continue;
      }
      std::fill(g.begin(), g.end(), 0.0);
      bool struck = false;
      for (std::size_t a = 0; a < active.size();) {
        const ForceSegment& x = *active[a];
        const std::size_t n = done - firstOwned(x);
        const double j = n < x.force.size() ? x.force[n] / o_.sample_rate_hz : 0.0;
        if (j != 0.0) {
          for (std::size_t i = 0; i < g.size(); ++i) g[i] += x.gains[i] * j;
          struck = true;
        }
        if (n + 1 >= x.force.size())
          active.erase(active.begin() + std::ptrdiff_t(a));
        else
          ++a;
      }
      if (struck) bank.strike(g);
      bank.render(std::span<double>(buffer).subspan(done, 1));
      ++done;
    }
  }

  const PhysicsStreams& streams_;
  const std::function<SoundingScene(const std::string&)>& scene_for_;
  std::int64_t origin_;
  PhysicsSoundOptions o_;
  std::vector<SoundingScene> scenes_;
  std::vector<Segment> switches_;
  std::vector<Strike> strikes_;
  std::vector<ForceSegment> segments_;
  std::vector<std::unique_ptr<PhysicsExcitation>> excitations_;  // by scene
  std::vector<std::unique_ptr<RoughnessProfile>> profiles_;       // by scene; null: no micro level there
  std::size_t last_segment_ = 0;
  PhysicsRender out_;
};

}  // namespace

std::int64_t PhysicsStreams::firstUtime() const {
  std::int64_t t = std::numeric_limits<std::int64_t>::max();
  if (!poses.empty()) t = std::min(t, poses.front().utime);
  if (!impacts.empty()) t = std::min(t, impacts.front().utime);
  if (!contacts.empty()) t = std::min(t, contacts.front().utime);
  return t == std::numeric_limits<std::int64_t>::max() ? 0 : t;
}

PhysicsStreams readPhysicsStreams(const std::string& path) {
  PhysicsStreams s;
  thx_msgs::LogReader log(path);
  thx_msgs::LogRecord e;
  while (log.next(e)) {
    const thx_msgs::LogPosition at{path, log.events(), e.channel, e.timestamp_us};
    if (e.channel == thx_msgs::kChannelPhysicsPoses) {
      thx_msgs::decodeLogRecord(e, at, s.poses.emplace_back());
    } else if (e.channel == thx_msgs::kChannelPhysicsImpact) {
      thx_msgs::decodeLogRecord(e, at, s.impacts.emplace_back());
    } else if (e.channel == thx_msgs::kChannelPhysicsContacts) {
      thx_msgs::decodeLogRecord(e, at, s.contacts.emplace_back());
    } else if (e.channel == thx_msgs::kChannelHello) {
      thx_msgs::hello_t h;
      thx_msgs::decodeLogRecord(e, at, h);
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

std::vector<float> scaledSessionSound(std::span<const double> scrape, std::span<const double> physics, double gain) {
  std::vector<float> out(std::max(scrape.size(), physics.size()));
  for (std::size_t n = 0; n < out.size(); ++n)
    out[n] = float(((n < scrape.size() ? scrape[n] : 0.0) + (n < physics.size() ? physics[n] : 0.0)) * gain);
  return out;
}

PhysicsRender renderPhysicsStreams(const PhysicsStreams& streams, const SoundingScene& first,
                                   const std::function<SoundingScene(const std::string&)>& scene_for,
                                   std::int64_t origin_utime, const PhysicsSoundOptions& options) {
  return Renderer(streams, first, scene_for, origin_utime, options).run();
}

}  // namespace thx::audio
