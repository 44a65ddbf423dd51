#pragma once
// The uniforms the plane's and the textured mesh's surface shaders share: the texture's units
// (texels on unit 0, depths on unit 1, as SurfaceTexture::bind(GL_TEXTURE0, GL_TEXTURE1)) and
// size, albedo, light terms, the relief's depth and its search steps (shaders/surface.frag,
// shaders/mesh_surface.frag read them under the same names). Set with the program in use.
#include "clients/visual/render_settings.hpp"
#include "clients/visual/shader_program.hpp"
#include "textures/texture_map.hpp"

namespace thx::visual {

// use_relief false: a normal map read as relief has no depth, so the search stops on the surface
// at once.
void setShadingUniforms(const ShaderProgram& program, const RenderSettings& settings, const tex::TextureMap& map,
                        bool use_relief);

}  // namespace thx::visual
