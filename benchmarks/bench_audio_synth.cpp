// Modal synthesis: speed against error (issue 14). Three measurements, one program:
//  1. modes synthesised in real time per core at 44.1 kHz: the bare resonator kernel and the full
//     path with excitation (modal impulses projected from a mode shape and struck between renders,
//     as the pen scrape does), float and double, the pre-vectorisation loop (-O2) and each
//     instruction-set variant of the -O3 kernel this CPU supports (forced one by one);
//  2. float against double over long runs (phase drift and decay error of single modes);
//  3. the psychoacoustic compression (merge of close modes, truncation) against the log-spectral
//     distance of a rendered impact from the uncompressed one, and the modes it saves.
// benchmarks/run.sh BUILD audio runs it; docs/audio.md §3 has the tables.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <functional>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_stamp.hpp"
#include "clients/audio/analysis/audible_modes.hpp"
#include "clients/audio/analysis/modal_analysis.hpp"
#include "clients/audio/spectrogram/stft.hpp"
#include "clients/audio/synthesis/resonator_bank.hpp"
#include "tools/report/plot.hpp"
#include "scenes/materials.hpp"

namespace {

using namespace thx::audio;
using thx::bench::isoNow;
using thx::bench::loadAverage;

const char* const kHelp = R"(usage: bench_audio_synth [--prefix PATH] [--md FILE] [--quick] [--sizes LIST]

Modal synthesis speed against error (clients/audio/synthesis/resonator_bank.hpp, docs/audio.md §3):
  speed        modes synthesised in real time per core at 44.1 kHz (thread CPU time), for the bare
               kernel and the full path (1000 impulses/s, each projected on every mode from a mode
               shape and struck between renders), float and double; "reference" is the loop before
               vectorisation at the project's -O2, the others the -O3 kernel forced to each
               instruction set this CPU supports.
  float        single modes (55 Hz ... 15 kHz, d = 0.1 1/s) struck once and rendered 60 s in float
               and double: the relative RMS difference in 50 ms windows at 1, 10 and 60 s, and the
               frequency and decay the float bank's rounded coefficients imply.
  compression  an impact on a brick slab like the default scene's surface (0.2 x 0.2 x 0.01 m,
               Tet10 16 x 16 x 1) and on a steel plate (0.3 x 0.3 x 0.005 m, Tet10 12 x 12 x 1),
               60 FEM modes each, free, 1 s:
               log-spectral distance (Hann 2048, hop 512, 80 dB floor) of the compressed modes'
               sound from all audible modes', for merge thresholds and truncations.
  --prefix PATH  writes PATH_speed.csv, PATH_float.csv, PATH_compression.csv, PATH.json, PATH.png
  --md FILE      the Markdown tables for docs/audio.md
  --quick        fewer sizes and shorter runs (a smoke run)
  --sizes LIST   the banks' mode counts, comma-separated (default 64,256,1024,4096,16384,65536)
  -h, --help
)";

constexpr double kRate = 44100.0;

double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// A deterministic pseudo-random sequence (the benchmark must not depend on a library's RNG).
struct Lcg {
  unsigned long long s = 88172645463325252ull;
  double next() {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return double(s >> 11) * (1.0 / 9007199254740992.0);
  }
};

// Modes spread over the audible band with light damping, as an object's would be.
void someModes(std::size_t n, std::vector<double>& f, std::vector<double>& d) {
  Lcg r;
  f.resize(n), d.resize(n);
  for (std::size_t k = 0; k < n; ++k) f[k] = 50.0 * std::pow(300.0, r.next()), d[k] = 0.5 + 1.5 * r.next();
}

struct SpeedRow {
  std::string precision, variant, path;
  std::size_t modes = 0;
  double modes_realtime = 0;  // modes one core synthesises at 44.1 kHz
  double ns_per_mode_sample = 0;
};

