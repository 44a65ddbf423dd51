#include "tools/report/report_data.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "base/error.hpp"

namespace thx::bench::report {

namespace {

[[noreturn]] void fail(const ResultsFile& f, const std::string& where, const std::string& key,
                       const std::string& expected, const nlohmann::json* got) {
  const std::string field = where.empty() ? key : where + "." + key;
  std::string seen = "nothing (the field is missing)";
  if (got != nullptr) {
    seen = got->dump();
    if (seen.size() > 40) seen = seen.substr(0, 37) + "...";
  }
  throw Error(Error::Kind::Config, f.path + ": " + field + ": expected " + expected + ", got " + seen);
}

const nlohmann::json* find(const ResultsFile& f, const nlohmann::json& obj, const std::string& where,
                           const std::string& key) {
  if (!obj.is_object()) fail(f, where, key, "an object holding it", &obj);
  const auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

std::optional<std::string> optionalText(const ResultsFile& f, const std::string& key) {
  const nlohmann::json* v = find(f, f.json, "", key);
  if (v == nullptr || v->is_null()) return std::nullopt;
  if (!v->is_string()) fail(f, "", key, "a string", v);
  return v->get<std::string>();
}

}  // namespace

std::optional<ResultsFile> readResults(const std::filesystem::path& dir, const std::string& name) {
  const std::filesystem::path p = dir / name;
  if (!std::filesystem::exists(p)) return std::nullopt;
  std::ifstream in(p);
  if (!in) throw Error(Error::Kind::Io, p.string() + ": cannot be read");
  ResultsFile f{p.string(), {}};
  try {
    f.json = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw Error(Error::Kind::Config, f.path + ": not valid JSON (" + e.what() + ")");
  }
  if (!f.json.is_object()) throw Error(Error::Kind::Config, f.path + ": expected a JSON object at the top");
  return f;
}

const nlohmann::json& array(const ResultsFile& f, const nlohmann::json& obj, const std::string& where,
                            const std::string& key) {
  const nlohmann::json* v = find(f, obj, where, key);
  if (v == nullptr || !v->is_array()) fail(f, where, key, "an array", v);
  return *v;
}

double number(const ResultsFile& f, const nlohmann::json& obj, const std::string& where, const std::string& key) {
  const nlohmann::json* v = find(f, obj, where, key);
  if (v == nullptr || !v->is_number()) fail(f, where, key, "a number", v);
  const double d = v->get<double>();
  if (!std::isfinite(d)) fail(f, where, key, "a finite number", v);
  return d;
}

std::optional<double> optionalNumber(const ResultsFile& f, const nlohmann::json& obj, const std::string& where,
                                     const std::string& key) {
  const nlohmann::json* v = find(f, obj, where, key);
  if (v == nullptr || v->is_null()) return std::nullopt;
  return number(f, obj, where, key);
}

std::string text(const ResultsFile& f, const nlohmann::json& obj, const std::string& where, const std::string& key) {
  const nlohmann::json* v = find(f, obj, where, key);
  if (v == nullptr || !v->is_string()) fail(f, where, key, "a string", v);
  return v->get<std::string>();
}

std::string at(const std::string& where, const std::string& key, std::size_t i) {
  return (where.empty() ? key : where + "." + key) + "[" + std::to_string(i) + "]";
}

std::string machineLine(const ResultsFile& f) {
  // Each benchmark stamps a little differently (benchmarks/bench_stamp.hpp and their own keys).
  const auto first = [&](std::initializer_list<const char*> keys) -> std::optional<std::string> {
    for (const char* k : keys) {
      if (auto v = optionalText(f, k)) return v;
    }
    return std::nullopt;
  };
  const std::string unknown = "not recorded";
  const auto machine = first({"machine"});
  const auto renderer = first({"renderer"});
  const auto date = first({"date", "measured"});
  const auto load = first({"load_average", "load_average_before"});
  const auto build = first({"build_type"});
  std::string line = "`" + std::filesystem::path(f.path).filename().string() + "`: machine " + machine.value_or(unknown);
  if (renderer) line += "; renderer " + *renderer;
  // The machine string of some benchmarks already carries the load average.
  if (!machine || machine->find("load average") == std::string::npos) {
    line += "; load average " + load.value_or(unknown);
  }
  line += "; measured " + date.value_or(unknown) + "; build type " + build.value_or(unknown);
  return line;
}

std::optional<Option> mostAccurateWithin(const std::vector<Option>& options, double budget) {
  std::optional<Option> best;
  for (const Option& o : options) {
    if (o.cost > budget) continue;
    if (!best || o.error < best->error || (o.error == best->error && o.cost < best->cost)) best = o;
  }
  return best;
}

std::optional<Option> cheapestWithin(const std::vector<Option>& options, double tolerance) {
  std::optional<Option> best;
  for (const Option& o : options) {
    if (o.error > tolerance) continue;
    if (!best || o.cost < best->cost || (o.cost == best->cost && o.error < best->error)) best = o;
  }
  return best;
}

std::string num(double v, int sig) {
  char buf[64];
  if (std::fabs(v) >= 1e9 || (v != 0 && std::fabs(v) < 1e-4)) {
    std::snprintf(buf, sizeof buf, "%.*e", std::max(0, sig - 1), v);
    return buf;
  }
  if (std::fabs(v) < std::pow(10.0, sig)) {
    std::snprintf(buf, sizeof buf, "%.*g", sig, v);
    return buf;
  }
  // Whole numbers in full with thousands grouped (counts, DOF, modes per core): 240,362.
  std::snprintf(buf, sizeof buf, "%.0f", std::fabs(v));
  std::string digits = buf, grouped;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) grouped += ',';
    grouped += digits[i];
  }
  return (v < 0 ? "-" : "") + grouped;
}

