#pragma once
// GlError: the visual client could not get or use OpenGL (no EGL display, no driver, a shader that
// does not compile, an incomplete framebuffer). The message names the cause and, where a package
// is missing, the Debian package to install. It is a thx::Error so mains print it and exit 1.
#include <string>

#include "base/error.hpp"

namespace thx::visual {

class GlError : public Error {
 public:
  explicit GlError(const std::string& what) : Error(Kind::Io, what) {}
};

// Throws GlError naming `where` when glGetError() reports anything.
void checkGl(const char* where);

}  // namespace thx::visual
