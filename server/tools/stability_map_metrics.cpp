#include "server/tools/stability_map_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace thx::srv::stab {

namespace {

struct Detrended {
  double pp = 0.0;
  double rms = 0.0;
  double mean = 0.0;
  int crossings = 0;  // of the residual through zero, with a dead band of +-band
};

// Peak-to-peak and RMS of y - (a + b t) over [begin, end), the least-squares line removed.
template <class Get>
Detrended detrend(const std::vector<WindowSample>& s, std::size_t begin, std::size_t end, double band, Get get) {
  Detrended d;
  const std::size_t n = end - begin;
  if (n < 2) return d;
  double st = 0, sy = 0;
  for (std::size_t k = begin; k < end; ++k) {
    st += s[k].t_s;
    sy += get(s[k]);
  }
  const double tm = st / double(n), ym = sy / double(n);
  double stt = 0, sty = 0;
  for (std::size_t k = begin; k < end; ++k) {
    const double dt = s[k].t_s - tm;
    stt += dt * dt;
    sty += dt * (get(s[k]) - ym);
  }
  const double slope = stt > 0 ? sty / stt : 0.0;
  double lo = INFINITY, hi = -INFINITY, sq = 0;
  int side = 0;
  for (std::size_t k = begin; k < end; ++k) {
    const double r = get(s[k]) - ym - slope * (s[k].t_s - tm);
    lo = std::min(lo, r);
    hi = std::max(hi, r);
    sq += r * r;
    // The dead band keeps quantisation chatter around a resting pen from counting as oscillation.
    const int now = r > band ? 1 : (r < -band ? -1 : 0);
    if (now != 0 && side != 0 && now != side) ++d.crossings;
    if (now != 0) side = now;
  }
  d.pp = hi - lo;
  d.rms = std::sqrt(sq / double(n));
  d.mean = ym;
  return d;
}

template <class Get>
double peakToPeak(const std::vector<WindowSample>& s, Get get) {
  double lo = INFINITY, hi = -INFINITY;
  for (const WindowSample& w : s) {
    lo = std::min(lo, get(w));
    hi = std::max(hi, get(w));
  }
  return s.empty() ? 0.0 : hi - lo;
}

double fraction(const std::vector<WindowSample>& s, bool WindowSample::*flag) {
  if (s.empty()) return 0.0;
  std::size_t n = 0;
  for (const WindowSample& w : s) n += (w.*flag) ? 1u : 0u;
  return double(n) / double(s.size());
}

std::string format(const char* fmt, double a, double b, double c = 0.0) {
  char buf[200];
  std::snprintf(buf, sizeof buf, fmt, a, b, c);
  return buf;
}

}  // namespace

const char* verdictName(Verdict v) {
  switch (v) {
    case Verdict::Stable: return "stable";
    case Verdict::LimitCycle: return "limit-cycle";
    case Verdict::Unstable: return "unstable";
    case Verdict::CannotHold: return "cannot-hold";
  }
  return "?";
}

int severity(Verdict v) {
  switch (v) {
    case Verdict::CannotHold: return 0;
    case Verdict::Stable: return 1;
    case Verdict::LimitCycle: return 2;
    case Verdict::Unstable: return 3;
  }
  return 3;
}

CellMetrics measureWindow(const std::vector<WindowSample>& s, const WindowEnergy& e, double aim_x_m,
                          double floor_x_m, double encoder_resolution_m, double peak_force_run_n) {
  CellMetrics m;
  m.peak_force_run_n = peak_force_run_n;
  if (s.size() < 4) {
    m.finite = false;
    return m;
  }
  for (const WindowSample& w : s) m.finite = m.finite && w.p_m.allFinite() && w.f_out_n.allFinite();
  m.finite = m.finite && std::isfinite(e.motor_work_j) && std::isfinite(e.kinetic_end_j) &&
             std::isfinite(e.hand_potential_end_j) && std::isfinite(peak_force_run_n);
  if (!m.finite) return m;

  const double period_s = (s.back().t_s - s.front().t_s) / double(s.size() - 1);
  m.window_s = s.back().t_s - s.front().t_s + period_s;
  const auto x = [](const WindowSample& w) { return w.p_m.x(); };
  const auto z = [](const WindowSample& w) { return w.p_m.z(); };
  const std::size_t half = s.size() / 2;
  const double band = encoder_resolution_m;
  const Detrended lat = detrend(s, 0, s.size(), band, x);
  const Detrended nor = detrend(s, 0, s.size(), band, z);
  m.lateral_pp_m = lat.pp;
  m.lateral_rms_m = lat.rms;
  m.lateral_offset_m = lat.mean - aim_x_m;
  m.lateral_pp_first_m = detrend(s, 0, half, band, x).pp;
  m.lateral_pp_second_m = detrend(s, half, s.size(), band, x).pp;
  m.normal_pp_m = nor.pp;
  m.crossings = lat.crossings;
  m.normal_crossings = nor.crossings;

  double depth_sum = 0, fx_sum = 0, fz_sum = 0;
  for (const WindowSample& w : s) {
    m.excursion_m = std::max(m.excursion_m, std::fabs(w.p_m.x() - floor_x_m));
    depth_sum += w.depth_m;
    fx_sum += w.f_out_n.x();
    fz_sum += w.f_out_n.z();
    m.peak_force_n = std::max(m.peak_force_n, w.f_out_n.norm());
  }
  const double n = double(s.size());
  m.depth_mean_m = depth_sum / n;
  const double fx_mean = fx_sum / n;
  double fx_sq = 0;
  for (const WindowSample& w : s) fx_sq += (w.f_out_n.x() - fx_mean) * (w.f_out_n.x() - fx_mean);
  m.lateral_force_rms_n = std::sqrt(fx_sq / n);
  m.lateral_force_pp_n = peakToPeak(s, [](const WindowSample& w) { return w.f_out_n.x(); });
  m.normal_force_mean_n = fz_sum / n;
  m.normal_force_pp_n = peakToPeak(s, [](const WindowSample& w) { return w.f_out_n.z(); });

  m.oscillation_hz = m.crossings / 2.0 / m.window_s;

  m.motor_work_j = e.motor_work_j;
  m.energy_injected_j = e.motor_work_j - (e.kinetic_end_j - e.kinetic_start_j) -
                        (e.hand_potential_end_j - e.hand_potential_start_j);
  m.injected_power_w = m.energy_injected_j / m.window_s;
  m.passivity_dissipated_j = e.passivity_dissipated_j;

  m.contact_fraction = fraction(s, &WindowSample::in_contact);
  m.at_peak_fraction = fraction(s, &WindowSample::at_peak);
  m.peak_clamp_fraction = fraction(s, &WindowSample::peak_clamped);
  m.continuous_limit_fraction = fraction(s, &WindowSample::continuous_limited);
  m.rate_limit_fraction = fraction(s, &WindowSample::rate_limited);
  m.recovery_fraction = fraction(s, &WindowSample::recovering);
  m.passivity_active_fraction = fraction(s, &WindowSample::passivity_active);
  return m;
}

