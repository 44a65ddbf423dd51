#include "device/hand_script.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "device/hand_script_detail.hpp"

namespace thx::dev {

namespace {

using detail::formatNumber;

// Minimum-jerk blend: zero velocity and acceleration at both ends, so chained moves join
// without a kick in the hand force.
double minJerk(double s) { return s * s * s * (10.0 + s * (-15.0 + 6.0 * s)); }
double minJerkRate(double s) { return 30.0 * s * s * (1.0 - s) * (1.0 - s); }  // d/ds

const char* kindName(const HandStep& step) {
  switch (step.index()) {
    case 0: return "press";
    case 1: return "stroke";
    case 2: return "hold";
    case 3: return "path";
    default: return "move";
  }
}

[[noreturn]] void stepError(std::size_t index, const HandStep& step, const std::string& field,
                            const std::string& problem, const std::string& expected, const std::string& value) {
  std::string where = "hand script step " + std::to_string(index + 1) + " (" + kindName(step);
  if (const auto* path = std::get_if<HandPath>(&step); path && !path->source.empty()) where += " from " + path->source;
  where += ")";
  throw HandScriptError(where + ": " + field + ": " + problem + "; expected " + expected + ", got '" + value + "'",
                        std::get_if<HandPath>(&step) ? std::get<HandPath>(step).source : std::string(), 0, field);
}

const char* rangeProblem(double v) { return std::isfinite(v) ? "out of range" : "not finite"; }

void requirePositive(std::size_t i, const HandStep& step, const char* field, double v, const char* expected) {
  if (!std::isfinite(v) || !(v > 0.0)) stepError(i, step, field, rangeProblem(v), expected, formatNumber(v));
}

void requireNonNegative(std::size_t i, const HandStep& step, const char* field, double v, const char* expected) {
  if (!std::isfinite(v) || v < 0.0) stepError(i, step, field, rangeProblem(v), expected, formatNumber(v));
}

void requireFinite(std::size_t i, const HandStep& step, const char* field, const Eigen::Vector2d& p) {
  if (!p.allFinite())
    stepError(i, step, field, "not finite", "finite surface-local [x, y] in m",
              "[" + formatNumber(p.x()) + ", " + formatNumber(p.y()) + "]");
}

void validateStep(std::size_t i, const HandStep& step) {
  if (const auto* press = std::get_if<HandPress>(&step)) {
    requireFinite(i, step, "position_m", press->position_m);
    requireNonNegative(i, step, "force_n", press->force_n, "a force >= 0 N");
    requirePositive(i, step, "duration_s", press->duration_s, "a duration > 0 s");
  } else if (const auto* stroke = std::get_if<HandStroke>(&step)) {
    requireFinite(i, step, "from_m", stroke->from_m);
    requireFinite(i, step, "to_m", stroke->to_m);
    if (stroke->from_m == stroke->to_m)
      stepError(i, step, "to_m", "equals from_m", "a stroke of non-zero length",
                "[" + formatNumber(stroke->to_m.x()) + ", " + formatNumber(stroke->to_m.y()) + "]");
    requirePositive(i, step, "speed_m_per_s", stroke->speed_m_per_s, "a speed > 0 m/s");
    requireNonNegative(i, step, "force_n", stroke->force_n, "a force >= 0 N");
  } else if (const auto* hold = std::get_if<HandHold>(&step)) {
    requirePositive(i, step, "duration_s", hold->duration_s, "a duration > 0 s");
  } else if (const auto* move = std::get_if<HandMove>(&step)) {
    const auto text = [](const Eigen::Vector3d& v) {
      return "[" + formatNumber(v.x()) + ", " + formatNumber(v.y()) + ", " + formatNumber(v.z()) + "]";
    };
    if (!move->to_m.allFinite()) stepError(i, step, "to_m", "not finite", "finite [x, y, z] in m", text(move->to_m));
    if (!move->push_n.allFinite()) stepError(i, step, "push_n", "not finite", "finite [x, y, z] in N", text(move->push_n));
    requirePositive(i, step, "duration_s", move->duration_s, "a duration > 0 s");
  } else {
    const HandPath& path = std::get<HandPath>(step);
    if (path.samples.size() < 2)
      stepError(i, step, "samples", "too few samples", "at least 2", std::to_string(path.samples.size()));
    for (std::size_t k = 0; k < path.samples.size(); ++k) {
      const PathSample& s = path.samples[k];
      const std::string at = "samples[" + std::to_string(k) + "].";
      if (!std::isfinite(s.t_s) || s.t_s < 0.0)
        stepError(i, step, at + "t_s", rangeProblem(s.t_s), "a time >= 0 s", formatNumber(s.t_s));
      if (k > 0 && !(s.t_s > path.samples[k - 1].t_s))
        stepError(i, step, at + "t_s", "time does not increase",
                  "a time > " + formatNumber(path.samples[k - 1].t_s) + " s", formatNumber(s.t_s));
      if (!s.p_m.allFinite())
        stepError(i, step, at + "p_m", "not finite", "finite [x, y] in m",
                  "[" + formatNumber(s.p_m.x()) + ", " + formatNumber(s.p_m.y()) + "]");
      if (!std::isfinite(s.force_n) || s.force_n < 0.0)
        stepError(i, step, at + "force_n", rangeProblem(s.force_n), "a force >= 0 N", formatNumber(s.force_n));
    }
  }
}

void validateOptions(const HandScriptOptions& o) {
  const auto check = [](const char* field, double v, bool allow_zero) {
    if (!std::isfinite(v) || v < 0.0 || (!allow_zero && v == 0.0))
      throw HandScriptError(std::string("hand script options: ") + field + ": out of range; expected " +
                                (allow_zero ? "a value >= 0" : "a value > 0") + ", got '" + formatNumber(v) + "'",
                            {}, 0, field);
  };
  check("hover_height_m", o.hover_height_m, false);
  check("approach_s", o.approach_s, false);
  check("force_ramp_s", o.force_ramp_s, false);
  check("transit_speed_m_per_s", o.transit_speed_m_per_s, false);
  check("min_transit_s", o.min_transit_s, true);
  check("stroke_ramp_s", o.stroke_ramp_s, false);
}

struct ContactEnds {
  Eigen::Vector2d start_m, end_m;
  double start_force_n, end_force_n;
};

ContactEnds contactEnds(const HandStep& step) {
  if (const auto* press = std::get_if<HandPress>(&step))
    return {press->position_m, press->position_m, press->force_n, press->force_n};
  if (const auto* stroke = std::get_if<HandStroke>(&step))
    return {stroke->from_m, stroke->to_m, stroke->force_n, stroke->force_n};
  const HandPath& path = std::get<HandPath>(step);
  return {path.samples.front().p_m, path.samples.back().p_m, path.samples.front().force_n, path.samples.back().force_n};
}

}  // namespace

HandScript::HandScript() : HandScript(std::vector<HandStep>{}) {}

HandScript::HandScript(std::vector<HandStep> steps, HandScriptOptions options) : options_(options) {
  validateOptions(options_);
  for (std::size_t i = 0; i < steps.size(); ++i) validateStep(i, steps[i]);

  const double h = options_.hover_height_m;
  Eigen::Vector2d first_xy = Eigen::Vector2d::Zero();
  for (const HandStep& step : steps) {
    if (std::holds_alternative<HandHold>(step)) continue;
    const auto* move = std::get_if<HandMove>(&step);
    first_xy = move ? Eigen::Vector2d(move->to_m.head<2>()) : contactEnds(step).start_m;
    break;
  }
  start_m_ = Eigen::Vector3d(first_xy.x(), first_xy.y(), h);

  Eigen::Vector3d cursor = start_m_;
  Eigen::Vector3d push = Eigen::Vector3d::Zero();  // the push the hand has at the cursor
  for (std::size_t i = 0; i < steps.size(); ++i) {
    if (const auto* hold = std::get_if<HandHold>(&steps[i])) {
      addBlend(cursor, cursor, push, push, hold->duration_s, 0.0, 0.0);
    } else if (const auto* move = std::get_if<HandMove>(&steps[i])) {
      addBlend(cursor, move->to_m, push, move->push_n, move->duration_s, 0.0, 0.0);
      cursor = move->to_m;
      push = move->push_n;
    } else {
      addContactStep(steps[i], cursor, push);
    }
  }
  // Ending with a push: ramped out where the hand is, so the force has no step at the end.
  if (push != Eigen::Vector3d::Zero())
    addBlend(cursor, cursor, push, Eigen::Vector3d::Zero(), options_.force_ramp_s, 0.0, 0.0);
  end_m_ = cursor;
  starts_s_.reserve(segments_.size());
  for (const Segment& s : segments_) starts_s_.push_back(s.t0_s);
}

void HandScript::addBlend(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, double f0, double f1, double d_s,
                          double c0, double c1) {
  addBlend(p0, p1, Eigen::Vector3d(0.0, 0.0, -f0), Eigen::Vector3d(0.0, 0.0, -f1), d_s, c0, c1);
}

void HandScript::addBlend(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& push0,
                          const Eigen::Vector3d& push1, double d_s, double c0, double c1) {
  if (!(d_s > 0.0)) return;
  Segment s;
  s.kind = Segment::Kind::Blend;
  s.t0_s = duration_s_;
  s.duration_s = d_s;
  s.p0_m = p0;
  s.p1_m = p1;
  s.push0_n = push0;
  s.push1_n = push1;
  s.c0 = c0;
  s.c1 = c1;
  segments_.push_back(s);
  duration_s_ += d_s;
}

void HandScript::addContactStep(const HandStep& step, Eigen::Vector3d& cursor, Eigen::Vector3d& push) {
  const double h = options_.hover_height_m;
  const ContactEnds ends = contactEnds(step);
  const Eigen::Vector3d above_start(ends.start_m.x(), ends.start_m.y(), h);
  const Eigen::Vector3d at_start(ends.start_m.x(), ends.start_m.y(), 0.0);
  const Eigen::Vector3d at_end(ends.end_m.x(), ends.end_m.y(), 0.0);
  const Eigen::Vector3d above_end(ends.end_m.x(), ends.end_m.y(), h);

  const double hop_m = (above_start - cursor).norm();
  if (hop_m > 0.0 || push != Eigen::Vector3d::Zero())  // a move's push ramps out on the way
    addBlend(cursor, above_start, push, Eigen::Vector3d::Zero(),
             std::max({hop_m / options_.transit_speed_m_per_s, options_.min_transit_s, push.isZero() ? 0.0 : options_.force_ramp_s}),
             0.0, 0.0);
  push = Eigen::Vector3d::Zero();
  addBlend(above_start, at_start, 0.0, 0.0, options_.approach_s, 0.0, 1.0);
  addBlend(at_start, at_start, 0.0, ends.start_force_n, options_.force_ramp_s, 1.0, 1.0);

  if (const auto* press = std::get_if<HandPress>(&step)) {
    addBlend(at_start, at_start, press->force_n, press->force_n, press->duration_s, 1.0, 1.0);
  } else if (const auto* stroke = std::get_if<HandStroke>(&step)) {
    const double length_m = (stroke->to_m - stroke->from_m).norm();
    const double cruise_s = length_m / stroke->speed_m_per_s;
    Segment s;
    s.kind = Segment::Kind::Stroke;
    s.t0_s = duration_s_;
    s.ramp_s = std::min(options_.stroke_ramp_s, cruise_s);
    s.duration_s = cruise_s + s.ramp_s;  // each raised-cosine ramp loses speed * ramp / 2 of distance
    s.p0_m = at_start;
    s.p1_m = at_end;
    s.push0_n = s.push1_n = Eigen::Vector3d(0.0, 0.0, -stroke->force_n);
    s.speed_m_per_s = stroke->speed_m_per_s;
    segments_.push_back(s);
    duration_s_ += s.duration_s;
  } else {
    const HandPath& path = std::get<HandPath>(step);
    Segment s;
    s.kind = Segment::Kind::Path;
    s.t0_s = duration_s_;
    s.duration_s = path.samples.back().t_s;
    s.p0_m = at_start;
    s.p1_m = at_end;
    s.path_begin = samples_.size();
    samples_.insert(samples_.end(), path.samples.begin(), path.samples.end());
    s.path_end = samples_.size();
    segments_.push_back(s);
    duration_s_ += s.duration_s;
  }

  addBlend(at_end, at_end, ends.end_force_n, 0.0, options_.force_ramp_s, 1.0, 1.0);
  addBlend(at_end, above_end, 0.0, 0.0, options_.approach_s, 1.0, 0.0);
  cursor = above_end;
}

HandTarget HandScript::sampleLocal(double t_s, const SurfaceHeight* height) const {
  HandTarget out;
  double c = 0.0, c_rate = 0.0;  // hovering, unless a segment says otherwise
  // NaN and times before the start sample the start; after the end the hand hovers.
  if (segments_.empty() || !(t_s > 0.0)) {
    out.p_m = start_m_;  // every script starts hovering, no push
  } else if (t_s >= duration_s_) {
    out.p_m = end_m_;
  } else {
    const auto it = std::upper_bound(starts_s_.begin(), starts_s_.end(), t_s);
    const std::size_t i = std::size_t(it - starts_s_.begin()) - 1;
    out = sampleSegment(segments_[i], t_s, c, c_rate);
  }
  if (height) followSurface(out, c, c_rate, *height);
  return out;
}

void HandScript::followSurface(HandTarget& target, double c, double c_rate, const SurfaceHeight& height) const {
  const double hover_z = options_.hover_height_m + height.top();
  if (c == 0.0 && c_rate == 0.0) {  // hovering: no need to know the surface
    target.p_m.z() = hover_z;
    target.v_m_per_s.z() = 0.0;
    return;
  }
  // Nothing under the point: the plane z = 0 of the script's frame.
  const auto heightAt = [&height](const Eigen::Vector2d& xy) {
    double z = 0.0;
    return height.heightAt(xy, z) ? z : 0.0;
  };
  const Eigen::Vector2d xy = target.p_m.head<2>();
  const double h = heightAt(xy);
  // dh/dt along the horizontal motion, only where the target is (partly) on the surface.
  double h_rate = 0.0;
  const Eigen::Vector2d v_xy = target.v_m_per_s.head<2>();
  const double speed = v_xy.norm();
  if (c > 0.0 && speed > 0.0) {
    const Eigen::Vector2d step = (kHeightSlopeStepM / speed) * v_xy;
    h_rate = speed * (heightAt(xy + step) - heightAt(xy - step)) / (2.0 * kHeightSlopeStepM);
  }
  target.p_m.z() = hover_z + c * (h - hover_z);
  target.v_m_per_s.z() = c_rate * (h - hover_z) + c * h_rate;
}

HandTarget HandScript::sample(double t_s, const Eigen::Isometry3d& plane_to_world, const SurfaceHeight* height) const {
  HandTarget local = sampleLocal(t_s, height);
  HandTarget world;
  world.p_m = plane_to_world * local.p_m;
  world.v_m_per_s = plane_to_world.linear() * local.v_m_per_s;
  world.push_n = plane_to_world.linear() * local.push_n;
  world.pressing = local.pressing;
  return world;
}

HandTarget HandScript::sampleSegment(const Segment& s, double t_s, double& c, double& c_rate) const {
  const double tau = std::clamp(t_s - s.t0_s, 0.0, s.duration_s);
  HandTarget out;
  Eigen::Vector3d push = s.push0_n;
  c = s.c0;  // Stroke and Path: 1
  c_rate = 0.0;
  switch (s.kind) {
    case Segment::Kind::Blend: {
      const double u = tau / s.duration_s;
      const double w = minJerk(u);
      const double w_rate = minJerkRate(u) / s.duration_s;
      out.p_m = s.p0_m + w * (s.p1_m - s.p0_m);
      out.v_m_per_s = w_rate * (s.p1_m - s.p0_m);
      push = s.push0_n + w * (s.push1_n - s.push0_n);
      c = s.c0 + w * (s.c1 - s.c0);
      c_rate = w_rate * (s.c1 - s.c0);
      break;
    }
    case Segment::Kind::Stroke: {
      const Eigen::Vector3d delta = s.p1_m - s.p0_m;
      const double length_m = delta.norm();
      const Eigen::Vector3d dir = delta / length_m;
      const double v = s.speed_m_per_s, r = s.ramp_s, pi = std::numbers::pi;
      // Raised-cosine speed ramps: distance covered in a ramp after q seconds.
      const auto rampDistance = [&](double q) { return 0.5 * v * (q - r / pi * std::sin(pi * q / r)); };
      const auto rampSpeed = [&](double q) { return 0.5 * v * (1.0 - std::cos(pi * q / r)); };
      double dist_m = 0.0, speed = v;
      if (tau < r) {
        dist_m = rampDistance(tau);
        speed = rampSpeed(tau);
      } else if (tau <= s.duration_s - r) {
        dist_m = 0.5 * v * r + v * (tau - r);
      } else {
        const double q = std::max(s.duration_s - tau, 0.0);
        dist_m = length_m - rampDistance(q);
        speed = rampSpeed(q);
      }
      out.p_m = s.p0_m + std::clamp(dist_m, 0.0, length_m) * dir;
      out.v_m_per_s = speed * dir;
      break;
    }
    case Segment::Kind::Path:
      return samplePath(s, tau);
  }
  out.push_n = push;
  out.pressing = push.squaredNorm() > 0.0;
  return out;
}

HandTarget HandScript::samplePath(const Segment& s, double tau_s) const {
  const auto first = samples_.begin() + std::ptrdiff_t(s.path_begin);
  const auto last = samples_.begin() + std::ptrdiff_t(s.path_end);
  HandTarget out;
  auto it = std::upper_bound(first, last, tau_s, [](double t, const PathSample& p) { return t < p.t_s; });
  if (it == first || it == last) {
    // Before the first sample the hand waits there; at the end it is at the last sample.
    const PathSample& p = it == first ? *first : *(last - 1);
    out.p_m = Eigen::Vector3d(p.p_m.x(), p.p_m.y(), 0.0);
    out.push_n.z() = -p.force_n;
  } else {
    const PathSample& a = *(it - 1);
    const PathSample& b = *it;
    const double dt = b.t_s - a.t_s;
    const double w = (tau_s - a.t_s) / dt;
    const Eigen::Vector2d p = a.p_m + w * (b.p_m - a.p_m);
    const Eigen::Vector2d v = (b.p_m - a.p_m) / dt;
    out.p_m = Eigen::Vector3d(p.x(), p.y(), 0.0);
    out.v_m_per_s = Eigen::Vector3d(v.x(), v.y(), 0.0);
    out.push_n.z() = -(a.force_n + w * (b.force_n - a.force_n));
  }
  out.pressing = out.push_n.z() < 0.0;
  return out;
}

}  // namespace thx::dev
