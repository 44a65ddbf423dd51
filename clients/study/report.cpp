#include "clients/study/report.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace thx::study {

namespace {

// Fixed decimals; "" for NaN (no value).
std::string fixed(double v, int decimals) {
  if (std::isnan(v)) return "";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string pText(double p) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", p);
  return buf;
}

std::vector<std::string> idCells(const IdGroup& g) {
  const Summary t = g.time();
  return {std::to_string(g.trials), std::to_string(g.correct), fixed(g.idRate(), 3), fixed(t.mean, 2), fixed(t.sd, 2)};
}

void append(std::vector<std::string>& row, const std::optional<TTest>& t) {
  if (t) {
    row.insert(row.end(), {fixed(t->t, 3), fixed(t->df, 2), pText(t->p)});
  } else {
    row.insert(row.end(), {"", "", ""});
  }
}

Table confusion(const std::string& name, const std::string& title, const std::string& note, const ConfusionMatrix& m) {
  Table t{name, title, note, {"truth \\ answer"}, {}};
  for (const std::string& l : m.labels()) t.columns.push_back(l);
  t.columns.insert(t.columns.end(), {"trials", "id_rate"});
  for (std::size_t i = 0; i < m.labels().size(); ++i) {
    std::vector<std::string> row{m.labels()[i]};
    for (std::size_t j = 0; j < m.labels().size(); ++j) row.push_back(std::to_string(m.count(i, j)));
    const int n = m.rowTotal(i);
    row.push_back(std::to_string(n));
    row.push_back(n == 0 ? "" : fixed(double(m.count(i, i)) / n, 3));
    t.rows.push_back(std::move(row));
  }
  return t;
}

std::string csvCell(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

bool isNumber(const std::string& s) {
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return !s.empty() && end == s.c_str() + s.size();
}

// Numbers are right-aligned in Markdown, names left.
bool numericColumn(const Table& t, std::size_t i) {
  for (const auto& row : t.rows) {
    if (!row[i].empty() && !isNumber(row[i])) return false;
  }
  return !t.rows.empty();
}

}  // namespace

std::vector<Table> identificationTables(const IdentificationResults& r) {
  const std::vector<std::string> id_columns{"trials", "correct", "id_rate", "time_mean_s", "time_sd_s"};
  std::vector<Table> out;
  Table cond{"identification_by_condition", "Study 1: identification by condition (Table 2)",
             "ID rate = correct answers / trials; times are those of correct answers (mean, sample SD), " +
                 std::to_string(r.sessions) + " sessions.",
             {"condition"}, {}};
  cond.columns.insert(cond.columns.end(), id_columns.begin(), id_columns.end());
  for (const IdGroup& g : r.by_condition) {
    std::vector<std::string> row{g.label};
    for (std::string& c : idCells(g)) row.push_back(std::move(c));
    cond.rows.push_back(std::move(row));
  }
  out.push_back(std::move(cond));

  Table cue{"identification_by_cue", "Study 1: identification by cue removed (Table 3)",
            "Correct-answer times of each condition against those with all cues: Student's t (pooled "
            "variance), Welch's t (Welch–Satterthwaite df), two-sided p; Cohen's d with pooled SD.",
            {"condition"}, {}};
  cue.columns.insert(cue.columns.end(), id_columns.begin(), id_columns.end());
  cue.columns.insert(cue.columns.end(), {"student_t", "student_df", "student_p", "welch_t", "welch_df", "welch_p",
                                         "cohens_d"});
  for (std::size_t i = 0; i < r.by_cue.size(); ++i) {
    std::vector<std::string> row{r.by_cue[i].label};
    for (std::string& c : idCells(r.by_cue[i])) row.push_back(std::move(c));
    const TimeComparison& c = r.by_cue_against_all[i];
    append(row, c.student);
    append(row, c.welch);
    row.push_back(c.d ? fixed(*c.d, 3) : "");
    cue.rows.push_back(std::move(row));
  }
  out.push_back(std::move(cue));

  Table asked{"identification_ratings", "Study 1: ease and cue ratings by cue condition",
              "Mean (and sample SD) of the ratings given in each condition: ease 1–10, how much each cue was "
              "used 1–5, how accurate it felt 1–10; a removed cue is not rated.",
              {"condition"}, {}};
  for (int i = 0; i < kRatingCount; ++i) {
    const RatingScale& sc = ratingScale(Rating(i));
    if (sc.study != Study::Identification) continue;
    asked.columns.push_back(std::string(sc.column) + "_mean");
    asked.columns.push_back(std::string(sc.column) + "_sd");
  }
  for (const IdGroup& g : r.by_cue) {
    std::vector<std::string> row{g.label};
    for (int i = 0; i < kRatingCount; ++i) {
      if (ratingScale(Rating(i)).study != Study::Identification) continue;
      const Summary sm = summarize(g.ratings[std::size_t(i)]);
      row.push_back(fixed(sm.mean, 2));
      row.push_back(fixed(sm.sd, 2));
    }
    asked.rows.push_back(std::move(row));
  }
  out.push_back(std::move(asked));

  Table surf{"identification_by_surface", "Study 1: identification by surface (Table 4)",
             "Per surface drawn: trials, correct answers, ID rate, correct-answer time.", {"surface", "family"}, {}};
  surf.columns.insert(surf.columns.end(), id_columns.begin(), id_columns.end());
  for (const IdGroup& g : r.by_surface) {
    std::vector<std::string> row{g.label, g.family};
    for (std::string& c : idCells(g)) row.push_back(std::move(c));
    surf.rows.push_back(std::move(row));
  }
  out.push_back(std::move(surf));
  out.push_back(confusion("identification_confusion", "Study 1: confusion matrix by surface",
                          "Rows: the surface drawn; columns: the surface answered.", r.surfaces));
  out.push_back(confusion("identification_family_confusion", "Study 1: confusion matrix by sound family",
                          "Rows: the family of the surface drawn; columns: the family answered.", r.families));
  return out;
}

std::vector<Table> ratingTables(const RatingResults& r) {
  std::vector<Table> out;
  std::string note = "Per participant, the mean of their ratings of relief-mapped and of normal-mapped surfaces; "
                     "paired t-test (relief − normal, df = participants − 1), two-sided p; Cohen's d with the "
                     "pooled SD of the two columns. " + std::to_string(r.sessions) + " sessions";
  if (!r.unpaired_participants.empty()) {
    note += "; left out (rated one representation only):";
    for (const std::string& p : r.unpaired_participants) note += " " + p;
  }
  note += ".";
  Table paired{"ratings_relief_vs_normal", "Study 2: ratings, relief against normal maps (Table 5)", note,
               {"rating", "participants", "relief_mean", "relief_sd", "normal_mean", "normal_sd", "t", "df", "p",
                "cohens_d"},
               {}};
  for (const RatingComparison& c : r.paired) {
    const Summary a = summarize(c.relief), b = summarize(c.normal);
    std::vector<std::string> row{std::string(ratingScale(c.rating).column), std::to_string(c.relief.size()),
                                 fixed(a.mean, 2), fixed(a.sd, 2), fixed(b.mean, 2), fixed(b.sd, 2)};
    append(row, c.paired);
    row.push_back(c.d ? fixed(*c.d, 3) : "");
    paired.rows.push_back(std::move(row));
  }
  out.push_back(std::move(paired));

  Table surf{"ratings_by_surface", "Study 2: ratings by surface",
             "Each participant rates a surface in one representation: Welch's t between the participants "
             "who saw it as relief and those who saw it as normal.",
             {"surface", "rating", "relief_n", "relief_mean", "normal_n", "normal_mean", "welch_t", "welch_df",
              "welch_p"},
             {}};
  for (const SurfaceRating& s : r.by_surface) {
    std::vector<std::string> row{s.surface, std::string(ratingScale(s.rating).column), std::to_string(s.relief.size()),
                                 fixed(summarize(s.relief).mean, 2), std::to_string(s.normal.size()),
                                 fixed(summarize(s.normal).mean, 2)};
    append(row, s.welch);
    surf.rows.push_back(std::move(row));
  }
  out.push_back(std::move(surf));
  return out;
}

std::string markdown(const Table& t) {
  std::string s = "### " + t.title + "\n\n" + t.note + "\n\n|";
  for (const std::string& c : t.columns) s += " " + c + " |";
  s += "\n|";
  for (std::size_t i = 0; i < t.columns.size(); ++i) s += numericColumn(t, i) ? "---:|" : "---|";
  s += "\n";
  for (const auto& row : t.rows) {
    s += "|";
    for (const std::string& c : row) s += " " + (c.empty() ? std::string("–") : c) + " |";
    s += "\n";
  }
  return s;
}

std::string csv(const Table& t) {
  std::string s;
  for (std::size_t i = 0; i < t.columns.size(); ++i) s += (i ? "," : "") + csvCell(t.columns[i]);
  s += "\n";
  for (const auto& row : t.rows) {
    for (std::size_t i = 0; i < row.size(); ++i) s += (i ? "," : "") + csvCell(row[i]);
    s += "\n";
  }
  return s;
}

}  // namespace thx::study
