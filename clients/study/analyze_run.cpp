#include "clients/study/analyze_run.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "clients/study/analysis.hpp"
#include "clients/study/bar_chart.hpp"
#include "clients/study/report.hpp"
#include "clients/study/session_csv.hpp"

namespace thx::study {

namespace {

void writeText(const std::string& path, const std::string& text, AnalyzeOutput& out) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f << text;
  f.flush();
  if (!f) throw Error(Error::Kind::Io, path + ": cannot write");
  out.files.push_back(path);
}

BarPanel idRatePanel(const IdentificationResults& r) {
  BarPanel p{"ID rate by cue condition", "ID rate", {}, 1.0, {{"ID rate", 70, 120, 180, {}, {}}}};
  for (const IdGroup& g : r.by_cue) {
    p.categories.push_back(g.label);
    p.series[0].values.push_back(g.idRate());
  }
  return p;
}

BarPanel timePanel(const IdentificationResults& r) {
  BarPanel p{"Time of correct answers (mean, SD)", "seconds", {}, 1.0, {{"time", 220, 140, 60, {}, {}}}};
  for (const IdGroup& g : r.by_cue) {
    const Summary s = g.time();
    p.categories.push_back(g.label);
    p.series[0].values.push_back(s.mean);
    p.series[0].errors.push_back(s.sd);
    if (!std::isnan(s.mean)) p.y_max = std::max(p.y_max, (s.mean + (std::isnan(s.sd) ? 0 : s.sd)) * 1.15);
  }
  return p;
}

BarPanel ratingsPanel(const RatingResults& r) {
  BarPanel p{"Ratings by representation (participant means, SD)", "rating (1-10)", {}, 10.0,
             {{"relief", 200, 90, 60, {}, {}}, {"normal", 70, 120, 180, {}, {}}}};
  for (const RatingComparison& c : r.paired) {
    const Summary a = summarize(c.relief), b = summarize(c.normal);
    p.categories.emplace_back(ratingScale(c.rating).column);
    p.series[0].values.push_back(a.mean);
    p.series[0].errors.push_back(a.sd);
    p.series[1].values.push_back(b.mean);
    p.series[1].errors.push_back(b.sd);
  }
  return p;
}

}  // namespace

AnalyzeOutput analyzeSessions(const std::vector<std::string>& session_files, const std::string& out_dir) {
  std::vector<Session> sessions;
  for (const std::string& f : session_files) sessions.push_back(readSession(f));
  // Analyse before creating anything, so a refused set of sessions leaves no folder behind.
  const IdentificationResults id = analyzeIdentification(sessions);
  const RatingResults rt = analyzeRatings(sessions);
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) throw Error(Error::Kind::Io, out_dir + ": cannot create the output folder: " + ec.message());
  const auto at = [&](const std::string& name) { return (std::filesystem::path(out_dir) / name).string(); };

  AnalyzeOutput out;
  std::string md = "# User study analysis\n\nSessions:";
  for (const std::string& f : session_files) md += " `" + std::filesystem::path(f).filename().string() + "`";
  md += "\n\n";
  std::vector<Table> tables;
  out.identification_sessions = id.sessions;
  out.rating_sessions = rt.sessions;
  if (id.sessions > 0) {
    md += "## Study 1: material identification\n\n![ID rate and time by cue](identification_by_cue.png)\n\n";
    for (Table& t : identificationTables(id)) {
      md += markdown(t) + "\n";
      tables.push_back(std::move(t));
    }
  }
  if (rt.sessions > 0) {
    md += "## Study 2: relief against normal maps\n\n![ratings by representation](ratings_by_representation.png)\n\n";
    for (Table& t : ratingTables(rt)) {
      md += markdown(t) + "\n";
      tables.push_back(std::move(t));
    }
  }
  writeText(at("study.md"), md, out);
  for (const Table& t : tables) writeText(at(t.name + ".csv"), csv(t), out);
  if (id.sessions > 0) {
    writeBarChartPng(at("identification_by_cue.png"), {idRatePanel(id), timePanel(id)},
                     "Study 1, " + std::to_string(id.sessions) + " sessions");
    out.files.push_back(at("identification_by_cue.png"));
  }
  if (rt.sessions > 0) {
    writeBarChartPng(at("ratings_by_representation.png"), {ratingsPanel(rt)},
                     "Study 2, " + std::to_string(rt.paired.front().relief.size()) + " participants paired",
                     760, 440);
    out.files.push_back(at("ratings_by_representation.png"));
  }
  return out;
}

}  // namespace thx::study
