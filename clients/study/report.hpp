#pragma once
// study-analyze's tables (docs/study.md §4) as text: each one Markdown for the report and CSV
// for other tools. A cell without a value (a test with too few data) is empty in CSV and "–"
// in Markdown.
#include <string>
#include <vector>

#include "clients/study/analysis.hpp"

namespace thx::study {

struct Table {
  std::string name;   // file stem of its CSV, e.g. "identification_by_cue"
  std::string title;  // Markdown heading
  std::string note;   // what the numbers are, under the heading
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;
};

std::vector<Table> identificationTables(const IdentificationResults& r);
std::vector<Table> ratingTables(const RatingResults& r);

std::string markdown(const Table& t);
std::string csv(const Table& t);

}  // namespace thx::study
