#include "clients/study/session_csv.hpp"

#include <charconv>
#include <cstring>
#include <sstream>
#include <vector>

namespace thx::study {

namespace {

std::vector<std::string> columns() {
  std::vector<std::string> c{"trial", "surface", "representation", "sound", "ball", "pen", "answer", "correct", "time_s"};
  for (int i = 0; i < kRatingCount; ++i) c.emplace_back(ratingScale(static_cast<Rating>(i)).column);
  return c;
}

std::string numberField(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);  // shortest text that reads back exactly
  return std::string(buf, r.ptr);
}

std::vector<std::string_view> split(std::string_view line, char sep) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t p = line.find(sep, start);
    out.push_back(line.substr(start, p == std::string_view::npos ? std::string_view::npos : p - start));
    if (p == std::string_view::npos) return out;
    start = p + 1;
  }
}

std::string place(const std::string& source, int line) { return source + ":" + std::to_string(line); }

[[noreturn]] void fieldError(const std::string& where, std::string_view field, const std::string& expected,
                             std::string_view got) {
  throw SessionError(where + ": field '" + std::string(field) + "': expected " + expected + ", got '" +
                     shownText(got) + "'");
}

template <class T>
bool parseWhole(std::string_view text, T& value) {
  if (text.empty() || text.front() == '+') return false;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), value);
  return r.ec == std::errc() && r.ptr == text.data() + text.size();
}

bool parseFlag(std::string_view text, bool& value) {
  if (text != "0" && text != "1") return false;
  value = text == "1";
  return true;
}

TrialRow parseRow(const std::vector<std::string_view>& f, const std::vector<std::string>& names,
                  const std::string& where) {
  TrialRow row;
  if (!parseWhole(f[0], row.trial) || row.trial < 1) fieldError(where, names[0], "a trial number >= 1", f[0]);
  if (!isToken(f[1])) fieldError(where, names[1], "a surface name", f[1]);
  row.surface = f[1];
  const auto rep = parseRepresentation(f[2]);
  if (!rep) fieldError(where, names[2], "normal, relief or mesh", f[2]);
  row.representation = *rep;
  for (int i = 0; i < 3; ++i) {
    bool on = true;
    if (!parseFlag(f[std::size_t(3 + i)], on)) fieldError(where, names[std::size_t(3 + i)], "1 (cue on) or 0 (off)", f[std::size_t(3 + i)]);
    (i == 0 ? row.cues.sound : i == 1 ? row.cues.ball : row.cues.pen) = on;
  }
  if (!f[6].empty() && !isToken(f[6])) fieldError(where, names[6], "a surface name or nothing", f[6]);
  row.answer = f[6];
  if (!f[7].empty()) {
    bool c = false;
    if (!parseFlag(f[7], c)) fieldError(where, names[7], "1, 0 or nothing", f[7]);
    row.correct = c;
  }
  if (!f[8].empty()) {
    double t = 0;
    if (!parseWhole(f[8], t)) fieldError(where, names[8], "seconds (a number) or nothing", f[8]);
    row.time_s = t;
  }
  for (int i = 0; i < kRatingCount; ++i) {
    const std::string_view text = f[std::size_t(9 + i)];
    if (text.empty()) continue;
    int v = 0;
    if (!parseWhole(text, v)) fieldError(where, names[std::size_t(9 + i)], "a whole number or nothing", text);
    row.ratings[std::size_t(i)] = v;
  }
  return row;
}

void parseHeaderValue(SessionHeader& h, std::string_view key, std::string_view value, const std::string& where) {
  if (key == "study") {
    const auto s = parseStudy(value);
    if (!s) fieldError(where, key, "identification or relief-vs-normal", value);
    h.study = *s;
  } else if (key == "participant") {
    h.participant = value;
  } else if (key == "seed") {
    if (!parseWhole(value, h.seed)) fieldError(where, key, "a whole number in [0, 2^64)", value);
  } else if (key == "software") {
    h.software = value;
  } else if (key == "surfaces") {
    for (std::string_view item : split(value, ' ')) {
      const auto eq = item.find('=');
      if (item.empty() || eq == std::string_view::npos) {
        fieldError(where, key, "space-separated NAME=FAMILY items", item);
      }
      h.surfaces.push_back({std::string(item.substr(0, eq)), std::string(item.substr(eq + 1))});
    }
  } else {
    for (const auto& [k, v] : h.extra) {
      if (k == key) throw SessionError(where + ": header key '" + shownText(key) + "' appears twice");
    }
    h.extra.emplace_back(key, value);
  }
}

}  // namespace

std::string columnLine() {
  std::string s;
  for (const std::string& c : columns()) s += (s.empty() ? "" : ",") + c;
  return s;
}

namespace {

std::string headerText(const SessionHeader& h) {
  std::string s = std::string(kSessionMagic) + "\n# format: " + std::to_string(kSessionFormat) +
                  "\n# study: " + std::string(studyName(h.study)) + "\n# participant: " + h.participant +
                  "\n# seed: " + std::to_string(h.seed) + "\n# software: " + h.software + "\n# surfaces:";
  for (const Candidate& c : h.surfaces) s += ' ' + c.name + '=' + c.family;
  s += '\n';
  for (const auto& [key, value] : h.extra) s += "# " + key + ": " + value + '\n';
  return s + columnLine() + '\n';
}

std::string rowText(const TrialRow& row) {
  std::string s = std::to_string(row.trial) + ',' + row.surface + ',' + std::string(representationName(row.representation)) +
                  ',' + (row.cues.sound ? '1' : '0') + ',' + (row.cues.ball ? '1' : '0') + ',' +
                  (row.cues.pen ? '1' : '0') + ',' + row.answer + ',' +
                  (row.correct ? (*row.correct ? "1" : "0") : "") + ',' + (row.time_s ? numberField(*row.time_s) : "");
  for (const std::optional<int>& r : row.ratings) s += ',' + (r ? std::to_string(*r) : "");
  return s + '\n';
}

}  // namespace

