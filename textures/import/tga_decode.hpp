#pragma once
// TGA through stb_image (OpenCV has no TGA codec). stb reads past the end of a short file as
// zeros, so the header and the pixel data's length are checked first.
#include <string>
#include <vector>

#include "textures/png_io.hpp"

namespace thx::tex {

// True when the 18-byte header is one stb can read (image types 1, 2, 3, 9, 10, 11).
bool looksLikeTga(const std::vector<unsigned char>& bytes);
RawImage decodeTga(const std::string& path, const std::vector<unsigned char>& bytes);

}  // namespace thx::tex
