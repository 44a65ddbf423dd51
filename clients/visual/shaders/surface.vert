#version 330 core
// The textured plane in its own frame (metres; +z = the plane's normal). The flat modes draw one
// quad at z = 0; mesh mode draws the displaced grid with per-vertex normals.
layout(location = 0) in vec3 a_position_local;
layout(location = 1) in vec3 a_normal_local;

uniform mat4 u_plane_to_clip;

out vec3 v_local;
out vec3 v_normal_local;

void main() {
  v_local = a_position_local;
  v_normal_local = a_normal_local;
  gl_Position = u_plane_to_clip * vec4(a_position_local, 1.0);
}
