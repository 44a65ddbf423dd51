// Haptics: the plane proxy's force error against the exact contact, by renderer variant and
// texture size, against its cost per tick (bench_force_error; the god object on meshes from
// bench_force_error_mesh). docs/benchmarks.md §2 and §2c define the measurement.
#include <algorithm>
#include <map>
#include <set>

#include "tools/report/report_sections.hpp"

namespace thx::bench::report {

namespace {

struct ForceErrorRow {
  std::string surface, variant;
  int size = 0;
  double rel_rms = 0, ns = 0;
};

std::vector<ForceErrorRow> readRows(const ResultsFile& f, bool only_mesh) {
  std::vector<ForceErrorRow> rows;
  const nlohmann::json& results = array(f, f.json, "", "results");
  for (std::size_t i = 0; i < results.size(); ++i) {
    const std::string w = at("", "results", i);
    const nlohmann::json& r = results[i];
    ForceErrorRow row{text(f, r, w, "surface"), text(f, r, w, "variant"), int(number(f, r, w, "size")),
            number(f, r, w, "rel_rms"), number(f, r, w, "ns_per_tick")};
    if (only_mesh && row.variant != "mesh") continue;
    rows.push_back(row);
  }
  return rows;
}

std::string label(const ForceErrorRow& r) { return r.variant + " " + std::to_string(r.size) + "²"; }

}  // namespace

Section hapticsSection(const std::filesystem::path& dir) {
  Section s;
  s.id = "haptics";
  s.title = "Haptics: force error against render cost per tick";
  s.command = "benchmarks/run.sh BUILD force_error";
  s.what =
      "Relative RMS force error of the renderer against the exact height-field contact force of analytic surfaces "
      "(`sine`: smooth bumps; `vvalley`: V-shaped valleys with sharp creases), pressed at random points, against the "
      "median cost of `render()` per servo tick; variants are the sampling filter (nearest, bilinear, Gaussian-"
      "smoothed), crease handling (`+crease`; `-blend`: issue 3's blended ridges), the normal map (depth ignored) and "
      "the relief as a grid mesh under the god object (`mesh`). Definitions: docs/benchmarks.md §2 and §2c.";
  const auto main = readResults(dir, "bench_force_error.json");
  if (!main) return notMeasured(s, dir, "bench_force_error.json");
  std::vector<ForceErrorRow> rows = readRows(*main, false);
  s.machine_lines.push_back(machineLine(*main));
  if (const auto mesh = readResults(dir, "bench_force_error_mesh.json")) {
    const std::vector<ForceErrorRow> m = readRows(*mesh, true);
    rows.insert(rows.end(), m.begin(), m.end());
    s.machine_lines.push_back(machineLine(*mesh));
  }
  if (rows.empty()) throw Error(Error::Kind::Config, main->path + ": results: expected at least one row, got none");

  std::vector<std::string> surfaces, variants;
  std::set<int> sizes;
  for (const ForceErrorRow& r : rows) {
    if (std::find(surfaces.begin(), surfaces.end(), r.surface) == surfaces.end()) surfaces.push_back(r.surface);
    if (std::find(variants.begin(), variants.end(), r.variant) == variants.end()) variants.push_back(r.variant);
    sizes.insert(r.size);
  }

  // Table: one row per surface and variant, one column per texture size: error and cost.
  std::string t = "| surface | variant |";
  std::string rule = "|---|---|";
  for (int n : sizes) {
    t += " " + std::to_string(n) + "²: error, ns/tick |";
    rule += "---|";
  }
  t += "\n" + rule + "\n";
  for (const std::string& surface : surfaces) {
    for (const std::string& variant : variants) {
      std::map<int, const ForceErrorRow*> cells;
      for (const ForceErrorRow& r : rows) {
        if (r.surface == surface && r.variant == variant) cells[r.size] = &r;
      }
      if (cells.empty()) continue;
      t += "| " + surface + " | " + variant + " |";
      for (int n : sizes) {
        const auto it = cells.find(n);
        t += it == cells.end() ? " – |" : " " + percent(it->second->rel_rms) + ", " + num(it->second->ns) + " |";
      }
      t += "\n";
    }
  }
  s.table = t;

  // Reading: the servo tick is 1 ms, so the cost column decides only between close errors.
  double worst_ns = 0;
  for (const ForceErrorRow& r : rows) worst_ns = std::max(worst_ns, r.ns);
  std::string reading = "Every configuration measured costs at most " + num(worst_ns) + " ns per tick, " +
                        percent(worst_ns / 1e6, 2) + " of the 1 ms servo tick, so on this machine accuracy decides.";
  for (const std::string& surface : surfaces) {
    std::vector<Option> options;
    for (const ForceErrorRow& r : rows) {
      if (r.surface == surface) options.push_back({label(r), r.ns, r.rel_rms});
    }
    reading += " On `" + surface + "`";
    for (double budget : {250.0, 1000.0}) {
      const auto best = mostAccurateWithin(options, budget);
      reading += best ? ", within " + num(budget) + " ns the most accurate is " + best->label + " (" +
                            percent(best->error) + " at " + num(best->cost) + " ns)"
                      : ", nothing fits within " + num(budget) + " ns";
    }
    const auto cheap = cheapestWithin(options, 0.01);
    reading += cheap ? "; the cheapest under 1 % error is " + cheap->label + " (" + percent(cheap->error) + ", " +
                           num(cheap->cost) + " ns)."
                     : "; no configuration stays under 1 % error.";
  }
  // A user who does not know their surface's shape: each configuration by its worse surface.
  std::map<std::string, Option> overall;
  std::map<std::string, std::size_t> seen;
  for (const ForceErrorRow& r : rows) {
    Option& o = overall[label(r)];
    o.label = label(r);
    o.cost = std::max(o.cost, r.ns);
    o.error = std::max(o.error, r.rel_rms);
    ++seen[label(r)];
  }
  std::vector<Option> both;
  for (const auto& [name, o] : overall) {
    if (seen[name] == surfaces.size()) both.push_back(o);
  }
  if (surfaces.size() > 1) {
    const auto best = mostAccurateWithin(both, 1000);
    if (best) {
      reading += " Taking each configuration's worse surface, the most accurate within 1 µs is " + best->label + " (" +
                 percent(best->error) + " at " + num(best->cost) + " ns): the pick when the surface's shape is unknown.";
    }
  }
  s.reading = reading;

  // Plot: one panel per surface, one series per variant, the sizes in order along each line.
  for (const std::string& surface : surfaces) {
    PlotPanel p;
    p.title = surface + ": force error against cost";
    p.x_label = "render() per tick (ns)";
    p.y_label = "relative RMS force error (%)";
    p.log_x = false;
    for (std::size_t v = 0; v < variants.size(); ++v) {
      PlotSeries ser;
      ser.label = variants[v];
      ser.color = palette(v);
      ser.marker = Marker(v % 3);
      for (const ForceErrorRow& r : rows) {
        if (r.surface != surface || r.variant != variants[v]) continue;
        ser.x.push_back(r.ns);
        ser.y.push_back(100 * r.rel_rms);
        ser.point_labels.push_back(r.variant == "bilinear+crease" || r.variant == "mesh" ? std::to_string(r.size)
                                                                                          : "");
      }
      if (!ser.x.empty()) p.series.push_back(ser);
    }
    fitAxes(p);
    s.panels.push_back(p);
  }
  s.caption = "Each line runs through the texture sizes (labelled for bilinear+crease and mesh). Source: " +
              std::filesystem::path(main->path).filename().string();
  return s;
}

}  // namespace thx::bench::report
