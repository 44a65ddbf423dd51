// Modal analysis: the worst relative error of the modal frequencies against the solve's time and
// peak memory, linear (Tet4) against quadratic (Tet10) tetrahedra (bench_audio_fem; docs/audio.md
// §6 defines the references and what is timed).
#include <algorithm>
#include <tuple>

#include "tools/report/report_sections.hpp"

namespace thx::bench::report {

namespace {

struct Case {
  std::string part, object, element, size;
  double dofs = 0, error = 0, seconds = 0, mb = 0;
};

// A short ASCII legend name (OpenCV's fonts): the first two words before a comma or bracket,
// "scene ..." for the scenes' bodies so the scene's sphere and the validation sphere differ.
std::string plotName(const std::string& object, const std::string& part) {
  std::string name = object.substr(0, object.find_first_of(",("));
  const std::size_t first = name.find(' ');
  const std::size_t second = first == std::string::npos ? first : name.find(' ', first + 1);
  name = name.substr(0, second);
  while (!name.empty() && name.back() == ' ') name.pop_back();
  return part == "validation" ? name : "scene " + name;
}

std::string label(const Case& c) { return c.element + " size " + c.size + " (" + num(c.dofs) + " DOF)"; }

}  // namespace

Section femSection(const std::filesystem::path& dir) {
  Section s;
  s.id = "modal";
  s.title = "Modal analysis: frequency error against solve cost";
  s.command = "benchmarks/run.sh BUILD audio";
  s.what =
      "The FEM modal analysis (ARPACK shift-invert) of the validation objects (a free bar, a free plate, a free "
      "sphere) against their analytic frequencies, and of the shipped scenes' bodies against their finest mesh: "
      "the worst relative frequency error over the modes compared, against the whole solve's CPU time, one thread (assemble, factor, "
      "iterate) and the peak resident memory of the child process that solved it. Sizes are mesh divisions; a bold "
      "size is the one the scene ships. Definitions and references: docs/audio.md §6 and §8.";
  const auto f = readResults(dir, "bench_audio_fem.json");
  if (!f) return notMeasured(s, dir, "bench_audio_fem.json");
  s.machine_lines.push_back(machineLine(*f));

  std::vector<Case> cases;
  const nlohmann::json& data = array(*f, f->json, "", "cases");
  for (std::size_t i = 0; i < data.size(); ++i) {
    const std::string w = at("", "cases", i);
    const nlohmann::json& r = data[i];
    cases.push_back({text(*f, r, w, "part"), text(*f, r, w, "object"), text(*f, r, w, "element"),
                     text(*f, r, w, "size"), number(*f, r, w, "dofs"), number(*f, r, w, "max_rel_error"),
                     number(*f, r, w, "cpu_s"), number(*f, r, w, "peak_rss_mb")});
  }
  if (cases.empty()) throw Error(Error::Kind::Config, f->path + ": cases: expected at least one case, got none");
  // The table in order of object, element and cost (the file lists refinements as they were added).
  std::stable_sort(cases.begin(), cases.end(), [](const Case& a, const Case& b) {
    return std::tie(a.part, a.object, a.element, a.dofs) < std::tie(b.part, b.object, b.element, b.dofs);
  });

  std::string t = "| part | object | element | size | DOF | worst frequency error | solve CPU (s) | peak memory (MB) |\n"
                  "|---|---|---|---|---|---|---|---|\n";
  for (const Case& c : cases) {
    const bool reference = c.part != "validation" && c.error == 0;
    t += "| " + c.part + " | " + c.object + " | " + c.element + " | " + c.size + " | " + num(c.dofs) + " | " +
         (reference ? std::string("(reference)") : percent(c.error)) + " | " + num(c.seconds) + " | " + num(c.mb) +
         " |\n";
  }
  s.table = t;

  std::vector<std::string> objects;
  for (const Case& c : cases) {
    if (std::find(objects.begin(), objects.end(), c.object) == objects.end()) objects.push_back(c.object);
  }
  std::string reading;
  PlotPanel by_time, by_memory;
  by_time.title = "frequency error against solve time";
  by_time.x_label = "solve time (s)";
  by_memory.title = "frequency error against peak memory";
  by_memory.x_label = "peak resident memory (MB)";
  by_time.y_label = by_memory.y_label = "worst relative frequency error (%)";
  std::size_t colour = 0;
  for (const std::string& object : objects) {
    std::vector<Option> options;
    std::string part;
    for (const char* element : {"Tet4", "Tet10"}) {
      PlotSeries ser;
      for (const Case& c : cases) {
        if (c.object != object || c.element != element) continue;
        part = c.part;
        if (c.part != "validation" && c.error == 0) continue;  // the reference itself
        options.push_back({label(c), c.seconds, c.error});
        ser.x.push_back(c.seconds);
        ser.y.push_back(100 * c.error);
      }
      if (ser.x.empty()) continue;
      ser.label = plotName(object, part) + " " + element;
      ser.color = palette(colour++);
      ser.marker = std::string(element) == "Tet4" ? Marker::Square : Marker::Circle;
      ser.filled = part == "validation";
      by_time.series.push_back(ser);
      PlotSeries mem = ser;
      mem.x.clear();
      for (const Case& c : cases) {
        if (c.object == object && c.element == element && !(c.part != "validation" && c.error == 0)) {
          mem.x.push_back(c.mb);
        }
      }
      by_memory.series.push_back(mem);
    }
    if (options.empty()) continue;
    reading += (reading.empty() ? "" : " ") + std::string("For the ") + object +
               (part == "validation" ? " (against its analytic frequencies)" : " (against its finest mesh)");
    for (double budget : {0.1, 1.0}) {
      const auto best = mostAccurateWithin(options, budget);
      reading += best ? ", within " + num(budget) + " s the most accurate is " + best->label + " at " +
                            percent(best->error) + " (" + num(best->cost) + " s)"
                      : ", nothing fits within " + num(budget) + " s";
    }
    const auto cheap = cheapestWithin(options, 0.01);
    reading += cheap ? "; the cheapest within 1 % is " + cheap->label + " (" + num(cheap->cost) + " s)."
                     : "; nothing measured reaches 1 %.";
  }
  s.reading = reading + " The solve runs offline, once per body (the result is cached, docs/audio.md §2), so a "
                        "budget here is start-up time, not frame time.";
  fitAxes(by_time);
  fitAxes(by_memory);
  s.panels = {by_time, by_memory};
  s.caption = "Squares: Tet4, circles: Tet10; filled: validation objects, hollow: scene bodies (against their finest "
              "mesh). Source: bench_audio_fem.json";
  return s;
}

}  // namespace thx::bench::report
