#include "clients/physics/relief_envelope.hpp"

#include <cmath>

namespace thx::phys {

namespace {

// Merges pairs of texels of `finer` along i (or j): each new texel the higher of the two (the
// lesser depth), with its normal; ties keep the first.
tex::TextureMap mergePairs(const tex::TextureMap& finer, bool along_i) {
  const int w = along_i ? finer.width() / 2 : finer.width(), h = along_i ? finer.height() : finer.height() / 2;
  tex::TextureMap merged(w, h, tex::Representation::Relief, finer.maxDepth());
  merged.meta() = finer.meta();
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const int ai = along_i ? 2 * i : i, aj = along_i ? j : 2 * j;
      const int bi = along_i ? ai + 1 : ai, bj = along_i ? aj : aj + 1;
      const bool first = finer.depthCode(ai, aj) <= finer.depthCode(bi, bj);
      const int si = first ? ai : bi, sj = first ? aj : bj;
      merged.setDepthCode(i, j, finer.depthCode(si, sj));
      merged.setNormal(i, j, finer.normal(si, sj));
    }
  return merged;
}

void buildAlong(const tex::TextureMap& relief, bool along_i, std::vector<tex::TextureMap>& levels) {
  const int side = along_i ? relief.width() : relief.height();
  for (int k = 1; k <= kMaxEnvelopeLevel; ++k) {
    const int runs = side >> k;
    if (runs < tex::kMinTextureSide || (runs << k) != side) break;
    levels.push_back(mergePairs(levels.empty() ? relief : levels.back(), along_i));
  }
}

}  // namespace

ReliefEnvelopes buildReliefEnvelopes(const tex::TextureMap& relief) {
  ReliefEnvelopes e;
  if (!relief.isRelief()) return e;
  buildAlong(relief, true, e.along_i);
  buildAlong(relief, false, e.along_j);
  return e;
}

const tex::TextureMap& envelopeFor(const ReliefEnvelopes& envelopes, const tex::TextureMap& map, double texel_x,
                                   double texel_y) {
  const double tx = std::fabs(texel_x), ty = std::fabs(texel_y);
  const bool squeezed_i = 2.0 * tx <= ty, squeezed_j = 2.0 * ty <= tx;
  if (!squeezed_i && !squeezed_j) return map;
  const std::vector<tex::TextureMap>& levels = squeezed_i ? envelopes.along_i : envelopes.along_j;
  const int k = std::min(int(std::floor(std::log2(squeezed_i ? ty / tx : tx / ty))), int(levels.size()));
  return k >= 1 ? levels[std::size_t(k - 1)] : map;
}

}  // namespace thx::phys
