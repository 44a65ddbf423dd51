#include "clients/physics_client/driver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "base/json_text.hpp"

namespace thx::physclient {

Driver::Driver(PhysicsScene& scene, EventSink& sink, const DriverOptions& options)
    : scene_(scene), sink_(sink), options_(options) {
  summary_.scene_name = scene_.sceneSurface().scene_name;
  summary_.mesh_surface = scene_.meshGround() != nullptr;
  for (const BodyState& b : scene_.bodies()) {
    ObjectSummary o;
    o.name = scene_.scene().objects[std::size_t(b.id)].name;
    o.fixed = scene_.scene().objects[std::size_t(b.id)].fixed;
    o.start_world = o.end_world = b.p_world;
    o.end_local = scene_.surface().toLocal(b.p_world);
    o.start_h_m = o.end_local.z();
    summary_.objects.push_back(o);
  }
  pens_.resize(std::size_t(scene_.penCount()));
  summary_.pens.resize(pens_.size());
  for (std::size_t i = 0; i < pens_.size(); ++i) summary_.pens[i].device = int(i);
}

void Driver::step(const std::optional<Eigen::Vector3d>& tip_world, std::int64_t ref_tick) {
  if (tip_world) scene_.setPenTip(*tip_world);
  if (ref_tick >= 0 && !pens_.empty()) pens_[0].last_ref_tick = ref_tick;
  stepScene();
}

void Driver::step(const std::vector<PenInput>& pens) {
  for (std::size_t i = 0; i < pens.size() && i < pens_.size(); ++i) {
    if (pens[i].tip_world) scene_.setPenTip(int(i), *pens[i].tip_world);
    if (pens[i].q_world) scene_.setPenOrientation(int(i), *pens[i].q_world);
    if (pens[i].ref_tick >= 0) pens_[i].last_ref_tick = pens[i].ref_tick;
  }
  stepScene();
}

void Driver::stepScene() {
  scene_.step(dt());
  const double t = scene_.simTime();
  summary_.steps = scene_.steps();
  summary_.sim_time_s = t;

  for (std::size_t i = 0; i < pens_.size(); ++i) {
    const PenForce& f = scene_.penForce(int(i));
    PenState& state = pens_[i];
    PenSummary& p = summary_.pens[i];
    const double sent = f.sent_world.norm(), raw = f.raw_world.norm();
    p.max_force_raw_n = std::max(p.max_force_raw_n, raw);
    p.max_force_sent_n = std::max(p.max_force_sent_n, sent);
    summary_.max_force_raw_n = std::max(summary_.max_force_raw_n, raw);
    summary_.max_force_sent_n = std::max(summary_.max_force_sent_n, sent);
    if (f.in_contact) {
      ++p.contact_steps;
      state.force_sum += sent;
      p.mean_force_in_contact_n = state.force_sum / double(p.contact_steps);
      ++summary_.pen_contact_steps;
      force_sum_ += sent;
      summary_.mean_force_in_contact_n = force_sum_ / double(summary_.pen_contact_steps);
    }
    if (f.clamped) ++p.clamped_steps, ++summary_.clamped_steps;
    const bool nonzero = sent > 0.0;
    if (nonzero) ++p.force_steps, ++summary_.force_steps;
    if (nonzero || state.force_was_nonzero) sink_.penForce(scene_, int(i), f, state.last_ref_tick);
    state.force_was_nonzero = nonzero;
  }

  const std::vector<Impact>& im = scene_.impacts();
  if (!im.empty()) {
    summary_.impacts += std::int64_t(im.size());
    for (const Impact& i : im) {
      summary_.pen_impacts += (i.body_a == kBodyPen || i.body_b == kBodyPen);
      if (i.pen >= 0 && std::size_t(i.pen) < summary_.pens.size()) ++summary_.pens[std::size_t(i.pen)].impacts;
    }
    sink_.impacts(scene_, im);
  }

  for (std::size_t i = 0; i < summary_.objects.size(); ++i) {
    const BodyState b = scene_.body(int(i));
    summary_.objects[i].end_world = b.p_world;
    summary_.objects[i].end_local = scene_.surface().toLocal(b.p_world);
    summary_.objects[i].max_rise_m =
        std::max(summary_.objects[i].max_rise_m, summary_.objects[i].end_local.z() - summary_.objects[i].start_h_m);
    summary_.objects[i].end_speed_m_per_s = b.v_world.norm();
    summary_.objects[i].max_speed_m_per_s = std::max(summary_.objects[i].max_speed_m_per_s, b.v_world.norm());
  }

  const double eps = 0.25 * dt();
  if (options_.pose_hz > 0 && t + eps >= next_pose_t_) {
    // physics_poses_t has one pen: the first's (docs/physics.md, "Several pens").
    const std::int64_t ref_tick = pens_.empty() ? -1 : pens_[0].last_ref_tick;
    sink_.poses(scene_, ref_tick, scene_.penForce().sent_world);
    ++summary_.pose_reports;
    next_pose_t_ = std::max(next_pose_t_ + 1.0 / options_.pose_hz, t - eps);
  }
  if (options_.contact_hz > 0 && t + eps >= next_contact_t_) {
    flush();
    next_contact_t_ = std::max(next_contact_t_ + 1.0 / options_.contact_hz, t - eps);
  }
}

void Driver::flush() {
  const double t = scene_.simTime();
  std::vector<LastingContact> c = scene_.takeContacts();
  for (const LastingContact& lc : c) {
    if (lc.body_a < 0 || lc.body_b < 0) continue;  // the plane or the pen
    noteTouch(lc.body_a, lc.body_b, t);
    noteTouch(lc.body_b, lc.body_a, t);
  }
  if (!c.empty()) {
    sink_.contacts(scene_, c, t - last_contact_t_);
    ++summary_.contact_reports;
  }
  last_contact_t_ = t;
}

void Driver::noteTouch(int id, int other, double t) {
  std::vector<Touch>& touched = summary_.objects.at(std::size_t(id)).touched;
  const std::string& name = summary_.objects.at(std::size_t(other)).name;
  for (const Touch& k : touched)
    if (k.name == name) return;
  touched.push_back({name, t});
}

namespace {
// A mean over contact steps carried on: `earlier`'s over its steps, then `current`'s over its.
double continuedMean(double earlier, std::int64_t earlier_steps, double current, std::int64_t current_steps) {
  const std::int64_t steps = earlier_steps + current_steps;
  return steps > 0 ? (earlier * double(earlier_steps) + current * double(current_steps)) / double(steps) : current;
}
}  // namespace

RunSummary continuedRun(const RunSummary& earlier, RunSummary current) {
  current.mean_force_in_contact_n = continuedMean(earlier.mean_force_in_contact_n, earlier.pen_contact_steps,
                                                  current.mean_force_in_contact_n, current.pen_contact_steps);
  current.steps += earlier.steps;
  current.sim_time_s += earlier.sim_time_s;
  current.pen_contact_steps += earlier.pen_contact_steps;
  current.force_steps += earlier.force_steps;
  current.clamped_steps += earlier.clamped_steps;
  current.max_force_raw_n = std::max(current.max_force_raw_n, earlier.max_force_raw_n);
  current.max_force_sent_n = std::max(current.max_force_sent_n, earlier.max_force_sent_n);
  current.impacts += earlier.impacts;
  current.pen_impacts += earlier.pen_impacts;
  current.contact_reports += earlier.contact_reports;
  current.pose_reports += earlier.pose_reports;
  for (std::size_t i = 0; i < current.pens.size() && i < earlier.pens.size(); ++i) {
    PenSummary& c = current.pens[i];
    const PenSummary& e = earlier.pens[i];
    c.mean_force_in_contact_n = continuedMean(e.mean_force_in_contact_n, e.contact_steps, c.mean_force_in_contact_n,
                                              c.contact_steps);
    c.contact_steps += e.contact_steps, c.force_steps += e.force_steps, c.clamped_steps += e.clamped_steps;
    c.max_force_raw_n = std::max(c.max_force_raw_n, e.max_force_raw_n);
    c.max_force_sent_n = std::max(c.max_force_sent_n, e.max_force_sent_n);
    c.impacts += e.impacts;
  }
  return current;
}

namespace {
std::string vec(const Eigen::Vector3d& v) {
  char b[128];
  std::snprintf(b, sizeof b, "[%.9g, %.9g, %.9g]", v.x(), v.y(), v.z());
  return b;
}
using json::quoted;
}  // namespace

void writeSummaryJson(const std::string& path, const std::string& scene_file, const RunSummary& s) {
  std::ofstream out(path);
  if (!out) throw thx::Error(thx::Error::Kind::Io, path + ": cannot write the summary");
  char b[512];
  out << "{\n  \"scene\": " << quoted(scene_file) << ",\n  \"scene_name\": " << quoted(s.scene_name)
      << ",\n  \"scene_switches\": " << s.scene_switches << ",\n";
  std::snprintf(b, sizeof b,
                "  \"steps\": %lld,\n  \"sim_time_s\": %.9g,\n  \"pen_contact_steps\": %lld,\n  \"force_steps\": %lld,\n"
                "  \"clamped_steps\": %lld,\n  \"max_force_raw_n\": %.9g,\n  \"max_force_sent_n\": %.9g,\n"
                "  \"mean_force_in_contact_n\": %.9g,\n  \"impacts\": %lld,\n  \"pen_impacts\": %lld,\n"
                "  \"contact_reports\": %lld,\n  \"pose_reports\": %lld,\n",
                (long long)s.steps, s.sim_time_s, (long long)s.pen_contact_steps, (long long)s.force_steps,
                (long long)s.clamped_steps, s.max_force_raw_n, s.max_force_sent_n, s.mean_force_in_contact_n,
                (long long)s.impacts, (long long)s.pen_impacts, (long long)s.contact_reports, (long long)s.pose_reports);
  out << b;
  if (s.pens.size() > 1) {  // a one-pen run's summary stays as it was: its pen is the fields above
    out << "  \"pens\": [";
    for (std::size_t i = 0; i < s.pens.size(); ++i) {
      const PenSummary& p = s.pens[i];
      std::snprintf(b, sizeof b,
                    "%s\n    {\"device\": %d, \"contact_steps\": %lld, \"force_steps\": %lld, \"clamped_steps\": %lld, "
                    "\"max_force_raw_n\": %.9g, \"max_force_sent_n\": %.9g, \"mean_force_in_contact_n\": %.9g, "
                    "\"impacts\": %lld}",
                    i ? "," : "", p.device, (long long)p.contact_steps, (long long)p.force_steps, (long long)p.clamped_steps,
                    p.max_force_raw_n, p.max_force_sent_n, p.mean_force_in_contact_n, (long long)p.impacts);
      out << b;
    }
    out << "\n  ],\n";
  }
  out << "  \"objects\": [";
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    const ObjectSummary& o = s.objects[i];
    out << (i ? ",\n" : "\n") << "    {\"name\": " << quoted(o.name) << ", \"start_world\": " << vec(o.start_world)
        << ", \"end_world\": " << vec(o.end_world) << ", \"end_surface_local\": " << vec(o.end_local)
        << ", \"displacement_m\": " << (o.end_world - o.start_world).norm()
        << ", \"max_rise_m\": " << o.max_rise_m << ", \"max_speed_m_per_s\": " << o.max_speed_m_per_s << ", \"end_speed_m_per_s\": " << o.end_speed_m_per_s
        << ", \"touched\": [";
    for (std::size_t k = 0; k < o.touched.size(); ++k)
      out << (k ? ", " : "") << "{\"name\": " << quoted(o.touched[k].name) << ", \"first_s\": " << o.touched[k].first_s << "}";
    out << "]}";
  }
  out << "\n  ]";
  if (s.hapticd.online) {
    std::snprintf(b, sizeof b,
                  ",\n  \"hapticd\": {\"device_states\": %lld, \"client_force_states\": %lld, "
                  "\"max_cmd_with_client_force_n\": %.9g, \"forces_sent\": %lld, \"stale_steps\": %lld, "
                  "\"missed_steps\": %lld}",
                  (long long)s.hapticd.device_states, (long long)s.hapticd.client_force_states,
                  s.hapticd.max_cmd_with_client_force_n, (long long)s.hapticd.forces_sent,
                  (long long)s.hapticd.stale_steps, (long long)s.hapticd.missed_steps);
    out << b;
  }
  out << "\n}\n";
  if (!out) throw thx::Error(thx::Error::Kind::Io, path + ": write failed");
}

