#include "scenes/closest_match.hpp"

#include <algorithm>
#include <cctype>

namespace thx::scene {

namespace {
char lower(char c) { return char(std::tolower(static_cast<unsigned char>(c))); }
}  // namespace

std::size_t editDistance(std::string_view a, std::string_view b) {
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::size_t> prev2(m + 1), prev(m + 1), cur(m + 1);
  for (std::size_t j = 0; j <= m; ++j) prev[j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
      if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) && lower(a[i - 2]) == lower(b[j - 1]))
        cur[j] = std::min(cur[j], prev2[j - 2] + 1);
    }
    std::swap(prev2, prev);
    std::swap(prev, cur);
  }
  return prev[m];
}

std::string closestMatch(std::string_view word, const std::vector<std::string>& candidates) {
  // Up to two edits is a typo ("texure", "aluminum", "mortar_widht"); more is usually another
  // word, and then a shared prefix is the better hint ("phantom_desk" -> "phantom_desktop",
  // "mortar_width" -> "mortar", rather than "mortar_depth", three edits away).
  const std::size_t limit = word.size() <= 4 ? 1 : 2;
  std::string best;
  std::size_t best_distance = limit + 1;
  for (const std::string& c : candidates) {
    const std::size_t d = editDistance(word, c);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  if (!best.empty()) return best;
  constexpr std::size_t kMinPrefix = 4;
  std::size_t best_prefix = 0;
  for (const std::string& c : candidates) {
    const std::size_t shorter = std::min(word.size(), c.size());
    if (shorter < kMinPrefix) continue;
    const bool prefix = std::equal(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(shorter), word.begin(),
                                   [](char a, char b) { return lower(a) == lower(b); });
    if (prefix && shorter > best_prefix) {
      best_prefix = shorter;
      best = c;
    }
  }
  return best;
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) {
    if (!s.empty()) s += ", ";
    s += n;
  }
  return s;
}

}  // namespace thx::scene