// Renders with `bank` until ~min_cpu seconds of thread CPU time; returns audio seconds per CPU s.
template <class Bank>
double measure(Bank& bank, std::size_t modes, bool full, double min_cpu, std::size_t max_samples) {
  std::vector<double> f, d;
  someModes(modes, f, d);
  bank.setModes(f, d);
  std::vector<double> shape(modes), g(modes);
  Lcg r;
  for (double& s : shape) s = r.next() - 0.5;
  std::vector<double> ones(modes, 1e-3);
  bank.strike(ones);
  std::vector<float> out(256);
  const std::size_t impulse_every = std::size_t(kRate / 1000.0);  // 1000 impulses per second
  std::size_t rendered = 0;
  auto step = [&] {
    if (!full) {
      bank.render(std::span<float>(out));
      rendered += out.size();
      return;
    }
    // The scrape path: render up to the next impulse, project it on the modes, strike.
    for (std::size_t at = 0; at < out.size();) {
      const std::size_t n = std::min(impulse_every, out.size() - at);
      bank.render(std::span<float>(out).subspan(at, n));
      at += n;
      const double j = 1e-4 * (r.next() - 0.5);
      for (std::size_t k = 0; k < modes; ++k) g[k] = shape[k] * j;
      bank.strike(g);
    }
    rendered += out.size();
  };
  for (int warm = 0; warm < 4; ++warm) step();
  rendered = 0;
  const double start = threadCpuSeconds();
  double cpu = 0;
  while ((cpu = threadCpuSeconds() - start) < min_cpu && rendered < max_samples) step();
  return (double(rendered) / kRate) / cpu;
}

template <class Bank>
void speedRows(const char* precision, const std::vector<std::size_t>& sizes, double min_cpu,
               std::vector<SpeedRow>& rows) {
  for (bool full : {false, true})
    for (std::size_t modes : sizes) {
      for (Isa isa : {Isa::Avx512, Isa::Avx2, Isa::Default}) {
        if (!isaSupported(isa)) continue;
        Bank bank(kRate, modes);
        bank.setIsa(isa);
        const double speed = measure(bank, modes, full, min_cpu, std::size_t(60 * kRate));
        rows.push_back({precision, isaName(isa), full ? "full" : "bare", modes, speed * double(modes),
                        1e9 / (speed * kRate * double(modes))});
      }
    }
}

// The loop before vectorisation, driven like the bank (the bank's public API no longer exposes
// it): the same arrays and impulses, resonateReference per block.
template <class T>
struct ReferenceBank {
  std::vector<T> a1, a2, b, y, yp, pending;
  std::vector<T> block = std::vector<T>(kResonatorBlock);
  bool any = false;
  ReferenceBank(double, std::size_t modes) : a1(modes), a2(modes), b(modes), y(modes), yp(modes), pending(modes) {}
  bool setIsa(Isa) { return true; }
  bool setModes(std::span<const double> f, std::span<const double> d) {
    for (std::size_t k = 0; k < f.size(); ++k) {
      const double wd = 2 * std::numbers::pi * f[k], r = std::exp(-d[k] / kRate), th = wd / kRate;
      a1[k] = T(2 * r * std::cos(th)), a2[k] = T(-r * r), b[k] = T(r * std::sin(th) / wd);
    }
    return true;
  }
  void strike(std::span<const double> g) {
    for (std::size_t k = 0; k < g.size(); ++k) pending[k] += T(g[k]);
    any = true;
  }
  void render(std::span<float> out) {
    const ResonatorArrays<T> s{a1.data(), a2.data(), b.data(), y.data(), yp.data(), any ? pending.data() : nullptr};
    resonateReference<T>(s, a1.size(), out.size(), block.data());
    any = false;
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = float(block[i]);
  }
};

template <class T>
void referenceRows(const char* precision, const std::vector<std::size_t>& sizes, double min_cpu,
                   std::vector<SpeedRow>& rows) {
  for (bool full : {false, true})
    for (std::size_t modes : sizes) {
      ReferenceBank<T> bank(kRate, modes);
      const double speed = measure(bank, modes, full, min_cpu, std::size_t(60 * kRate));
      rows.push_back({precision, "reference -O2", full ? "full" : "bare", modes, speed * double(modes),
                      1e9 / (speed * kRate * double(modes))});
    }
}

struct FloatRow {
  double f_hz = 0;
  double err_1s = 0, err_10s = 0, err_60s = 0;  // relative RMS difference in a 50 ms window
  double df_rel = 0;                            // (f_float - f) / f from the rounded coefficients
  double dd_rel = 0;                            // (d_float - d) / d
};

