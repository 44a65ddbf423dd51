// Modal synthesis: modes in real time per core by precision and instruction set, float's error
// against double, and compression's spectral error against how many sounds a core then carries
// (bench_audio_synth; docs/audio.md §3 defines the measurement).
#include <algorithm>
#include <cmath>
#include <map>

#include "tools/report/report_sections.hpp"

namespace thx::bench::report {

namespace {

struct Speed {
  std::string precision, variant, path;
  double modes = 0, per_core = 0;
};

}  // namespace

Section synthSection(const std::filesystem::path& dir) {
  Section s;
  s.id = "synthesis";
  s.title = "Modal synthesis: error against modes per core";
  s.command = "benchmarks/run.sh BUILD audio";
  s.what =
      "How many modes one core synthesises in real time at 44.1 kHz (the bare resonator kernel, and the full path "
      "with struck impulses), in float and double, for the portable loop (`reference -O2`), the compiler's default "
      "and each instruction set forced; float's relative RMS error against double after 1 s and 60 s of ringing; "
      "and the compression of an impact's modes (merging close modes, truncating to the loudest) against the "
      "log-spectral distance from the uncompressed impact. Definitions: docs/audio.md §3.";
  const auto f = readResults(dir, "bench_audio_synth.json");
  if (!f) return notMeasured(s, dir, "bench_audio_synth.json");
  s.machine_lines.push_back(machineLine(*f));

  std::vector<Speed> speed;
  const nlohmann::json& sp = array(*f, f->json, "", "speed");
  for (std::size_t i = 0; i < sp.size(); ++i) {
    const std::string w = at("", "speed", i);
    speed.push_back({text(*f, sp[i], w, "precision"), text(*f, sp[i], w, "variant"), text(*f, sp[i], w, "path"),
                     number(*f, sp[i], w, "modes"), number(*f, sp[i], w, "modes_realtime_per_core")});
  }
  if (speed.empty()) throw Error(Error::Kind::Config, f->path + ": speed: expected at least one row, got none");
  double worst_1s = 0, worst_60s = 0, worst_f = 0;
  const nlohmann::json& fd = array(*f, f->json, "", "float_vs_double");
  for (std::size_t i = 0; i < fd.size(); ++i) {
    const std::string w = at("", "float_vs_double", i);
    worst_1s = std::max(worst_1s, number(*f, fd[i], w, "rel_rms_err_1s"));
    const double e60 = number(*f, fd[i], w, "rel_rms_err_60s");
    if (e60 >= worst_60s) worst_60s = e60, worst_f = number(*f, fd[i], w, "f_hz");
  }

  // Speed at the largest bank measured (where the per-call overhead no longer counts).
  double bank = 0;
  for (const Speed& r : speed) bank = std::max(bank, r.modes);
  std::vector<std::pair<std::string, std::string>> kinds;  // precision, variant
  for (const Speed& r : speed) {
    if (std::find(kinds.begin(), kinds.end(), std::make_pair(r.precision, r.variant)) == kinds.end()) {
      kinds.emplace_back(r.precision, r.variant);
    }
  }
  const auto rate = [&](const std::string& precision, const std::string& variant, const std::string& path) {
    std::optional<double> v;
    for (const Speed& r : speed) {
      if (r.precision == precision && r.variant == variant && r.path == path && r.modes == bank) v = r.per_core;
    }
    return v;
  };
  const std::string error_text = fd.empty() ? std::string("not measured")
                                            : percent(worst_1s, 2) + " after 1 s, " + percent(worst_60s, 2) + " after 60 s";
  std::string t = "| precision | instruction set | modes per core, full path | modes per core, bare kernel | "
                  "float's error against double (one resonator ringing) |\n|---|---|---|---|---|\n";
  std::optional<Option> fastest;  // full path
  for (const auto& [precision, variant] : kinds) {
    const auto full = rate(precision, variant, "full"), bare = rate(precision, variant, "bare");
    t += "| " + precision + " | " + variant + " | " + (full ? num(*full) : "–") + " | " + (bare ? num(*bare) : "–") +
         " | " + (precision == "double" ? std::string("(reference)") : error_text) + " |\n";
    if (full && (!fastest || *full > fastest->cost)) fastest = Option{precision + " " + variant, *full, 0};
  }
  t += "\nAt a bank of " + num(bank) + " modes. Compression (the impact's modes kept, and the sounds of that impact "
       "one core carries at the fastest full path):\n\n";

  // Compression: sounds per core = the fastest full path's modes per core over the modes kept.
  const double per_core = fastest ? fastest->cost : 0;
  t += "| object | setting | modes kept | log-spectral distance (dB) | sounds per core |\n|---|---|---|---|---|\n";
  std::vector<std::string> objects;
  std::map<std::string, std::vector<Option>> by_object;
  PlotPanel rates, compression;
  const nlohmann::json& cp = array(*f, f->json, "", "compression");
  std::map<std::string, PlotSeries> series;
  std::vector<std::string> series_order;
  for (std::size_t i = 0; i < cp.size(); ++i) {
    const std::string w = at("", "compression", i);
    const std::string object = text(*f, cp[i], w, "object"), setting = text(*f, cp[i], w, "setting");
    const double modes = number(*f, cp[i], w, "modes"), lsd = number(*f, cp[i], w, "log_spectral_distance_db");
    if (modes <= 0) throw Error(Error::Kind::Config, f->path + ": " + w + ".modes: expected a positive count, got " + num(modes));
    t += "| " + object + " | " + setting + " | " + num(modes) + " | " + num(lsd) + " | " +
         (per_core > 0 ? num(per_core / modes) : std::string("–")) + " |\n";
    if (std::find(objects.begin(), objects.end(), object) == objects.end()) objects.push_back(object);
    by_object[object].push_back({setting + " (" + num(modes) + " modes)", modes, lsd});
    const std::string kind = object + (setting.rfind("merge", 0) == 0 ? " merge" : setting.rfind("truncate", 0) == 0 ? " truncate" : " all");
    if (!series.count(kind)) series_order.push_back(kind);
    PlotSeries& ser = series[kind];
    ser.x.push_back(per_core > 0 ? per_core / modes : modes);
    ser.y.push_back(lsd);
  }
  s.table = t;

  std::string reading;
  if (fastest) {
    reading = "The fastest full path is " + fastest->label + " at " + num(fastest->cost) + " modes per core";
    const std::string precision = fastest->label.substr(0, fastest->label.find(' '));
    const std::string variant = fastest->label.substr(fastest->label.find(' ') + 1);
    const auto other = rate(precision == "float" ? "double" : "float", variant, "full");
    if (other) reading += " (" + num(fastest->cost / *other, 2) + "× the other precision with the same instructions)";
    reading += ". ";
    if (precision == "float") {
      reading += "Float's error against double is at most " + error_text + " (worst at " + num(worst_f) + " Hz)" +
                 (fd.empty() ? std::string(".")
                  : worst_1s <= 0.01 ? ", under 1 % for the first second: float is the pick for sounds whose modes die "
                                       "out within seconds, double only for modes that must ring far longer."
                                     : ", over 1 % within the first second: double is the safer pick.");
    } else {
      reading += "Double is also the reference, so nothing is lost in accuracy.";
    }
  }
  for (const std::string& object : objects) {
    const auto pick = [&](double tolerance_db) {
      // The fewest modes (the most sounds per core) whose distance stays within the tolerance.
      return cheapestWithin(by_object[object], tolerance_db);
    };
    reading += " For the " + object;
    for (double tol : {0.1, 1.0}) {
      const auto best = pick(tol);
      reading += best ? ", within " + num(tol) + " dB the fewest modes is " + best->label +
                            (per_core > 0 ? ", " + num(per_core / best->cost) + " sounds per core" : std::string())
                      : ", nothing stays within " + num(tol) + " dB";
    }
    reading += ".";
  }
  s.reading = reading;

  rates.title = "modes in real time per core (full path)";
  rates.x_label = "modes in the bank";
  rates.y_label = "modes per core at 44.1 kHz";
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    PlotSeries ser;
    ser.label = kinds[k].first + " " + kinds[k].second;
    ser.color = palette(k);
    ser.marker = kinds[k].first == "float" ? Marker::Circle : Marker::Square;
    ser.filled = kinds[k].first == "float";
    for (const Speed& r : speed) {
      if (r.precision == kinds[k].first && r.variant == kinds[k].second && r.path == "full") {
        ser.x.push_back(r.modes);
        ser.y.push_back(r.per_core);
      }
    }
    if (!ser.x.empty()) rates.series.push_back(ser);
  }
  compression.title = "compression: spectral error against sounds per core";
  compression.x_label = per_core > 0 ? "sounds of the impact per core (fastest full path)" : "modes kept";
  compression.y_label = "log-spectral distance (dB)";
  compression.log_x = false;
  for (std::size_t k = 0; k < series_order.size(); ++k) {
    // The uncompressed impact is 0 dB by definition: nothing to draw on a log axis.
    if (series_order[k].size() >= 4 && series_order[k].compare(series_order[k].size() - 4, 4, " all") == 0) continue;
    PlotSeries ser = series[series_order[k]];
    ser.label = series_order[k];
    ser.color = palette(kinds.size() + k);
    ser.marker = series_order[k].find("truncate") == std::string::npos ? Marker::Triangle : Marker::Square;
    compression.series.push_back(ser);
  }
  fitAxes(rates);
  fitAxes(compression);
  s.panels = {rates, compression};
  s.caption = "Left: circles float, squares double. Right: triangles merge, squares truncate; the uncompressed impact (0 dB) is not drawn. "
              "Source: bench_audio_synth.json";
  return s;
}

}  // namespace thx::bench::report