void printSummary(std::FILE* out, const RunSummary& s) {
  std::fprintf(out, "physics-client: %lld steps, %.3f s simulated; scene '%s', %lld scene switches followed\n",
               (long long)s.steps, s.sim_time_s, s.scene_name.c_str(), (long long)s.scene_switches);
  std::fprintf(out, "  pen: in contact %lld steps, force sent %lld steps, max |f| %.4f N (raw %.4f N), mean in contact %.4f N, clamped %lld steps\n",
               (long long)s.pen_contact_steps, (long long)s.force_steps, s.max_force_sent_n, s.max_force_raw_n,
               s.mean_force_in_contact_n, (long long)s.clamped_steps);
  if (s.pens.size() > 1)
    for (std::size_t i = 0; i < s.pens.size(); ++i) {
      const PenSummary& p = s.pens[i];
      std::fprintf(out, "  pen %zu (device %d): in contact %lld steps, force sent %lld steps, max |f| %.4f N (raw %.4f N), mean in contact %.4f N, %lld impacts\n",
                   i, p.device, (long long)p.contact_steps, (long long)p.force_steps, p.max_force_sent_n, p.max_force_raw_n,
                   p.mean_force_in_contact_n, (long long)p.impacts);
    }
  std::fprintf(out, "  events: %lld impacts (%lld with the pen), %lld contact reports, %lld pose reports\n",
               (long long)s.impacts, (long long)s.pen_impacts, (long long)s.contact_reports, (long long)s.pose_reports);
  if (s.hapticd.online)
    std::fprintf(out,
                 "  hapticd: %lld device states received, %lld with FLAG_CLIENT_FORCE (max |f_cmd| then %.4f N); "
                 "%lld forces sent; %lld steps reused a pose, %lld grid points missed\n",
                 (long long)s.hapticd.device_states, (long long)s.hapticd.client_force_states,
                 s.hapticd.max_cmd_with_client_force_n, (long long)s.hapticd.forces_sent,
                 (long long)s.hapticd.stale_steps, (long long)s.hapticd.missed_steps);
  for (const ObjectSummary& o : s.objects) {
    if (o.fixed) {  // obstacles never move: only what touched them
      if (o.touched.empty()) continue;
      std::fprintf(out, "  %-12s (fixed) touched by", o.name.c_str());
      for (const Touch& k : o.touched) std::fprintf(out, " %s (%.3f s)", k.name.c_str(), k.first_s);
      std::fputc('\n', out);
      continue;
    }
    const Eigen::Vector3d d = o.end_world - o.start_world;
    // On a plane: where on it and how high above it; on a mesh: where in its frame (the bowl's).
    char where[128];
    if (s.mesh_surface)
      std::snprintf(where, sizeof where, "in the surface frame (%+.4f, %+.4f, %+.4f) m", o.end_local.x(), o.end_local.y(),
                    o.end_local.z());
    else
      std::snprintf(where, sizeof where, "on the surface (%+.4f, %+.4f) m h %+.2f mm", o.end_local.x(), o.end_local.y(),
                    o.end_local.z() * 1e3);
    std::fprintf(out, "  %-12s moved %.1f mm (%+.1f, %+.1f, %+.1f) mm to (%+.4f, %+.4f, %+.4f) m, %s; max speed %.3f m/s, end %.2g m/s",
                 o.name.c_str(), d.norm() * 1e3, d.x() * 1e3, d.y() * 1e3, d.z() * 1e3, o.end_world.x(), o.end_world.y(),
                 o.end_world.z(), where, o.max_speed_m_per_s, o.end_speed_m_per_s);
    // A lift worth naming (a pinch): well above the settling of a body on its support.
    if (o.max_rise_m > 0.002) std::fprintf(out, "; rose at most %.1f mm", o.max_rise_m * 1e3);
    std::fputc('\n', out);
  }
}

}  // namespace thx::physclient