FloatRow floatAgainstDouble(double f, double d, double seconds) {
  ResonatorBank bd(kRate, 1);
  ResonatorBankFloat bf(kRate, 1);
  bd.setModes({&f, 1}, {&d, 1});
  bf.setModes({&f, 1}, {&d, 1});
  const double g = 2 * std::numbers::pi * f;  // unit amplitude
  bd.strike({&g, 1});
  bf.strike({&g, 1});
  const std::size_t n = std::size_t(seconds * kRate);
  std::vector<double> yd(n);
  std::vector<float> yf(n);
  bd.render(std::span<double>(yd));
  bf.render(std::span<float>(yf));
  auto window = [&](double t) {
    const std::size_t end = std::min(n, std::size_t(t * kRate)), start = end - std::size_t(0.05 * kRate);
    double e = 0, s = 0;
    for (std::size_t i = start; i < end; ++i) e += (double(yf[i]) - yd[i]) * (double(yf[i]) - yd[i]), s += yd[i] * yd[i];
    return std::sqrt(e / s);
  };
  FloatRow r;
  r.f_hz = f;
  r.err_1s = window(1), r.err_10s = window(std::min(10.0, seconds)), r.err_60s = window(seconds);
  // What the float bank's coefficients (the difference form, resonator_kernel.hpp) mean:
  // c2 = R^2, c1 = 2 R cos(theta) - 1 - R^2, rounded to float as the bank rounds them.
  const double wd = 2 * std::numbers::pi * f, rr = std::exp(-d / kRate), th = wd / kRate;
  const double one_minus_r = -std::expm1(-d / kRate), sh = std::sin(0.5 * th);
  const double c1 = double(float(-one_minus_r * one_minus_r - 4 * rr * sh * sh)), c2 = double(float(rr * rr));
  const double rf = std::sqrt(c2), thf = std::acos((1 + c2 + c1) / (2 * rf));
  r.df_rel = (thf - th) / th;
  r.dd_rel = (-std::log(rf) * kRate - d) / d;
  return r;
}

struct CompressionRow {
  std::string object, setting;
  int modes = 0, saved = 0;
  double lsd_db = 0, energy_db = 0;
};

std::vector<float> renderImpact(const AudibleModes& m, int dof, double seconds) {
  ResonatorBank bank(kRate, std::max<std::size_t>(1, m.size()));
  std::vector<double> out(std::size_t(seconds * kRate));
  if (m.size() == 0 || !bank.setModes(m.frequency_hz, m.decay_per_s)) return std::vector<float>(out.size(), 0.0f);
  std::vector<double> g(m.size());
  for (std::size_t k = 0; k < m.size(); ++k) g[k] = m.shapes(dof, Eigen::Index(k)) * 1e-3;  // 1 mN s along z
  bank.strike(g);
  bank.render(std::span<double>(out));
  return std::vector<float>(out.begin(), out.end());
}

void compressionRows(const std::string& object, const TetMesh& mesh, const ElasticMaterial& material, int fem_modes,
                     std::vector<CompressionRow>& rows) {
  ModalSettings s;
  s.elastic_modes = fem_modes;
  const ModalSolution sol = analyse(mesh, material, s);
  // Struck at the top-face node nearest to (0.31, 0.17) of the extent from the centre: off every
  // symmetry line, so no family of modes is silent there.
  double xmax = 0, ymax = 0, ztop = -1e9;
  for (const auto& p : mesh.nodes) xmax = std::max(xmax, p.x()), ymax = std::max(ymax, p.y()), ztop = std::max(ztop, p.z());
  int node = 0;
  double best = 1e18;
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    const auto& p = mesh.nodes[i];
    if (std::fabs(p.z() - ztop) > 1e-9) continue;
    const double dist = std::hypot(p.x() - 0.31 * xmax, p.y() - 0.17 * ymax);
    if (dist < best) best = dist, node = int(i);
  }
  const int dof = 3 * node + 2;
  AudibleOptions all;
  all.merge = false;
  const AudibleModes full = audibleModes(sol, material, all);
  const std::vector<float> ref = renderImpact(full, dof, 1.0);
  const StftOptions so{2048, 512};
  const Spectrogram ref_s = stft(ref, kRate, so);
  double ref_energy = 0;
  for (float x : ref) ref_energy += double(x) * double(x);
  auto add = [&](const std::string& setting, const AudibleOptions& o) {
    const AudibleModes m = audibleModes(sol, material, o);
    const std::vector<float> y = renderImpact(m, dof, 1.0);
    double e = 0;
    for (float x : y) e += double(x) * double(x);
    rows.push_back({object, setting, int(m.size()), int(full.size() - m.size()),
                    logSpectralDistance(ref_s, stft(y, kRate, so)), 10 * std::log10(std::max(e, 1e-300) / ref_energy)});
    std::fprintf(stderr, "bench_audio_synth: %s %s: %zu modes, LSD %.2f dB\n", object.c_str(), setting.c_str(), m.size(),
                 rows.back().lsd_db);
  };
  add("all audible (reference)", all);
  for (double rel : {0.001, 0.003, 0.01, 0.03, 0.1}) {
    AudibleOptions o;
    o.merge_rel = rel;
    char name[64];
    std::snprintf(name, sizeof name, "merge max(2 Hz, %.1f %% f)", 100 * rel);
    add(name, o);
  }
  for (int keep : {int(full.size()) / 2, int(full.size()) / 4, 5}) {
    AudibleOptions o;
    o.merge = false;
    o.max_modes = keep;
    add("truncate to " + std::to_string(keep), o);
  }
}

