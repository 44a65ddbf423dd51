#pragma once
// A relief map's upper envelope merged along one axis (a ripmap of the highest point): level k
// holds, for each run of 2^k texels along i (or j), the least depth among them and that texel's
// normal. Where a mesh's uv squeezes the texture along one axis (a lathe near its pole: 31 texels
// along u for one along v at the bowl's centre), a chart is laid with the level whose texels are
// about as long along that axis as the other's (mesh_relief_chart.cpp), so every texel of the
// squeezed relief has a say in the contact. Read at a stride instead, which texels were read
// depended on where the object stood: a ball's support changed by 9 um in a step in which it
// moved 7 um, and a bump-mapped ball near the bowl's pole never came to rest. The runs are fixed
// in the texture (texel 2^k I to 2^k (I + 1) - 1), so the envelope under a moving object is one
// surface. The upper envelope, not the mean: a groove narrower than a run is one a large object
// bridges, and the mean would lower the run by the groove's share of it.
#include <vector>

#include "textures/texture_map.hpp"

namespace thx::phys {

struct ReliefEnvelopes {
  // along_i[k - 1]: 2^k texels merged along i (width / 2^k wide); along_j likewise by rows. Levels
  // stop where 2^k no longer divides the side, so that a wrapped level keeps the map's period.
  std::vector<tex::TextureMap> along_i, along_j;
};

// Levels up to kMaxEnvelopeLevel (2^6 = 64 texels a run) along each axis of a relief map; none for
// a normal map. Linear in the map's texels (twice them, per axis, at most).
inline constexpr int kMaxEnvelopeLevel = 6;
ReliefEnvelopes buildReliefEnvelopes(const tex::TextureMap& relief);

// The map a chart reads where its texels are `texel_x` by `texel_y` metres: the level merging
// about ty / tx texels along i where tx is at most half ty (the largest 2^k not above it, so
// its texels stay no longer than the other axis's), or along j the other way round; `map` itself
// otherwise.
const tex::TextureMap& envelopeFor(const ReliefEnvelopes& envelopes, const tex::TextureMap& map, double texel_x,
                                   double texel_y);

}  // namespace thx::phys
