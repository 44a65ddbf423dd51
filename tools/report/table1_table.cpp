#include "tools/report/table1_table.hpp"

#include <cstdio>
#include <sstream>

namespace thx::bench::table1 {

const char* columnName(int c) {
  static const char* const names[kColumns] = {"normal map", "relief map", "mesh 256²", "mesh 512²"};
  return names[c];
}

const char* columnKey(int c) {
  static const char* const keys[kColumns] = {"normal", "relief", "mesh256", "mesh512"};
  return keys[c];
}

const char* sourceName(Source s) {
  switch (s) {
    case Source::Measured: return "measured";
    case Source::Extrapolated: return "extrapolated";
    case Source::Computed: return "computed";
    case Source::Pending: return "pending";
    case Source::None: return "none";
  }
  return "?";
}

namespace {

std::string printf1(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// Three significant digits at most, no trailing zeros beyond them.
std::string sig(double v) {
  if (v >= 100) return printf1("%.0f", v);
  if (v >= 10) return printf1("%.1f", v);
  return printf1("%.2f", v);
}

std::string thousands(double v) {
  std::string digits = printf1("%.0f", v), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

}  // namespace

std::string formatValue(double v, Unit unit) {
  if (std::isnan(v)) return "—";
  switch (unit) {
    case Unit::Bytes: {
      // Up to GB, as the paper writes its 4500 GB.
      const char* prefixes[] = {"B", "KB", "MB", "GB"};
      int p = 0;
      while (v >= 1024 && p < 3) v /= 1024, ++p;
      return sig(v) + " " + prefixes[p];
    }
    case Unit::Seconds:
      if (v >= 1) return sig(v) + " s";
      if (v >= 1e-3) return sig(v * 1e3) + " ms";
      return sig(v * 1e6) + " µs";
    case Unit::Count: return thousands(v);
  }
  return "?";
}

std::string formatRatio(double v, double normal) {
  if (std::isnan(v) || std::isnan(normal) || normal == 0) return "";
  const double r = v / normal;
  return "× " + (r >= 100 ? thousands(r) : sig(r));
}

std::string markdownTable(const std::vector<Metric>& metrics) {
  std::ostringstream md;
  md << "| | |";
  for (int c = 0; c < kColumns; ++c) md << ' ' << columnName(c) << " |";
  md << "\n|---|---|";
  for (int c = 0; c < kColumns; ++c) md << "---|";
  md << '\n';
  for (const Metric& m : metrics) {
    md << "| **" << m.name << "** | ours |";
    for (int c = 0; c < kColumns; ++c) {
      const Cell& cell = m.ours[std::size_t(c)];
      std::string text;
      if (cell.source == Source::Pending) text = cell.note.empty() ? "pending" : cell.note;
      else {
        text = formatValue(cell.value, m.unit);
        if (cell.source == Source::Extrapolated) text += "*";
        if (cell.source == Source::Computed) text += "†";
        const std::string r = formatRatio(cell.value, m.ours[kNormal].value);
        if (!r.empty() && c != kNormal) text += " (" + r + ")";
      }
      md << ' ' << text << " |";
    }
    md << "\n| | paper |";
    for (int c = 0; c < kColumns; ++c) {
      const PaperCell& p = m.paper[std::size_t(c)];
      std::string text = p.text.empty() ? formatValue(p.value, m.unit) + (p.star ? "*" : "") : p.text;
      const std::string r = formatRatio(p.value, m.paper[kNormal].value);
      if (!r.empty() && c != kNormal) text += " (" + r + ")";
      md << ' ' << text << " |";
    }
    md << '\n';
  }
  return md.str();
}

std::string csvTable(const std::vector<Metric>& metrics) {
  std::ostringstream csv;
  csv << "metric,unit,figure,column,value,ratio_to_normal,how,note\n";
  const char* units[] = {"bytes", "seconds", "count"};
  auto number = [](double v) { return std::isnan(v) ? std::string() : printf1("%.6g", v); };
  auto quoted = [](const std::string& s) {
    std::string out = "\"";
    for (char ch : s) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return out + "\"";
  };
  for (const Metric& m : metrics) {
    for (int c = 0; c < kColumns; ++c) {
      const Cell& o = m.ours[std::size_t(c)];
      const double on = m.ours[kNormal].value;
      csv << m.key << ',' << units[int(m.unit)] << ",ours," << columnKey(c) << ',' << number(o.value) << ','
          << (std::isnan(o.value) || std::isnan(on) || on == 0 ? std::string() : number(o.value / on)) << ','
          << sourceName(o.source) << ',' << quoted(o.note) << '\n';
    }
    for (int c = 0; c < kColumns; ++c) {
      const PaperCell& p = m.paper[std::size_t(c)];
      const double pn = m.paper[kNormal].value;
      csv << m.key << ',' << units[int(m.unit)] << ",paper," << columnKey(c) << ',' << number(p.value) << ','
          << (std::isnan(p.value) || std::isnan(pn) || pn == 0 ? std::string() : number(p.value / pn)) << ','
          << (std::isnan(p.value) ? "none" : p.star ? "extrapolated" : "measured") << ',' << quoted(p.text) << '\n';
    }
  }
  return csv.str();
}

}  // namespace thx::bench::table1
