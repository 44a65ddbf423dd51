#include "clients/visual/shader_sources.hpp"

#include <map>

#include "clients/visual/gl_error.hpp"

namespace thx::visual {

// Generated from shaders/*.{vert,frag} (see CMakeLists.txt).
const std::map<std::string, std::string>& embeddedShaderTexts();

ShaderSource embeddedShader(const std::string& file_name) {
  const auto& texts = embeddedShaderTexts();
  const auto it = texts.find(file_name);
  if (it == texts.end()) throw GlError("no embedded shader named " + file_name);
  return {file_name, it->second};
}

ShaderSource withDefines(ShaderSource source, const std::vector<std::string>& defines) {
  const std::size_t eol = source.text.find('\n');
  if (eol == std::string::npos || defines.empty()) return source;
  std::string inserted;
  for (const std::string& d : defines) inserted += "#define " + d + " 1\n";
  inserted += "#line 2\n";
  source.text.insert(eol + 1, inserted);
  return source;
}

}  // namespace thx::visual
