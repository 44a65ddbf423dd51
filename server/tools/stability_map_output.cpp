#include "server/tools/stability_map_output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "device/device_specs.hpp"
#include "server/stability_budget.hpp"
#include "base/json_text.hpp"

namespace thx::srv::stab {

namespace {

std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string csvNum(double v) { return std::isfinite(v) ? num(v) : "nan"; }

template <class T, class F>
std::string list(const std::vector<T>& v, F f) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + f(v[i]);
  return s + "]";
}

const char* representation(bool relief) { return relief ? "relief" : "normal"; }

// Every metric, in one order shared by the JSON and the CSV.
std::vector<std::pair<const char*, double>> metricFields(const CellMetrics& m) {
  return {{"lateral_pp_m", m.lateral_pp_m},
          {"lateral_pp_first_half_m", m.lateral_pp_first_m},
          {"lateral_pp_second_half_m", m.lateral_pp_second_m},
          {"lateral_rms_m", m.lateral_rms_m},
          {"lateral_offset_m", m.lateral_offset_m},
          {"excursion_m", m.excursion_m},
          {"normal_pp_m", m.normal_pp_m},
          {"depth_mean_m", m.depth_mean_m},
          {"crossings", double(m.crossings)},
          {"normal_crossings", double(m.normal_crossings)},
          {"oscillation_hz", m.oscillation_hz},
          {"lateral_force_pp_n", m.lateral_force_pp_n},
          {"lateral_force_rms_n", m.lateral_force_rms_n},
          {"normal_force_mean_n", m.normal_force_mean_n},
          {"normal_force_pp_n", m.normal_force_pp_n},
          {"peak_force_n", m.peak_force_n},
          {"peak_force_run_n", m.peak_force_run_n},
          {"motor_work_j", m.motor_work_j},
          {"energy_injected_j", m.energy_injected_j},
          {"injected_power_w", m.injected_power_w},
          {"contact_fraction", m.contact_fraction},
          {"at_peak_fraction", m.at_peak_fraction},
          {"peak_clamp_fraction", m.peak_clamp_fraction},
          {"continuous_limit_fraction", m.continuous_limit_fraction},
          {"rate_limit_fraction", m.rate_limit_fraction},
          {"recovery_fraction", m.recovery_fraction},
          {"passivity_active_fraction", m.passivity_active_fraction},
          {"passivity_dissipated_j", m.passivity_dissipated_j}};
}

void writeAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(path + ": cannot open for writing");
    out << text;
    out.flush();
    if (!out) throw std::runtime_error(path + ": write failed");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::runtime_error(path + ": cannot rename " + tmp + ": " + ec.message());
}

// The configuration-time check hapticd runs (K <= 2 (b - |B|) / T), at the stiffest cell swept.
std::string budgetJson(const CellSetup& s, double stiffness_fraction) {
  const dev::SimPhantomConfig sim = simConfigFor(s.hand);
  StabilityRequest r;
  r.stiffness_fraction = stiffness_fraction;
  r.virtual_damping_ns_per_m = s.virtual_damping_ns_per_m;
  r.period_s = double(sim.servo_period_ns) * 1e-9;
  const StabilityBudget b = checkStabilityBudget(sim.spec, r);
  std::ostringstream o;
  o << "{\"stiffness_fraction\": " << num(stiffness_fraction) << ", \"bound_n_per_m\": " << num(b.bound_n_per_m)
    << ", \"required_physical_damping_ns_per_m\": " << num(b.required_physical_damping_ns_per_m)
    << ", \"within_bound\": " << (b.within_bound ? "true" : "false") << ", \"message\": " << json::quoted(b.message) << "}";
  return o.str();
}

