#include "clients/visual/shader_program.hpp"

#include <regex>
#include <sstream>
#include <vector>

#include "clients/visual/gl_error.hpp"

namespace thx::visual {
namespace {

std::string infoLog(GLuint object, bool is_program) {
  GLint length = 0;
  if (is_program) glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
  else glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> text(std::size_t(length > 0 ? length : 1), '\0');
  if (is_program) glGetProgramInfoLog(object, GLsizei(text.size()), nullptr, text.data());
  else glGetShaderInfoLog(object, GLsizei(text.size()), nullptr, text.data());
  return text.data();
}

GLuint compile(GLenum stage, const ShaderSource& source) {
  const GLuint shader = glCreateShader(stage);
  const char* text = source.text.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = infoLog(shader, false);
    glDeleteShader(shader);
    throw GlError("shader " + source.name + " does not compile:\n" + namedInfoLog(source.name, log));
  }
  return shader;
}

}  // namespace

std::string namedInfoLog(const std::string& name, const std::string& log) {
  static const std::regex mesa(R"(^\s*\d+:(\d+)\(\d+\):\s*)");
  static const std::regex nvidia(R"(^\s*\d+\((\d+)\)\s*:\s*)");
  std::istringstream in(log);
  std::string line, out;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::smatch m;
    if (std::regex_search(line, m, mesa) || std::regex_search(line, m, nvidia))
      line = name + ":" + m[1].str() + ": " + m.suffix().str();
    else
      line = name + ": " + line;
    out += "  " + line + "\n";
  }
  return out;
}

ShaderProgram::ShaderProgram(const ShaderSource& vertex, const ShaderSource& fragment) {
  const GLuint vs = compile(GL_VERTEX_SHADER, vertex);
  GLuint fs = 0;
  try {
    fs = compile(GL_FRAGMENT_SHADER, fragment);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  program_ = glCreateProgram();
  glAttachShader(program_, vs);
  glAttachShader(program_, fs);
  glLinkProgram(program_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = GL_FALSE;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = infoLog(program_, true);
    glDeleteProgram(program_);
    throw GlError("program " + vertex.name + " + " + fragment.name + " does not link:\n" +
                  namedInfoLog(vertex.name + "+" + fragment.name, log));
  }
}

ShaderProgram::~ShaderProgram() { glDeleteProgram(program_); }

}  // namespace thx::visual
