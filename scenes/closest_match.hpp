#pragma once
// "Did you mean ...?" for typos in field names, enum values, materials and generator names.
#include <string>
#include <string_view>
#include <vector>

namespace thx::scene {

// Optimal-string-alignment distance (Levenshtein plus adjacent transpositions), case-insensitive,
// so "mortar_widht" is one edit from "mortar_width".
std::size_t editDistance(std::string_view a, std::string_view b);

// The candidate nearest to `word` if it is close enough to be a plausible typo, else "".
std::string closestMatch(std::string_view word, const std::vector<std::string>& candidates);

// "a, b, c"
std::string joinNames(const std::vector<std::string>& names);

}  // namespace thx::scene
