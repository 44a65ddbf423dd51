#include "clients/physics/crease_contact.hpp"

#include "textures/sampling.hpp"

namespace thx::phys {

void faceNormalsOnCreases(const tex::TexturedSurface& surface, const Underside& box, ChosenReliefContacts& chosen) {
  const tex::TextureMap& map = surface.map();
  const tex::Address address = surface.sampling().address;
  const Eigen::Vector2d texel = surface.mapping().texelSize(map);
  auto heightAt = [&](long long i, long long j) {
    return -double(map.depth(tex::resolveIndex(i, map.width(), address), tex::resolveIndex(j, map.height(), address)));
  };
  for (std::size_t k = 0; k < chosen.count; ++k) {
    ReliefCandidate& c = chosen.contacts[k];
    // The relief first (five texels): most contacts are on no crease, and the box's faces are
    // then not asked.
    const double twice_top = 2.0 * heightAt(c.i, c.j);
    const bool crease = heightAt(c.i - 1, c.j) + heightAt(c.i + 1, c.j) - twice_top < -kCreaseSlopeJump * texel.x() ||
                        heightAt(c.i, c.j - 1) + heightAt(c.i, c.j + 1) - twice_top < -kCreaseSlopeJump * texel.y();
    if (!crease) continue;
    const int face = boxFaceUnder(box, c.p_surface.x(), c.p_surface.y());
    if (face < 0) continue;
    bool one_face = true;
    for (int dj = -1; dj <= 1 && one_face; ++dj)
      for (int di = -1; di <= 1 && one_face; ++di) {
        // Texel rows run down in y as j grows.
        const int f = boxFaceUnder(box, c.p_surface.x() + di * texel.x(), c.p_surface.y() - dj * texel.y());
        one_face = f == face || f < 0;
      }
    if (one_face) c.n_local = boxFaceNormalUp(box, face);
  }
}

}  // namespace thx::phys