void classify(CellMetrics& m, const Thresholds& t, double period_m) {
  const double a_stable = t.stableAmplitudeM();
  // Oscillation amplitudes: an axis that does not oscillate (too few crossings) is drifting.
  const bool fed = m.motor_work_j > t.drift_energy_j;
  const bool lat_osc = fed || m.crossings >= t.min_crossings, nor_osc = fed || m.normal_crossings >= t.min_crossings;
  const double lat_amp = lat_osc ? m.lateral_pp_m : 0.0, nor_amp = nor_osc ? m.normal_pp_m : 0.0;
  const double ripple = std::max(m.lateral_force_pp_n, m.normal_force_pp_n);
  const double excursion_limit = t.excursion_period_fraction * period_m;
  const double sink_limit = m.held_depth_m + t.sink_period_fraction * period_m;
  if (!m.finite) {
    m.verdict = Verdict::Unstable;
    m.reason = "non-finite state or force";
  } else if (m.continuous_limit_fraction > 0.0 &&
             (m.push_force_n > m.continuous_force_n || m.depth_mean_m > sink_limit)) {
    m.verdict = Verdict::CannotHold;
    m.reason = format("cannot hold the push: continuous-force limit in %.3g%% of the window, pen %.3g mm deep "
                      "(the push is held at %.3g mm)",
                      m.continuous_limit_fraction * 100, m.depth_mean_m * 1e3, m.held_depth_m * 1e3);
    m.reason += format(", push %.3g N above the continuous %.3g N", m.push_force_n, m.continuous_force_n);
  } else if (m.excursion_m > excursion_limit) {
    m.verdict = Verdict::Unstable;
    m.reason = format("pen %.3g mm from the floor (limit %.3g mm)", m.excursion_m * 1e3, excursion_limit * 1e3);
  } else if (m.at_peak_fraction > 0.0) {
    m.verdict = Verdict::Unstable;
    m.reason = format("force at the device peak in %.3g%% of the window (max %.3g N)", m.at_peak_fraction * 100,
                      m.peak_force_n);
  } else if (lat_osc && m.lateral_pp_second_m > a_stable &&
             m.lateral_pp_second_m > t.growth_ratio * m.lateral_pp_first_m) {
    m.verdict = Verdict::Unstable;
    m.reason = format("lateral amplitude growing: %.3g -> %.3g um p-p", m.lateral_pp_first_m * 1e6,
                      m.lateral_pp_second_m * 1e6);
  } else if (lat_amp <= a_stable && nor_amp <= a_stable && ripple <= t.buzz_force_pp_n) {
    m.verdict = Verdict::Stable;
    m.reason = format("settled: oscillation %.3g um p-p, ripple %.3g N p-p", std::max(lat_amp, nor_amp) * 1e6, ripple);
    if (!lat_osc && !nor_osc && std::max(m.lateral_pp_m, m.normal_pp_m) > a_stable)
      m.reason += format(" (drifting %.3g um in the window, %.0f crossings)",
                         std::max(m.lateral_pp_m, m.normal_pp_m) * 1e6, double(std::max(m.crossings, m.normal_crossings)));
  } else {
    m.verdict = Verdict::LimitCycle;
    m.reason = format("sustained: oscillation %.3g um p-p, ripple %.3g N p-p", std::max(lat_amp, nor_amp) * 1e6, ripple);
  }
}

}  // namespace thx::srv::stab
