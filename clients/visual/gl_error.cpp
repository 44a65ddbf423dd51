#include "clients/visual/gl_error.hpp"

#include <cstdio>

#include "clients/visual/gl_api.hpp"

namespace thx::visual {

void checkGl(const char* where) {
  const GLenum e = glGetError();
  if (e == GL_NO_ERROR) return;
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", unsigned(e));
  throw GlError(std::string("OpenGL error ") + code + " in " + where);
}

}  // namespace thx::visual
