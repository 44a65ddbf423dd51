#version 330 core
// A textured triangle mesh in its own frame (metres), with its vertex tangent frames
// (meshes/textured_mesh.hpp): the fragment shader interpolates them per pixel.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_tangent;  // xyz along +u; w = handedness (+-1)
layout(location = 3) in vec2 a_uv;       // tiles

uniform mat4 u_mesh_to_clip;

out vec3 v_position;
out vec3 v_normal;
out vec4 v_tangent;
out vec2 v_uv;

void main() {
  v_position = a_position;
  v_normal = a_normal;
  v_tangent = a_tangent;
  v_uv = a_uv;
  gl_Position = u_mesh_to_clip * vec4(a_position, 1.0);
}
