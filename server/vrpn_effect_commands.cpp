#include "server/vrpn_effect_commands.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string_view>

namespace thx::srv {

namespace {

template <class Range>
bool allFinite(const Range& values) {
  return std::all_of(std::begin(values), std::end(values), [](float x) { return std::isfinite(x); });
}

std::string fmt(std::string_view what, double value, std::string_view expected) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%.*s = %g: expected %.*s", int(what.size()), what.data(), value,
                int(expected.size()), expected.data());
  return buf;
}

std::string nonFinite(std::string_view message) {
  return std::string(message) + ": a value is not finite (NaN or infinity); ignored";
}

bool samePlane(const ExternalPlane& a, const ExternalPlane& b) {
  return a.on == b.on && std::equal(a.n, a.n + 3, b.n) && a.d_m == b.d_m && a.k_n_per_m == b.k_n_per_m &&
         a.b_ns_per_m == b.b_ns_per_m && a.mu_static == b.mu_static && a.mu_dynamic == b.mu_dynamic &&
         a.recovery_ticks == b.recovery_ticks;
}

}  // namespace

CommandVerdict applyPlane(ExternalEffects& effects, const vrpn::ForcePlane& msg, const EffectLimits& limits) {
  CommandVerdict v;
  if (!allFinite(msg.plane) || !std::isfinite(msg.kspring) || !std::isfinite(msg.kdamp) ||
      !std::isfinite(msg.fdyn) || !std::isfinite(msg.fstat)) {
    v.problem = nonFinite("Plane");
    return v;
  }
  if (msg.plane_index < 0 || msg.plane_index >= kMaxExternalPlanes) {
    v.problem = fmt("Plane plane_index", msg.plane_index, "0..3");
    return v;
  }
  ExternalPlane& slot = effects.planes[std::size_t(msg.plane_index)];
  ExternalPlane next;
  const double a = msg.plane[0], b = msg.plane[1], c = msg.plane[2], d = msg.plane[3];
  const double len = std::sqrt(a * a + b * b + c * c);
  if (len > 0.0) {
    next.on = true;
    next.n[0] = a / len;
    next.n[1] = b / len;
    next.n[2] = c / len;
    next.d_m = d / len;
    double ks = msg.kspring;
    if (ks <= 0.0) ks = 0.001;
    if (ks > 1.0) ks = 1.0;
    next.k_n_per_m = ks * limits.max_stiffness_n_per_m;
    next.b_ns_per_m = std::clamp(double(msg.kdamp), 0.0, 0.005) * 1000.0;
    next.mu_static = std::clamp(double(msg.fstat), 0.0, 1.0);
    next.mu_dynamic = msg.fdyn > next.mu_static ? 0.0 : std::max(0.0, double(msg.fdyn));
    next.recovery_ticks = std::clamp(msg.n_rec_cycles, 1, limits.max_recovery_ticks);
  }
  next.version = slot.version;
  if (samePlane(slot, next)) return v;
  next.version = slot.version + 1;
  slot = next;
  v.applied = true;
  return v;
}

CommandVerdict applyPlane2(ExternalEffects& effects, const vrpn::ForcePlane2& msg, const EffectLimits& limits) {
  CommandVerdict v;
  const float values[] = {msg.k_adhesion_normal, msg.k_adhesion_lateral, msg.tex_amp,
                          msg.tex_wavelength,    msg.buzz_amp,           msg.buzz_freq};
  if (!allFinite(values)) {
    v.problem = nonFinite("Plane2");
    return v;
  }
  ExternalSurfaceEffects s = effects.surface;
  s.adhesion_k_n_per_m = std::clamp(double(msg.k_adhesion_normal), 0.0, 1.0) * limits.max_stiffness_n_per_m;
  s.texture_amplitude_m = std::clamp(double(msg.tex_amp), 0.0, 0.002);
  s.texture_wavelength_m = msg.tex_wavelength >= 0.0005f ? double(msg.tex_wavelength) : 0.0;
  s.buzz_amplitude_m = std::clamp(double(msg.buzz_amp), 0.0, 0.001);
  s.buzz_frequency_hz = std::clamp(double(msg.buzz_freq), 0.0, limits.servo_rate_hz / 2.0);
  effects.surface = s;
  v.applied = true;
  return v;
}

