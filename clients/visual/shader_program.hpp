#pragma once
// A linked GLSL program built from named sources. A compile error names the shader and the line:
//   relief.frag:42: error: 'foo' undeclared   (GL info log, Mesa's "0:42(7):" made readable)
#include <string>

#include "clients/visual/gl_api.hpp"

namespace thx::visual {

struct ShaderSource {
  std::string name;  // "surface.frag": what errors call it
  std::string text;  // GLSL, starting with its #version line
};

class ShaderProgram {
 public:
  // Throws GlError with the info log, each line prefixed by the shader's name and line.
  ShaderProgram(const ShaderSource& vertex, const ShaderSource& fragment);
  ~ShaderProgram();
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  void use() const { glUseProgram(program_); }
  // -1 when the uniform does not exist or was optimised away (setting it is then a no-op in GL).
  GLint uniform(const char* name) const { return glGetUniformLocation(program_, name); }

 private:
  GLuint program_ = 0;
};

// Rewrites Mesa/NVIDIA-style info-log locations ("0:12(5): " or "0(12) : ") as "NAME:12: ".
std::string namedInfoLog(const std::string& name, const std::string& log);

}  // namespace thx::visual
