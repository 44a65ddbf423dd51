#include "clients/study/rating_prompt.hpp"

#include <charconv>
#include <istream>
#include <ostream>

namespace thx::study {

std::optional<int> askRating(std::istream& in, std::ostream& out, const std::string& question, int min, int max) {
  for (;;) {
    out << question << " [" << min << "-" << max << "]: " << std::flush;
    std::string line;
    if (!std::getline(in, line)) return std::nullopt;
    const auto b = line.find_first_not_of(" \t\r");
    const auto e = line.find_last_not_of(" \t\r");
    const std::string t = b == std::string::npos ? "" : line.substr(b, e - b + 1);
    int v = 0;
    const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (t.empty() || ec != std::errc() || p != t.data() + t.size())
      out << "  expected a whole number from " << min << " to " << max << ", got '" << t << "'\n";
    else if (v < min || v > max)
      out << "  " << v << " is outside the scale; expected " << min << " to " << max << "\n";
    else
      return v;
  }
}

}  // namespace thx::study