std::string percent(double fraction, int sig) { return num(100 * fraction, sig) + " %"; }

Rgb palette(std::size_t i) {
  static const Rgb colours[] = {{31, 119, 180}, {214, 39, 40},  {44, 160, 44},  {148, 103, 189},
                                {255, 127, 14}, {140, 86, 75},  {227, 119, 194}, {127, 127, 127},
                                {188, 189, 34}, {23, 190, 207}, {0, 0, 0},       {100, 60, 200}};
  return colours[i % (sizeof colours / sizeof colours[0])];
}

void fitAxes(PlotPanel& p) {
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const PlotSeries& s : p.series) {
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if ((p.log_x && s.x[i] <= 0) || (p.log_y && s.y[i] <= 0)) continue;
      x0 = std::min(x0, s.x[i]);
      x1 = std::max(x1, s.x[i]);
      y0 = std::min(y0, s.y[i]);
      y1 = std::max(y1, s.y[i]);
    }
  }
  if (!(x0 <= x1)) x0 = 1, x1 = 10;
  if (!(y0 <= y1)) y0 = 1, y1 = 10;
  const auto pad = [](bool log, double& lo, double& hi) {
    if (log) {
      lo = std::pow(10.0, std::floor(std::log10(lo) * 10 - 1) / 10);
      hi = std::pow(10.0, std::ceil(std::log10(hi) * 10 + 1) / 10);
    } else {
      const double span = hi > lo ? hi - lo : std::max(1.0, std::fabs(hi));
      lo = lo >= 0 ? 0 : lo - 0.05 * span;
      hi = hi + 0.08 * span;
    }
  };
  pad(p.log_x, x0, x1);
  pad(p.log_y, y0, y1);
  p.x_min = x0, p.x_max = x1, p.y_min = y0, p.y_max = y1;
}

Section notMeasured(Section s, const std::filesystem::path& dir, const std::string& file) {
  s.measured = false;
  s.missing = "`" + (dir / file).string() + "` does not exist; run `" + s.command + "` first.";
  return s;
}

}  // namespace thx::bench::report
