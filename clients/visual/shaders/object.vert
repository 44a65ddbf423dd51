#version 330 core
// Scene objects and the pen: unit meshes placed by a model matrix (world frame, metres).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model;
uniform mat3 u_normal_matrix;
uniform mat4 u_view_projection;

out vec3 v_world;
out vec3 v_normal_world;
out vec3 v_unit;  // the unit mesh's own coordinates (the box: [-0.5, 0.5]^3)

void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_world = world.xyz;
  v_normal_world = u_normal_matrix * a_normal;
  v_unit = a_position;
  gl_Position = u_view_projection * world;
}
