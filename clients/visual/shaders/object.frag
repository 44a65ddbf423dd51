#version 330 core
// Blinn-Phong under the scene's one directional light.
in vec3 v_world;
in vec3 v_normal_world;

layout(location = 0) out vec4 o_colour;
layout(location = 1) out vec4 o_hit;

uniform vec3 u_camera_world;
uniform vec3 u_light_world;  // unit, towards the light
uniform vec3 u_albedo;
uniform float u_ambient;
uniform float u_specular;

void main() {
  vec3 n = normalize(v_normal_world);
  vec3 view_dir = normalize(v_world - u_camera_world);
  if (dot(n, view_dir) > 0.0) n = -n;
  float diffuse = max(dot(n, u_light_world), 0.0);
  vec3 h = normalize(u_light_world - view_dir);
  float specular = u_specular * pow(max(dot(n, h), 0.0), 32.0);
  o_colour = vec4(u_albedo * (u_ambient + diffuse) + vec3(specular), 1.0);
  o_hit = vec4(-1.0);  // not the surface
}