std::string setupJson(const CellSetup& s, double max_stiffness_fraction) {
  const dev::SimPhantomConfig sim = simConfigFor(s.hand);
  const ValleyGeometry& g = s.geometry;
  std::ostringstream o;
  o << "{\n"
    << "    \"valley\": {\"generator\": \"vvalley\", \"period_m\": " << num(g.period_m)
    << ", \"texels_per_period\": " << g.texels_per_period << ", \"texel_m\": " << num(g.texelM())
    << ", \"periods\": " << g.periods << ", \"extent_m\": " << num(g.extentM())
    << ", \"floor_x_m\": " << num(g.floorXM())
    << ", \"sampling\": \"bilinear, wrap\", \"smoothing_sigma_texels\": " << num(g.smoothing_sigma_texels)
    << ", \"smoothing_domain\": \"gradient\"},\n"
    << "    \"hand\": {\"name\": " << json::quoted(s.hand.name) << ", \"mass_kg\": " << num(s.hand.mass_kg)
    << ", \"stiffness_n_per_m\": " << num(s.hand.stiffness_n_per_m)
    << ", \"damping_ns_per_m\": " << num(s.hand.damping_ns_per_m) << ", \"friction_n\": " << num(s.hand.friction_n)
    << ", \"push_normal_stiffness_fraction\": " << num(sim.hand_push_normal_stiffness_fraction) << "},\n"
    << "    \"device\": {\"model\": " << json::quoted(sim.spec.model) << ", \"peak_force_n\": " << num(sim.spec.peak_force_n)
    << ", \"continuous_force_n\": " << num(sim.spec.continuous_force_n)
    << ", \"max_stiffness_n_per_m\": " << num(sim.spec.max_stiffness_n_per_m)
    << ", \"max_damping_ns_per_m\": " << num(sim.spec.max_damping_ns_per_m)
    << ", \"physical_damping_ns_per_m\": " << num(sim.spec.physical_damping_ns_per_m)
    << ", \"device_mass_kg\": " << num(sim.device_mass_kg)
    << ", \"encoder_resolution_m\": " << num(sim.encoder_resolution_m)
    << ", \"servo_hz\": " << num(1e9 / double(sim.servo_period_ns)) << ", \"integration_hz\": " << sim.integration_hz
    << "},\n"
    << "    \"renderer\": {\"virtual_damping_ns_per_m\": " << num(s.virtual_damping_ns_per_m)
    << ", \"recovery_ticks\": " << s.recovery_ticks << ", \"ridges\": \"" << (s.sided_ridges ? "sided" : "blend")
    << "\"},\n"
    << "    \"pen\": {\"tool\": " << json::quoted(penToolName(s.tool));
  if (s.tool != PenTool::Point)
    o << ", \"capsule_length_m\": " << num(s.capsule_length_m) << ", \"capsule_radius_m\": " << num(s.capsule_radius_m);
  o << "},\n"
    << "    \"stability_budget\": " << budgetJson(s, max_stiffness_fraction) << ",\n"
    << "    \"script\": {\"aim_offset_m\": " << num(s.aim_offset_m) << ", \"hover_m\": " << num(s.hover_m)
    << ", \"settle_s\": " << num(s.settle_s) << ", \"duration_s\": " << num(s.duration_s)
    << ", \"window_s\": " << num(s.window_s) << "}\n  }";
  return o.str();
}

std::string thresholdsJson(const Thresholds& t, double period_m) {
  std::ostringstream o;
  o << "{\"stable_amplitude_m\": " << num(t.stableAmplitudeM()) << ", \"buzz_force_pp_n\": " << num(t.buzz_force_pp_n)
    << ", \"unstable_excursion_m\": " << num(t.excursion_period_fraction * period_m)
    << ", \"growth_ratio\": " << num(t.growth_ratio) << ", \"min_crossings\": " << t.min_crossings
    << ", \"drift_energy_j\": " << num(t.drift_energy_j)
    << ", \"cannot_hold_sink_m\": " << num(t.sink_period_fraction * period_m)
    << ", \"rules\": \"unstable: non-finite; cannot-hold: the continuous-force limit acted in the window and the "
       "push exceeds the device's continuous force or the mean depth exceeds push / k by more than cannot_hold_sink_m "
       "(the valley is not tested); unstable: excursion, force at device peak, or lateral amplitude growing; "
       "stable: oscillation amplitudes <= stable_amplitude_m and force ripple <= buzz_force_pp_n (an axis with fewer "
       "than min_crossings mean crossings and at most drift_energy_j of motor work is drift, amplitude 0); else "
       "limit-cycle\"}";
  return o.str();
}

std::string summaryJson(const CliOptions& options, const std::vector<CellResult>& results) {
  // Per mitigation combination: verdict counts, and the unstable cells at the highest stiffness swept.
  double k_max = 0;
  for (const double k : options.axes.stiffness_fractions) k_max = std::max(k_max, k);
  std::ostringstream o;
  o << "[";
  bool first = true;
  for (const Mitigations& m : options.axes.mitigations) {
    int counts[kVerdicts] = {};
    std::vector<std::string> unstable_at_max;
    for (const CellResult& r : results) {
      if (r.params.mitigations.index() != m.index()) continue;
      ++counts[int(r.metrics.verdict)];
      if (r.metrics.verdict == Verdict::Unstable && r.params.stiffness_fraction == k_max) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "%s %g deg %g N", representation(r.params.relief), r.params.angle_deg,
                      r.params.push_force_n);
        unstable_at_max.push_back(buf);
      }
    }
    o << (first ? "\n" : ",\n") << "    {\"mitigations\": " << json::quoted(m.name()) << ", \"stable\": " << counts[0]
      << ", \"limit_cycle\": " << counts[1] << ", \"unstable\": " << counts[2] << ", \"cannot_hold\": " << counts[3]
      << ", \"unstable_at_max_stiffness\": " << list(unstable_at_max, [](const std::string& s) { return json::quoted(s); }) << "}";
    first = false;
  }
  o << "\n  ]";
  return o.str();
}

}  // namespace

