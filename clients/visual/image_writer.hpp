#pragma once
// Writes a rendered frame: PNG (libpng at compression level 1, no row filter: default settings
// cost ~0.4 s per 720p frame here) or binary PPM, chosen by the file's extension.
#include <string>

#include "clients/visual/framebuffer.hpp"

namespace thx::visual {

// Throws thx::Error (Io) naming the file and the reason; an extension other than .png/.ppm is a
// UsageError naming the file and what is expected.
// png_level: zlib level 0..9 (9 for pictures kept in git).
void writeImage(const std::string& path, const Rgba8Image& image, int png_level = 1);
// DIR/frame_0042.FORMAT: the numbered frames of --frames, --replay-log and --live.
std::string framePath(const std::string& dir, int index, const std::string& format);

}  // namespace thx::visual