void save(const std::string& path, const std::string& text) {
  if (path.empty()) return;
  std::ofstream out(path);
  out << text;
  if (!out) std::fprintf(stderr, "bench_audio_synth: %s: cannot be written\n", path.c_str());
}

void plot(const std::string& path, const std::vector<SpeedRow>& speed, const std::vector<CompressionRow>& comp) {
  using thx::bench::PlotPanel;
  using thx::bench::PlotSeries;
  PlotPanel p1;
  p1.title = "full path: modes in real time per core (44.1 kHz)";
  p1.x_label = "modes in the bank";
  p1.y_label = "modes real time per core";
  p1.x_min = 1e9, p1.x_max = 0, p1.y_min = 1e9, p1.y_max = 0;
  const thx::bench::Rgb colors[] = {{200, 30, 30}, {30, 100, 200}, {30, 150, 60}, {120, 120, 120}};
  int c = 0;
  for (const char* precision : {"float", "double"})
    for (const char* variant : {"avx512f", "avx2", "default", "reference -O2"}) {
      PlotSeries s;
      s.label = std::string(precision) + " " + variant;
      s.color = colors[c % 4];
      s.filled = std::string(precision) == "float";
      s.marker = std::string(precision) == "float" ? thx::bench::Marker::Circle : thx::bench::Marker::Square;
      for (const SpeedRow& r : speed)
        if (r.path == "full" && r.precision == precision && r.variant == variant) {
          s.x.push_back(double(r.modes));
          s.y.push_back(r.modes_realtime);
          p1.x_min = std::min(p1.x_min, double(r.modes)), p1.x_max = std::max(p1.x_max, double(r.modes));
          p1.y_min = std::min(p1.y_min, r.modes_realtime), p1.y_max = std::max(p1.y_max, r.modes_realtime);
        }
      ++c;
      if (!s.x.empty()) p1.series.push_back(s);
    }
  p1.x_min /= 1.5, p1.x_max *= 1.5, p1.y_min /= 2, p1.y_max *= 2;
  PlotPanel p2;
  p2.title = "compression: spectral error against modes kept";
  p2.x_label = "modes synthesised";
  p2.y_label = "log-spectral distance, dB";
  p2.log_x = false, p2.log_y = false;
  p2.x_min = 0, p2.x_max = 1, p2.y_min = 0, p2.y_max = 1;
  c = 0;
  for (const char* object : {"brick slab", "steel plate"})
    for (const char* kind : {"merge", "truncate"}) {
      PlotSeries s;
      s.label = std::string(object) + ", " + kind;
      s.color = colors[c % 4];
      s.marker = std::string(kind) == "merge" ? thx::bench::Marker::Circle : thx::bench::Marker::Triangle;
      for (const CompressionRow& r : comp)
        if (r.object == object && r.setting.rfind(kind, 0) == 0) {
          s.x.push_back(r.modes), s.y.push_back(r.lsd_db);
          p2.x_max = std::max(p2.x_max, double(r.modes) * 1.1), p2.y_max = std::max(p2.y_max, r.lsd_db * 1.15);
        }
      ++c;
      if (!s.x.empty()) p2.series.push_back(s);
    }
  thx::bench::writePlotPng(path, {p1, p2}, "bench_audio_synth (docs/audio.md section 3)");
}

}  // namespace