std::string commandLine(const std::vector<std::string>& argv) {
  std::string s;
  for (const std::string& a : argv) {
    if (!s.empty()) s += ' ';
    const bool plain = !a.empty() && a.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                         "0123456789-_.,/+=:") == std::string::npos;
    if (plain) {
      s += a;
    } else {
      s += '\'';
      for (const char c : a) s += c == '\'' ? std::string("'\\''") : std::string(1, c);
      s += '\'';
    }
  }
  return s;
}

void writeJson(const std::string& path, const CliOptions& options, const std::vector<CellResult>& results) {
  const SweepAxes& a = options.axes;
  std::ostringstream o;
  o << "{\n  \"tool\": \"stability-map\",\n"
    << "  \"command_line\": " << json::quoted(commandLine(options.argv)) << ",\n"
    << "  \"argv\": " << list(options.argv, [](const std::string& s) { return json::quoted(s); }) << ",\n"
    << "  \"deterministic\": \"lock-step virtual clock; results do not depend on --threads\",\n"
    << "  \"setup\": "
    << setupJson(options.setup, *std::max_element(a.stiffness_fractions.begin(), a.stiffness_fractions.end()))
    << ",\n"
    << "  \"thresholds\": " << thresholdsJson(options.setup.thresholds, options.setup.geometry.period_m) << ",\n"
    << "  \"axes\": {\"angles_deg\": " << list(a.angles_deg, num)
    << ", \"stiffness_fractions\": " << list(a.stiffness_fractions, num)
    << ", \"push_forces_n\": " << list(a.push_forces_n, num)
    << ", \"representations\": " << list(a.relief, [](bool r) { return json::quoted(representation(r)); })
    << ", \"mitigations\": " << list(a.mitigations, [](const Mitigations& m) { return json::quoted(m.name()); }) << "},\n"
    << "  \"summary\": " << summaryJson(options, results) << ",\n"
    << "  \"cells\": [";
  for (std::size_t i = 0; i < results.size(); ++i) {
    const CellResult& r = results[i];
    const CellParams& p = r.params;
    o << (i ? ",\n" : "\n") << "    {\"angle_deg\": " << num(p.angle_deg)
      << ", \"wall_angle_deg\": " << num(90.0 - p.angle_deg / 2.0)
      << ", \"stiffness_fraction\": " << num(p.stiffness_fraction)
      << ", \"stiffness_n_per_m\": " << num(r.stiffness_n_per_m) << ", \"push_force_n\": " << num(p.push_force_n)
      << ", \"representation\": " << json::quoted(representation(p.relief))
      << ", \"mitigations\": " << json::quoted(p.mitigations.name()) << ", \"crease\": " << (p.mitigations.crease ? "true" : "false")
      << ", \"passivity\": " << (p.mitigations.passivity ? "true" : "false")
      << ", \"smoothing\": " << (p.mitigations.smoothing ? "true" : "false")
      << ", \"floor_height_m\": " << num(r.floor_height_m) << ", \"verdict\": " << json::quoted(verdictName(r.metrics.verdict))
      << ", \"reason\": " << json::quoted(r.metrics.reason) << ", \"finite\": " << (r.metrics.finite ? "true" : "false");
    for (const auto& [name, value] : metricFields(r.metrics)) o << ", " << json::quoted(name) << ": " << num(value);
    o << "}";
  }
  o << "\n  ]\n}\n";
  writeAtomically(path, o.str());
}

void writeCsv(const std::string& path, const std::vector<CellResult>& results) {
  std::ostringstream o;
  o << "angle_deg,stiffness_fraction,stiffness_n_per_m,push_force_n,representation,mitigations,crease,passivity,"
       "smoothing,floor_height_m,verdict,finite";
  for (const auto& [name, value] : metricFields(CellMetrics{})) o << ',' << name;
  o << ",reason\n";
  for (const CellResult& r : results) {
    const CellParams& p = r.params;
    o << num(p.angle_deg) << ',' << num(p.stiffness_fraction) << ',' << num(r.stiffness_n_per_m) << ','
      << num(p.push_force_n) << ',' << representation(p.relief) << ',' << p.mitigations.name() << ','
      << int(p.mitigations.crease) << ',' << int(p.mitigations.passivity) << ',' << int(p.mitigations.smoothing) << ','
      << num(r.floor_height_m) << ',' << verdictName(r.metrics.verdict) << ',' << int(r.metrics.finite);
    for (const auto& [name, value] : metricFields(r.metrics)) o << ',' << csvNum(value);
    // The reason may hold commas: quote it (RFC 4180).
    std::string reason = "\"";
    for (const char c : r.metrics.reason) reason += c == '"' ? std::string("\"\"") : std::string(1, c);
    o << ',' << reason << "\"\n";
  }
  writeAtomically(path, o.str());
}

}  // namespace thx::srv::stab
