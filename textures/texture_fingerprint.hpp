#pragma once
// A stable 64-bit fingerprint of a textured surface: everything a sense reads from it, so two
// programs (hapticd and a client, perhaps on two hosts) can tell whether they feel and show the
// same surface. hello_t.texture_fingerprint carries it (docs/scenes.md#texture-fingerprint).
//
// FNV-1a 64 (offset basis 0xcbf29ce484222325, prime 0x100000001b3) over this byte stream, every
// integer written little-endian whatever the host:
//   1. the ASCII tag "thx.texture.v1" (16 bytes, NUL-padded): a new definition gets a new tag;
//   2. width, height (int32); relief read as geometry (1 byte: 0/1); filter (1 byte: 0 nearest,
//      1 bilinear); address (1 byte: 0 wrap, 1 clamp);
//   3. as int64 = llround(value * 1e12): size_m x, y (so in picometres); plane_to_world's
//      rotation, row by row (9 entries, units of 1e-12); its translation x, y, z (picometres);
//      the maximum depth (picometres; 0 unless relief is read);
//   4. every texel, row j = 0 (top) to the bottom, column i = 0 to the right: the stored normal's
//      snorm16 x and y codes (int16), then, when relief is read, the 16-bit depth code (uint16).
// So the fingerprint covers the texels exactly as sampled (after any load-time processing:
// green convention, max_depth override, smoothing), the size, the representation as read, the
// sampling, and where the plane lies. It ignores metadata no sense reads (kind, extent, params).
// Geometry is quantised to 1e-12 so that a last-bit difference of a computed rotation (libm
// cos/sin on another host) does not change it. Integers make the rest host-independent; texels
// that a generator computes are the same on hosts whose libm and floating-point contraction agree.
#include <cstdint>
#include <string>

#include "textures/textured_surface.hpp"

namespace thx::tex {

std::uint64_t textureFingerprint(const TexturedSurface& surface);

// "0x" and 16 lower-case hex digits.
std::string formatFingerprint(std::uint64_t fingerprint);

}  // namespace thx::tex
