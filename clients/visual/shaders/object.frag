#version 330 core
// Blinn-Phong under the scene's one directional light; a letter block's glyph in dark ink on its
// ±z faces (5 x 7 cells of 0.1 x 0.1 of the face, centred; mirrored on -z so it reads from there).
in vec3 v_world;
in vec3 v_normal_world;
in vec3 v_unit;

layout(location = 0) out vec4 o_colour;
layout(location = 1) out vec4 o_hit;

uniform vec3 u_camera_world;
uniform vec3 u_light_world;  // unit, towards the light
uniform vec3 u_albedo;
uniform float u_ambient;
uniform float u_specular;
uniform bool u_has_glyph;
uniform int u_glyph[7];  // rows top to bottom, bit 4 = the leftmost column

bool inked(vec3 p) {
  if (!u_has_glyph || abs(p.z) < 0.499) return false;
  float x = p.z > 0.0 ? p.x : -p.x;
  int column = int(floor((x + 0.25) / 0.1));
  int row = int(floor((0.35 - p.y) / 0.1));
  if (column < 0 || column > 4 || row < 0 || row > 6) return false;
  return ((u_glyph[row] >> (4 - column)) & 1) != 0;
}

void main() {
  vec3 n = normalize(v_normal_world);
  vec3 view_dir = normalize(v_world - u_camera_world);
  if (dot(n, view_dir) > 0.0) n = -n;
  float diffuse = max(dot(n, u_light_world), 0.0);
  vec3 h = normalize(u_light_world - view_dir);
  float specular = u_specular * pow(max(dot(n, h), 0.0), 32.0);
  vec3 albedo = inked(v_unit) ? vec3(0.08, 0.06, 0.05) : u_albedo;
  o_colour = vec4(albedo * (u_ambient + diffuse) + vec3(specular), 1.0);
  o_hit = vec4(-1.0);  // not the surface
}