CommandVerdict applyField(ExternalEffects& effects, const vrpn::ForceField& msg, const EffectLimits& limits) {
  CommandVerdict v;
  bool finite = allFinite(msg.origin) && allFinite(msg.force) && std::isfinite(msg.radius);
  for (const auto& row : msg.jacobian) finite = finite && allFinite(row);
  if (!finite) {
    v.problem = nonFinite("Force_Field");
    return v;
  }
  ExternalField f;
  bool any = false;
  for (int i = 0; i < 3; ++i) {
    f.origin_m[i] = msg.origin[std::size_t(i)];
    f.force_n[i] = msg.force[std::size_t(i)];
    any = any || msg.force[std::size_t(i)] != 0.0f;
    for (int j = 0; j < 3; ++j) {
      f.jacobian_n_per_m[i][j] = msg.jacobian[std::size_t(i)][std::size_t(j)];
      any = any || msg.jacobian[std::size_t(i)][std::size_t(j)] != 0.0f;
    }
  }
  f.radius_m = msg.radius;
  f.on = any && msg.radius > 0.0f;
  if (f.on) {
    const double fnorm = std::sqrt(f.force_n[0] * f.force_n[0] + f.force_n[1] * f.force_n[1] +
                                   f.force_n[2] * f.force_n[2]);
    if (fnorm > limits.peak_force_n) {
      for (double& x : f.force_n) x *= limits.peak_force_n / fnorm;
      v.note = fmt("Force_Field |force|", fnorm, "<= the device's peak force; scaled down");
    }
    double jn = 0.0;
    for (const auto& row : f.jacobian_n_per_m)
      for (double x : row) jn += x * x;
    jn = std::sqrt(jn);
    if (jn > limits.max_stiffness_n_per_m) {
      for (auto& row : f.jacobian_n_per_m)
        for (double& x : row) x *= limits.max_stiffness_n_per_m / jn;
      v.note = fmt("Force_Field |jacobian|", jn, "<= the device's maximum stiffness (N/m); scaled down");
    }
  } else {
    f = ExternalField{};
  }
  effects.field = f;
  v.applied = true;
  return v;
}

CommandVerdict applyCustomEffect(ExternalEffects& effects, const vrpn::ForceCustomEffect& msg,
                                 const EffectLimits& limits) {
  CommandVerdict v;
  if (msg.effect_id == vrpn::ForceCustomEffect::kStopEffect) {
    effects.buzz.on = false;
    ++effects.buzz.version;
    v.applied = true;
    return v;
  }
  if (msg.effect_id != 0) {
    v.problem = fmt("Custom Effect effect_id", double(msg.effect_id), "0 (buzz) or 0xFFFFFFFF (stop)");
    return v;
  }
  if (msg.params.size() < 3) {
    v.problem = fmt("Custom Effect 0 (buzz): number of params", double(msg.params.size()),
                    "3 (amplitude, frequency, duration) or 6 (+ direction)");
    return v;
  }
  if (!allFinite(msg.params)) {
    v.problem = nonFinite("Custom Effect");
    return v;
  }
  ExternalBuzz b;
  b.on = true;
  b.amplitude_n = std::clamp(double(msg.params[0]), 0.0, limits.peak_force_n);
  b.frequency_hz = std::clamp(double(msg.params[1]), 0.0, limits.servo_rate_hz / 2.0);
  b.duration_s = std::clamp(double(msg.params[2]), 0.0, 60.0);
  if (msg.params.size() >= 6) {
    const double x = msg.params[3], y = msg.params[4], z = msg.params[5];
    const double len = std::sqrt(x * x + y * y + z * z);
    if (len > 0.0) {
      b.direction[0] = x / len;
      b.direction[1] = y / len;
      b.direction[2] = z / len;
    }
  }
  b.version = effects.buzz.version + 1;
  effects.buzz = b;
  v.applied = true;
  return v;
}

void resetEffects(ExternalEffects& effects) {
  for (ExternalPlane& p : effects.planes) {
    const std::uint32_t version = p.version + 1;
    p = ExternalPlane{};
    p.version = version;
  }
  effects.surface = ExternalSurfaceEffects{};
  effects.field = ExternalField{};
  const std::uint32_t buzz_version = effects.buzz.version + 1;
  effects.buzz = ExternalBuzz{};
  effects.buzz.version = buzz_version;
}

}  // namespace thx::srv
