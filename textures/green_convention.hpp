#pragma once
// Which green-channel convention a normal map most likely uses, from the normals alone.
//
// A normal map made from a height field h stores n ∝ (−h_x, −h_y, 1), so p = −n_x/n_z and
// q = −n_y/n_z are the two slopes of one surface and their cross derivatives agree:
// ∂q/∂x = ∂p/∂y = h_xy (the field is integrable, its curl is zero). Read with the wrong green
// convention, q changes sign and ∂q/∂x = −h_xy: the curl is −2·h_xy instead of 0. The test is the
// sign of C = Σ ∂q/∂x · ∂p/∂y over the interior texels (central differences), reported as
// score = C / Σ |∂q/∂x · ∂p/∂y|: the magnitude-weighted share of texels where the two cross
// derivatives agree in sign, minus the share where they disagree. It is +1 for an exact map read
// as written and −1 for one read flipped. Noise (JPEG, 8-bit rounding) and creases, where the
// differences are large but unrelated, pull it towards 0 without changing its sign; a map with no
// mixed slopes (straight grooves, a uniform tilt, a flat map) scores near 0: then the normals
// cannot tell, and neither could a person looking at them.
#include <optional>

#include "textures/texture_io.hpp"
#include "textures/texture_map.hpp"

namespace thx::tex {

struct GreenGuess {
  std::optional<GreenConvention> convention;  // nullopt: the normals cannot tell
  double score = 0.0;                         // in [−1, 1], > 0 = consistent with how it was read
};

// `read_as` is the convention the map was decoded with; the guess is about the file.
GreenGuess guessGreenConvention(const TextureMap& map, GreenConvention read_as);

// Below this |score| the guess is "cannot tell".
inline constexpr double kGreenGuessMinScore = 0.2;

}  // namespace thx::tex
