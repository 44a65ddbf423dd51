// Physics: the worst outcome error of a sphere and a box (rolling, sliding, escaping over a bump,
// against analytic answers) against the time per step, for each ground representation and size
// (bench_physics; docs/benchmarks.md §6 defines the cases).
#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "tools/report/report_sections.hpp"

namespace thx::bench::report {

namespace {

// A ground, a size and a shape, at one contact breaking threshold.
struct Key {
  std::string representation;
  int size = 0;
  std::string shape;
  double breaking = 0;
  bool operator<(const Key& o) const {
    return std::tie(representation, size, shape, breaking) < std::tie(o.representation, o.size, o.shape, o.breaking);
  }
};

struct Cell {
  std::optional<double> step_us;
  std::optional<double> worst;  // max |relative error| over the cases with an analytic answer
  std::string worst_case;
};

std::string groundLabel(const Key& k) {
  std::string l = k.representation;
  if (k.size > 0) l += " " + std::to_string(k.size) + "²";
  return l;
}

}  // namespace

Section physicsSection(const std::filesystem::path& dir) {
  Section s;
  s.id = "physics";
  s.title = "Physics: outcome error against step cost";
  s.command = "benchmarks/run.sh BUILD physics";
  s.what =
      "A sphere and a box on the same surface as a plain plane, a normal map, a relief map, Bullet's heightfield and "
      "a BVH mesh at several sizes: the median time of one physics step, and the worst relative error over the "
      "cases that have an analytic answer (the sphere: speed after rolling on the flat, acceleration down a slope, "
      "escape speed over a bump; the box: acceleration sliding down a slope), at Bullet's default contact breaking "
      "threshold. Cases without an analytic answer (rest, sink) and the rows at a smaller threshold are in "
      "docs/benchmarks.md §6, which defines every case and its settings.";
  const auto f = readResults(dir, "bench_physics.json");
  if (!f) return notMeasured(s, dir, "bench_physics.json");
  s.machine_lines.push_back(machineLine(*f));

  std::map<Key, Cell> cells;
  std::vector<Key> order;
  const auto cell = [&](const Key& k) -> Cell& {
    if (!cells.count(k)) order.push_back(k);
    return cells[k];
  };
  const nlohmann::json& timing = array(*f, f->json, "", "timing");
  for (std::size_t i = 0; i < timing.size(); ++i) {
    const std::string w = at("", "timing", i);
    const nlohmann::json& r = timing[i];
    const Key k{text(*f, r, w, "representation"), int(number(*f, r, w, "size")), text(*f, r, w, "shape"),
                number(*f, r, w, "breaking_threshold")};
    cell(k).step_us = number(*f, r, w, "median_us");
  }
  const nlohmann::json& accuracy = array(*f, f->json, "", "accuracy");
  for (std::size_t i = 0; i < accuracy.size(); ++i) {
    const std::string w = at("", "accuracy", i);
    const nlohmann::json& r = accuracy[i];
    const Key k{text(*f, r, w, "representation"), int(number(*f, r, w, "size")), text(*f, r, w, "shape"),
                number(*f, r, w, "breaking_threshold")};
    const auto rel = optionalNumber(*f, r, w, "rel_error");
    const std::string c = text(*f, r, w, "case");
    if (!rel) continue;
    Cell& e = cell(k);
    if (!e.worst || std::fabs(*rel) > *e.worst) e.worst = std::fabs(*rel), e.worst_case = c;
  }
  if (order.empty()) throw Error(Error::Kind::Config, f->path + ": timing: expected at least one row, got none");

  // Table: one row per ground (at Bullet's default breaking threshold, the one every ground ran).
  const double kDefaultBreaking = 0.02;
  std::string t =
      "| ground | sphere: µs/step | sphere: worst error | box: µs/step | box: worst error |\n|---|---|---|---|---|\n";
  std::vector<Key> grounds;
  for (const Key& k : order) {
    Key g = k;
    g.shape.clear();
    if (k.breaking == kDefaultBreaking &&
        std::find_if(grounds.begin(), grounds.end(), [&](const Key& o) { return !(o < g) && !(g < o); }) ==
            grounds.end()) {
      grounds.push_back(g);
    }
  }
  const auto show = [](const std::optional<double>& v, bool pct) {
    return v ? (pct ? percent(*v) : num(*v)) : std::string("–");
  };
  for (const Key& g : grounds) {
    t += "| " + groundLabel(g) + " |";
    for (const char* shape : {"sphere", "box"}) {
      Key k = g;
      k.shape = shape;
      const auto it = cells.find(k);
      const Cell c = it == cells.end() ? Cell{} : it->second;
      t += " " + show(c.step_us, false) + " | " + show(c.worst, true) + " |";
    }
    t += "\n";
  }
  s.table = t;

  // Reading and plot: per shape, the grounds as options (cost: step time; error: worst case).
  std::string reading =
      "A physics step has 1000 µs at the shipped 1 kHz rate, but it shares the core with everything else; the picks "
      "below are among the textured grounds (the plain plane is the untextured baseline).";
  std::vector<std::string> representations;
  for (const Key& k : order) {
    if (std::find(representations.begin(), representations.end(), k.representation) == representations.end()) {
      representations.push_back(k.representation);
    }
  }
  for (const char* shape : {"sphere", "box"}) {
    std::vector<Option> options;
    PlotPanel p;
    p.title = std::string(shape) + ": worst outcome error against step time";
    p.x_label = "median time per step (us)";
    p.y_label = "worst |relative error| (%)";
    for (std::size_t ri = 0; ri < representations.size(); ++ri) {
      PlotSeries ser;
      ser.label = representations[ri];
      ser.color = palette(ri);
      ser.marker = Marker(ri % 3);
      for (const Key& k : order) {
        const Cell& c = cells[k];
        if (k.shape != shape || k.breaking != kDefaultBreaking || k.representation != representations[ri]) continue;
        if (!c.step_us || !c.worst) continue;
        // The plain plane has no texture: it is the baseline, not a way to render the surface.
        if (k.size > 0) options.push_back({groundLabel(k), *c.step_us, *c.worst});
        ser.x.push_back(*c.step_us);
        ser.y.push_back(std::max(100 * *c.worst, 1e-4));  // a zero error still shows, at the axis floor
        // Sizes on the relief and the plain mesh only: the normal map's sizes and the other Bullet
        // grounds lie on top of one another.
        const bool labelled = k.representation == "relief map" || k.representation == "BVH mesh";
        ser.point_labels.push_back(labelled && k.size > 0 ? std::to_string(k.size) : "");
      }
      if (!ser.x.empty()) p.series.push_back(ser);
    }
    fitAxes(p);
    s.panels.push_back(p);
    reading += " For the " + std::string(shape);
    for (double budget : {5.0, 50.0}) {
      const auto best = mostAccurateWithin(options, budget);
      reading += best ? ", within " + num(budget) + " µs per step the most accurate ground is " + best->label + " (" +
                            percent(best->error) + " worst error, " + num(best->cost) + " µs)"
                      : ", no ground fits within " + num(budget) + " µs";
    }
    const auto cheap = cheapestWithin(options, 0.01);
    reading += cheap ? "; the cheapest within 1 % is " + cheap->label + " (" + num(cheap->cost) + " µs)."
                     : "; no ground stays within 1 %.";
  }
  s.reading = reading;
  s.caption = "Relief map and BVH mesh points labelled with their size N (N x N). Source: bench_physics.json";
  return s;
}

}  // namespace thx::bench::report
