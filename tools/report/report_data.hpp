#pragma once
// The speed-against-error report (bench_report): reading the benchmarks' results files with
// errors that name the file and the field, the machine line, budget picks and number formatting.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tools/report/plot.hpp"

namespace thx::bench::report {

// One results file: its parsed JSON and the path messages name.
struct ResultsFile {
  std::string path;
  nlohmann::json json;
};

// dir/name parsed; nullopt when the file does not exist. Throws thx::Error (Kind::Config) naming
// the file when it exists but is not JSON.
std::optional<ResultsFile> readResults(const std::filesystem::path& dir, const std::string& name);

// Checked access. `where` is the JSON path of `obj` for messages ("rows[3]"; "" at the top). Each
// throws thx::Error "FILE: WHERE.KEY: expected ..., got ..." when the field is absent or of the
// wrong type.
const nlohmann::json& array(const ResultsFile& f, const nlohmann::json& obj, const std::string& where,
                            const std::string& key);
double number(const ResultsFile& f, const nlohmann::json& obj, const std::string& where, const std::string& key);
std::string text(const ResultsFile& f, const nlohmann::json& obj, const std::string& where, const std::string& key);
// Absent or null gives nullopt; present and not a number throws.
std::optional<double> optionalNumber(const ResultsFile& f, const nlohmann::json& obj, const std::string& where,
                                     const std::string& key);
// "where[i]" for the i-th element of array `key` under `where`.
std::string at(const std::string& where, const std::string& key, std::size_t i);

// The run's stamp as the benchmark wrote it: machine (or renderer), date, load average and build
// type, each "not recorded" when the file has no such field.
std::string machineLine(const ResultsFile& f);

// A configuration a user could pick: what it is, what it costs, how wrong it is.
struct Option {
  std::string label;
  double cost = 0;
  double error = 0;
};
// The most accurate option costing at most `budget` (ties: the cheaper); nullopt if none fits.
std::optional<Option> mostAccurateWithin(const std::vector<Option>& options, double budget);
// The cheapest option whose error is at most `tolerance` (ties: the more accurate).
std::optional<Option> cheapestWithin(const std::vector<Option>& options, double tolerance);

// Numbers for prose and tables: `sig` significant digits; percent of a fraction.
std::string num(double v, int sig = 3);
std::string percent(double fraction, int sig = 3);

// A plot colour from a fixed palette (cycles).
Rgb palette(std::size_t i);
// Panel bounds around the positive values of its series, padded (log axes) or from zero (linear).
void fitAxes(PlotPanel& panel);

// One modality's part of the report.
struct Section {
  std::string id;       // the picture's name: report/<id>.png
  std::string title;
  std::string command;  // what regenerates its results
  std::string what;     // fixed prose: what is measured and where it is documented
  bool measured = true;
  std::string missing;  // why not, when !measured
  std::vector<std::string> machine_lines;  // one per results file
  std::string table;                       // markdown
  std::string reading;                     // computed from the data
  std::vector<PlotPanel> panels;
  std::string caption;
};

// A section for a results file that does not exist.
Section notMeasured(Section s, const std::filesystem::path& dir, const std::string& file);

}  // namespace thx::bench::report
