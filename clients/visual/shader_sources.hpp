#pragma once
// The GLSL files in shaders/, embedded at configure time (CMakeLists.txt here) under their file
// names, so compile errors read "surface.frag:42: ...". withDefines() adds #defines after the
// #version line and a #line directive so the reported line numbers stay the file's.
#include <string>
#include <vector>

#include "clients/visual/shader_program.hpp"

namespace thx::visual {

ShaderSource embeddedShader(const std::string& file_name);  // throws GlError for an unknown name
ShaderSource withDefines(ShaderSource source, const std::vector<std::string>& defines);

}  // namespace thx::visual