SessionWriter::SessionWriter(const std::string& path, const SessionHeader& header)
    : path_(path), header_(header), rules_(header_) {
  checkHeader(header_, path_ + ": header");
  out_.open(path_, std::ios::binary | std::ios::trunc);
  if (!out_) throw Error(Error::Kind::Io, path_ + ": cannot create the session file: " + std::strerror(errno));
  out_ << headerText(header_);
  line_ = 8 + static_cast<int>(header_.extra.size());
  flushOrThrow();
}

void SessionWriter::append(const TrialRow& row) {
  ++line_;
  rules_.check(row, place(path_, line_));
  out_ << rowText(row);
  flushOrThrow();
}

void SessionWriter::flushOrThrow() {
  out_.flush();
  if (!out_) throw Error(Error::Kind::Io, path_ + ": cannot write the session file");
}

void writeSession(const std::string& path, const Session& session) {
  SessionWriter w(path, session.header);
  for (const TrialRow& r : session.trials) w.append(r);
}

std::string formatSession(const Session& session, const std::string& name) {
  checkHeader(session.header, name + ": header");
  std::string text = headerText(session.header);
  RowRules rules(session.header);
  int line = 8 + static_cast<int>(session.header.extra.size());
  for (const TrialRow& r : session.trials) {
    rules.check(r, place(name, ++line));
    text += rowText(r);
  }
  return text;
}

Session readSession(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(Error::Kind::Io, path + ": cannot open the session file: " + std::strerror(errno));
  std::stringstream text;
  text << in.rdbuf();
  return parseSession(text.str(), path);
}

Session parseSession(std::string_view text, const std::string& source) {
  Session s;
  s.source = source;
  std::vector<std::string_view> lines = split(text, '\n');
  if (!lines.empty() && lines.back().empty()) lines.pop_back();
  for (std::string_view& l : lines) {
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
  }
  if (lines.empty() || lines[0] != kSessionMagic) {
    throw SessionError(place(source, 1) + ": expected '" + std::string(kSessionMagic) +
                       "' (not a session file of this project)");
  }
  bool has_format = false, has_study = false, has_seed = false, has_participant = false, has_software = false,
       has_surfaces = false;
  std::size_t i = 1;
  for (; i < lines.size() && !lines[i].empty() && lines[i][0] == '#'; ++i) {
    const std::string where = place(source, int(i + 1));
    const std::string_view l = lines[i];
    const auto colon = l.find(": ");
    if (l.size() < 3 || l[1] != ' ' || colon == std::string_view::npos) {
      throw SessionError(where + ": expected a header line '# key: value', got '" + shownText(l) + "'");
    }
    const std::string_view key = l.substr(2, colon - 2), value = l.substr(colon + 2);
    bool* once = key == "format"        ? &has_format
                 : key == "study"       ? &has_study
                 : key == "seed"        ? &has_seed
                 : key == "participant" ? &has_participant
                 : key == "software"    ? &has_software
                 : key == "surfaces"    ? &has_surfaces
                                        : nullptr;
    if (once && *once) throw SessionError(where + ": header key '" + shownText(key) + "' appears twice");
    if (key == "format") {
      int f = 0;
      if (!parseWhole(value, f) || f != kSessionFormat) {
        fieldError(where, key, std::to_string(kSessionFormat) + " (the format this reader knows)", value);
      }
      has_format = true;
      continue;
    }
    parseHeaderValue(s.header, key, value, where);
    if (once) *once = true;
  }
  const std::string header_place = place(source, 1) + ": header";
  for (auto [has, key] : {std::pair{has_format, "format"}, {has_study, "study"}, {has_participant, "participant"},
                          {has_seed, "seed"}, {has_software, "software"}, {has_surfaces, "surfaces"}}) {
    if (!has) throw SessionError(header_place + ": missing the line '# " + std::string(key) + ": ...'");
  }
  checkHeader(s.header, header_place);
  const std::vector<std::string> names = columns();
  if (i >= lines.size() || lines[i] != columnLine()) {
    throw SessionError(place(source, int(i + 1)) + ": expected the column line '" + columnLine() + "', got '" +
                       (i < lines.size() ? shownText(lines[i]) : std::string("end of file")) + "'");
  }
  RowRules rules(s.header);
  for (++i; i < lines.size(); ++i) {
    const std::string where = place(source, int(i + 1));
    const std::vector<std::string_view> f = split(lines[i], ',');
    if (f.size() != names.size()) {
      throw SessionError(where + ": expected " + std::to_string(names.size()) + " comma-separated fields, got " +
                         std::to_string(f.size()));
    }
    TrialRow row = parseRow(f, names, where);
    rules.check(row, where);
    s.trials.push_back(std::move(row));
  }
  return s;
}

}  // namespace thx::study
