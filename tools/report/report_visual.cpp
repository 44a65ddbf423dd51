// Visual: image error against the exact CPU reference (share of pixels showing another texel,
// and mean colour error) against frame time, by mode, search settings and image size
// (bench_visual; docs/visual.md defines the measurement).
#include <algorithm>
#include <map>

#include "tools/report/report_sections.hpp"

namespace thx::bench::report {

namespace {

struct FrameRow {
  std::string config, group, resolution;
  double ms = 0, texel = 0, lsb = 0;
};

// The configuration's name, and its family for the plot (shadows are their own family).
std::pair<std::string, std::string> describe(const std::string& mode, const std::string& search, int linear,
                                             int binary, int shadow, int mesh) {
  std::string config, group;
  if (mode == "mesh") {
    config = "mesh " + std::to_string(mesh) + "²";
    group = "mesh";
  } else if (mode == "relief" && search == "maxmip") {
    config = group = "relief max-mipmap";
  } else if (mode == "relief") {
    config = "relief linear " + std::to_string(linear) + " + binary " + std::to_string(binary);
    group = "relief linear";
  } else {
    config = group = mode;
  }
  if (shadow > 0) {
    config += ", shadows " + std::to_string(shadow);
    group += " + shadows";
  }
  return {config, group};
}

}  // namespace

Section visualSection(const std::filesystem::path& dir) {
  Section s;
  s.id = "visual";
  s.title = "Visual: image error against frame time";
  s.command = "benchmarks/run.sh BUILD visual";
  s.what =
      "The visual client's median frame time (with `glFinish`, on the renderer the machine line names) "
      "against the exact CPU reference image: the share of pixels that show another texel than the reference "
      "(\"mis-texel\") and the mean colour error in 8-bit steps (LSB). Modes: normal mapping, relief mapping with "
      "the linear + binary search or the max-mipmap walk, with and without self-shadows, and displaced meshes. "
      "Definitions: docs/visual.md, \"Speed against error\".";
  const auto f = readResults(dir, "bench_visual.json");
  if (!f) return notMeasured(s, dir, "bench_visual.json");
  s.machine_lines.push_back(machineLine(*f));

  std::vector<FrameRow> rows;
  std::vector<std::string> configs, groups, resolutions;
  const auto remember = [](std::vector<std::string>& v, const std::string& x) {
    if (std::find(v.begin(), v.end(), x) == v.end()) v.push_back(x);
  };
  const nlohmann::json& data = array(*f, f->json, "", "rows");
  for (std::size_t i = 0; i < data.size(); ++i) {
    const std::string w = at("", "rows", i);
    const nlohmann::json& r = data[i];
    const auto [config, group] =
        describe(text(*f, r, w, "mode"), text(*f, r, w, "search"), int(number(*f, r, w, "linear_steps")),
                 int(number(*f, r, w, "binary_steps")), int(number(*f, r, w, "shadow_steps")),
                 int(number(*f, r, w, "mesh_n")));
    const std::string res =
        std::to_string(int(number(*f, r, w, "width"))) + "x" + std::to_string(int(number(*f, r, w, "height")));
    rows.push_back({config, group, res, number(*f, r, w, "median_ms"), number(*f, r, w, "other_texel_fraction"),
                    number(*f, r, w, "mean_error_lsb")});
    remember(configs, config);
    remember(groups, group);
    remember(resolutions, res);
  }
  if (rows.empty()) throw Error(Error::Kind::Config, f->path + ": rows: expected at least one row, got none");

  std::string t = "| configuration |", rule = "|---|";
  for (const std::string& res : resolutions) {
    t += " " + res + ": ms/frame | mis-texel | error (LSB) |";
    rule += "---|---|---|";
  }
  t += "\n" + rule + "\n";
  for (const std::string& c : configs) {
    t += "| " + c + " |";
    for (const std::string& res : resolutions) {
      const auto it =
          std::find_if(rows.begin(), rows.end(), [&](const FrameRow& r) { return r.config == c && r.resolution == res; });
      t += it == rows.end() ? " – | – | – |" : " " + num(it->ms) + " | " + percent(it->texel) + " | " + num(it->lsb) + " |";
    }
    t += "\n";
  }
  s.table = t;

  // Reading: per image size, the fewest mis-texels within each frame budget.
  std::string reading;
  for (const std::string& res : resolutions) {
    std::vector<Option> options;
    std::map<std::string, double> lsb;
    for (const FrameRow& r : rows) {
      if (r.resolution != res) continue;
      // Equal shares (shadows change colour, not texels) go to the cheaper configuration.
      options.push_back({r.config, r.ms, r.texel});
      lsb[r.config] = r.lsb;
    }
    reading += (reading.empty() ? "" : " ") + std::string("At ") + res;
    for (double budget : {1000.0 / 60, 1000.0 / 30}) {
      const auto best = mostAccurateWithin(options, budget);
      reading += best ? ", within " + num(budget) + " ms per frame (" + num(1000 / budget) +
                            " Hz) the most accurate is " + best->label + " at " + percent(best->error) +
                            " mis-texels (" + num(lsb[best->label]) + " LSB, " + num(best->cost) + " ms)"
                      : ", nothing fits within " + num(budget) + " ms per frame (" + num(1000 / budget) + " Hz)";
    }
    const auto cheap = cheapestWithin(options, 0.001);
    reading += cheap ? "; the cheapest under 0.1 % mis-texels is " + cheap->label + " (" + num(cheap->cost) + " ms)."
                     : "; nothing stays under 0.1 % mis-texels.";
  }
  const auto renderer = f->json.find("renderer");
  s.reading = reading + " Frame times are those of the renderer that ran the benchmark (" +
              (renderer != f->json.end() && renderer->is_string() ? renderer->get<std::string>() : "not recorded") +
              "); another renderer changes them, so compare configurations by their ratios to one another.";

  // Plot: mis-texels and colour error against frame time; filled markers for the first image size.
  PlotPanel texel, colour;
  texel.title = "share of pixels showing another texel";
  colour.title = "mean colour error";
  texel.x_label = colour.x_label = "median frame time (ms)";
  texel.y_label = "mis-texel (%)";
  colour.y_label = "mean error (LSB)";
  for (std::size_t ri = 0; ri < resolutions.size(); ++ri) {
    for (std::size_t gi = 0; gi < groups.size(); ++gi) {
      PlotSeries a;
      a.label = groups[gi];  // one legend entry per family: the caption says which marker is which size
      a.color = palette(gi);
      a.marker = Marker(ri % 3);
      a.filled = ri == 0;
      a.connect = false;
      PlotSeries b = a;
      for (const FrameRow& r : rows) {
        if (r.resolution != resolutions[ri] || r.group != groups[gi]) continue;
        a.x.push_back(r.ms);
        a.y.push_back(100 * r.texel);
        b.x.push_back(r.ms);
        b.y.push_back(r.lsb);
      }
      if (a.x.empty()) continue;
      texel.series.push_back(a);
      colour.series.push_back(b);
    }
  }
  fitAxes(texel);
  fitAxes(colour);
  s.panels = {texel, colour};
  s.caption = "Filled circles: " + resolutions.front() +
              (resolutions.size() > 1 ? "; hollow squares: " + resolutions[1] : std::string()) +
              (resolutions.size() > 2 ? ", hollow triangles: " + resolutions[2] : std::string()) +
              ". Source: bench_visual.json";
  return s;
}

}  // namespace thx::bench::report