int main(int argc, char** argv) {
  thx::bench::exitOnHelp(argc, argv, kHelp);
  std::string prefix, md;
  bool quick = false;
  std::vector<std::size_t> sizes;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "bench_audio_synth: %s: missing value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--prefix") prefix = value();
    else if (a == "--md") md = value();
    else if (a == "--quick") quick = true;
    else if (a == "--sizes") {
      std::stringstream list(value());
      for (std::string item; std::getline(list, item, ',');) {
        const long n = std::atol(item.c_str());
        if (n < 1 || n > 1 << 22) {
          std::fprintf(stderr, "bench_audio_synth: --sizes: '%s' is not a mode count in [1, 4194304]\n", item.c_str());
          return 2;
        }
        sizes.push_back(std::size_t(n));
      }
    }
    else {
      std::fprintf(stderr, "bench_audio_synth: unknown option '%s' (--help lists them)\n", a.c_str());
      return 2;
    }
  }
  const std::string started = isoNow(), load = loadAverage();
  if (sizes.empty())
    sizes = quick ? std::vector<std::size_t>{256, 4096} : std::vector<std::size_t>{64, 256, 1024, 4096, 16384, 65536};
  const double min_cpu = quick ? 0.05 : 0.3;

  std::fprintf(stderr, "bench_audio_synth: speed (best variant here: %s) ...\n", isaName(bestIsa()));
  std::vector<SpeedRow> speed;
  referenceRows<float>("float", sizes, min_cpu, speed);
  referenceRows<double>("double", sizes, min_cpu, speed);
  speedRows<ResonatorBankFloat>("float", sizes, min_cpu, speed);
  speedRows<ResonatorBank>("double", sizes, min_cpu, speed);

  std::fprintf(stderr, "bench_audio_synth: float against double ...\n");
  std::vector<FloatRow> floats;
  for (double f : {55.0, 440.0, 3000.0, 15000.0}) floats.push_back(floatAgainstDouble(f, 0.1, quick ? 10.0 : 60.0));

  std::fprintf(stderr, "bench_audio_synth: compression ...\n");
  std::vector<CompressionRow> comp;
  const ElasticMaterial brick = *thx::scene::findMaterial("brick"), steel = *thx::scene::findMaterial("steel");
  compressionRows("brick slab", slabMesh("brick slab", 0.2, 0.2, 0.01, {16, 16, 1}, ElementOrder::Quadratic, false),
                  brick, quick ? 20 : 60, comp);
  compressionRows("steel plate", slabMesh("steel plate", 0.3, 0.3, 0.005, {12, 12, 1}, ElementOrder::Quadratic, false),
                  steel, quick ? 20 : 60, comp);

  // Output.
  std::ostringstream csv1, csv2, csv3, json, mdt;
  csv1 << "precision,variant,path,modes,modes_realtime_per_core,ns_per_mode_sample\n";
  for (const SpeedRow& r : speed)
    csv1 << r.precision << ',' << r.variant << ',' << r.path << ',' << r.modes << ',' << r.modes_realtime << ','
         << r.ns_per_mode_sample << '\n';
  csv2 << "f_hz,rel_rms_err_1s,rel_rms_err_10s,rel_rms_err_60s,freq_rel_err,decay_rel_err\n";
  for (const FloatRow& r : floats)
    csv2 << r.f_hz << ',' << r.err_1s << ',' << r.err_10s << ',' << r.err_60s << ',' << r.df_rel << ',' << r.dd_rel << '\n';
  csv3 << "object,setting,modes,modes_saved,log_spectral_distance_db,energy_change_db\n";
  for (const CompressionRow& r : comp)
    csv3 << r.object << ',' << r.setting << ',' << r.modes << ',' << r.saved << ',' << r.lsd_db << ',' << r.energy_db
         << '\n';
  json << "{\n  \"machine\": \"" << thx::bench::machineSummary() << "\",\n  \"measured\": \"" << started << "\",\n  \"load_average\": \"" << load << "\",\n  \"build_type\": \""
       << thx::bench::buildType() << "\",\n  \"best_isa\": \""
       << isaName(bestIsa()) << "\",\n  \"speed\": [\n";
  for (std::size_t i = 0; i < speed.size(); ++i)
    json << "    {\"precision\": \"" << speed[i].precision << "\", \"variant\": \"" << speed[i].variant
         << "\", \"path\": \"" << speed[i].path << "\", \"modes\": " << speed[i].modes
         << ", \"modes_realtime_per_core\": " << speed[i].modes_realtime << ", \"ns_per_mode_sample\": "
         << speed[i].ns_per_mode_sample << "}" << (i + 1 < speed.size() ? ",\n" : "\n");
  json << "  ],\n  \"float_vs_double\": [\n";
  for (std::size_t i = 0; i < floats.size(); ++i)
    json << "    {\"f_hz\": " << floats[i].f_hz << ", \"rel_rms_err_1s\": " << floats[i].err_1s
         << ", \"rel_rms_err_10s\": " << floats[i].err_10s << ", \"rel_rms_err_60s\": " << floats[i].err_60s
         << ", \"freq_rel_err\": " << floats[i].df_rel << ", \"decay_rel_err\": " << floats[i].dd_rel << "}"
         << (i + 1 < floats.size() ? ",\n" : "\n");
  json << "  ],\n  \"compression\": [\n";
  for (std::size_t i = 0; i < comp.size(); ++i)
    json << "    {\"object\": \"" << comp[i].object << "\", \"setting\": \"" << comp[i].setting
         << "\", \"modes\": " << comp[i].modes << ", \"modes_saved\": " << comp[i].saved
         << ", \"log_spectral_distance_db\": " << comp[i].lsd_db << ", \"energy_change_db\": " << comp[i].energy_db
         << "}" << (i + 1 < comp.size() ? ",\n" : "\n");
  json << "  ]\n}\n";

  char line[512];
  mdt << "Measured " << started << " (" << long(sysconf(_SC_NPROCESSORS_ONLN)) << " CPUs, load average " << load
      << " at start), thread CPU time, the kernel at -O3 (RelWithDebInfo tree), this CPU's best variant: "
      << isaName(bestIsa()) << ".\n\n"
      << "Modes synthesised in real time per core at 44.1 kHz (thousands); bare = the kernel alone, full = with "
         "1000 impulses/s projected on every mode and struck between renders.\n\n"
      << "| precision | variant | path |";
  for (std::size_t m : sizes) mdt << ' ' << m << " modes |";
  mdt << "\n|---|---|---|";
  for (std::size_t i = 0; i < sizes.size(); ++i) mdt << "---|";
  mdt << '\n';
  for (const char* path : {"bare", "full"})
    for (const char* precision : {"float", "double"})
      for (const char* variant : {"reference -O2", "default", "avx2", "avx512f"}) {
        std::ostringstream row;
        bool any = false;
        row << "| " << precision << " | " << variant << " | " << path << " |";
        for (std::size_t m : sizes)
          for (const SpeedRow& r : speed)
            if (r.path == path && r.precision == precision && r.variant == variant && r.modes == m) {
              std::snprintf(line, sizeof line, " %.1f |", r.modes_realtime / 1000);
              row << line;
              any = true;
            }
        if (any) mdt << row.str() << '\n';
      }
  mdt << "\nFloat against double, one mode, d = 0.1 1/s, struck once: relative RMS difference in the 50 ms "
         "before t, and the frequency and decay the float-rounded coefficients imply.\n\n"
      << "| mode Hz | at 1 s | at 10 s | at " << (quick ? 10 : 60) << " s | frequency error | decay error |\n"
      << "|---|---|---|---|---|---|\n";
  for (const FloatRow& r : floats) {
    std::snprintf(line, sizeof line, "| %.0f | %.2g | %.2g | %.2g | %+.2g | %+.2g |\n", r.f_hz, r.err_1s, r.err_10s,
                  r.err_60s, r.df_rel, r.dd_rel);
    mdt << line;
  }
  mdt << "\nCompression: an impact (1 mN s along z at a top-face node off the symmetry lines), 1 s, against all "
         "audible modes unmerged. Log-spectral distance: Hann 2048, hop 512, 80 dB floor below the reference's "
         "peak.\n\n| object | setting | modes | saved | log-spectral distance | energy change |\n|---|---|---|---|---|---|\n";
  for (const CompressionRow& r : comp) {
    std::snprintf(line, sizeof line, "| %s | %s | %d | %d | %.2f dB | %+.2f dB |\n", r.object.c_str(), r.setting.c_str(),
                  r.modes, r.saved, r.lsd_db, r.energy_db);
    mdt << line;
  }
  std::fputs(mdt.str().c_str(), stdout);
  if (!prefix.empty()) {
    save(prefix + "_speed.csv", csv1.str());
    save(prefix + "_float.csv", csv2.str());
    save(prefix + "_compression.csv", csv3.str());
    save(prefix + ".json", json.str());
    try {
      plot(prefix + ".png", speed, comp);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "bench_audio_synth: %s\n", e.what());
      return 1;
    }
  }
  save(md, mdt.str());
  return 0;
}
