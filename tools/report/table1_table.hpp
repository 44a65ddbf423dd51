#pragma once
// bench_table1's table: the paper's Table 1 (one textured surface as a normal map, a relief map
// and meshes of 256² and 512² quads) with our measurement beside the paper's figure in every
// cell, and each also as a ratio to the normal-map column. Writers for docs/results/table1.{md,csv}.
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace thx::bench::table1 {

enum Column { kNormal = 0, kRelief = 1, kMesh256 = 2, kMesh512 = 3 };
inline constexpr int kColumns = 4;
const char* columnName(int column);  // "normal map", "relief map", "mesh 256²", "mesh 512²"
const char* columnKey(int column);   // "normal", "relief", "mesh256", "mesh512" (CSV)

// How a cell was obtained. Measured: on this machine in this run. Extrapolated: a fit of measured
// points (shown below the table). Computed: exact arithmetic from counts, not allocated. Pending:
// the method is not in the project yet (note says which). None: the quantity does not apply.
enum class Source { Measured, Extrapolated, Computed, Pending, None };
const char* sourceName(Source s);

struct Cell {
  double value = std::nan("");
  Source source = Source::None;
  std::string note;  // pending: why; otherwise optional detail for the CSV
};

// The paper's figure; `star` = extrapolated in the paper (its asterisk).
struct PaperCell {
  double value = std::nan("");
  bool star = false;
  std::string text;  // when it is not a number ("not measurable")
};

enum class Unit { Bytes, Seconds, Count };

struct Metric {
  std::string key;   // CSV
  std::string name;  // Markdown
  Unit unit = Unit::Count;
  std::array<Cell, kColumns> ours;
  std::array<PaperCell, kColumns> paper;
};

// "10 KB", "4.5 MB", "4500 GB", "175 µs", "66,049" (binary prefixes, 1 KB = 1024 B, up to GB).
std::string formatValue(double value, Unit unit);
// "× 12.3" of value / the normal column's (blank when either is missing or the normal's is 0).
std::string formatRatio(double value, double normal);

// One Markdown table: per metric a line "ours" and a line "paper", each cell "value (× ratio)";
// extrapolated cells carry '*', computed ones '†'.
std::string markdownTable(const std::vector<Metric>& metrics);
// metric,unit,source_of_figure(ours|paper),column,value,ratio_to_normal,how,note
std::string csvTable(const std::vector<Metric>& metrics);

}  // namespace thx::bench::table1
