#version 330 core
// The textured plane: normal mapping, relief mapping (MODE_RELIEF) or the displaced mesh
// (MODE_MESH). Everything happens in the plane's frame, which is also the tangent frame.
// Sampling follows textures/sampling.hpp exactly: texel (i, j) = column i, row j from the TOP,
// centres at u = (i + .5)/W, v = 1 - (j + .5)/H; bilinear over the four nearest centres with the
// normal renormalised; wrap or clamp. It filters here with texelFetch, in float, because the
// rasteriser's 8-bit filter weights cannot meet the 1-LSB reference test.
in vec3 v_local;
in vec3 v_normal_local;

layout(location = 0) out vec4 o_colour;
layout(location = 1) out vec4 o_hit;  // u, v, depth (m) of the shaded point, 1

uniform sampler2D u_texels;  // RGBA32F: tangent normal xyz, depth in metres in w
uniform sampler2D u_depths;  // R32F: depth in metres, filtered as the scene samples
uniform ivec2 u_texels_size;
uniform vec2 u_plane_size;   // metres covered by the map once
uniform bool u_wrap;
uniform bool u_bilinear;
uniform bool u_flat_beyond_edge;  // a clamped relief: the plane's normal outside the map
uniform mat4 u_plane_to_clip;
uniform vec3 u_camera_local;
uniform vec3 u_light_local;  // unit, towards the light
uniform vec3 u_albedo;
uniform float u_ambient;
uniform float u_specular;
uniform float u_max_depth;   // metres; the relief search spans [0, u_max_depth]
uniform int u_linear_steps;
uniform int u_binary_steps;
uniform int u_shadow_steps;  // 0 = no self-shadowing

int resolveIndex(int k, int n) {
  // GLSL's % is undefined for negative operands.
  if (u_wrap) return k - n * int(floor(float(k) / float(n)));
  return clamp(k, 0, n - 1);
}

vec4 texel(int i, int j) {
  return texelFetch(u_texels, ivec2(resolveIndex(i, u_texels_size.x), resolveIndex(j, u_texels_size.y)), 0);
}

vec2 uvOfLocal(vec2 xy) { return xy / u_plane_size + 0.5; }

vec2 reduced(vec2 uv) { return u_wrap ? uv - floor(uv) : clamp(uv, -1.0, 2.0); }

// Normal in xyz (not yet renormalised), depth in w.
vec4 sampleMap(vec2 uv) {
  uv = reduced(uv);
  vec2 st = vec2(uv.x * float(u_texels_size.x), (1.0 - uv.y) * float(u_texels_size.y));
  if (!u_bilinear) {
    ivec2 k = ivec2(floor(st));
    return texel(k.x, k.y);
  }
  st -= 0.5;
  vec2 c = floor(st);
  vec2 f = st - c;
  int i = int(c.x), j = int(c.y);
  return mix(mix(texel(i, j), texel(i + 1, j), f.x), mix(texel(i, j + 1), texel(i + 1, j + 1), f.x), f.y);
}

// The search loops' depth: one hardware-filtered fetch of a float depth texture (float filter
// weights in llvmpipe; wrap = GL_REPEAT, clamp = GL_CLAMP_TO_EDGE, the same texel centres).
float depthAt(vec2 xy) {
  vec2 uv = uvOfLocal(xy);
  return textureLod(u_depths, vec2(uv.x, 1.0 - uv.y), 0.0).r;
}

vec3 normalAt(vec2 xy) {
  vec2 uv = uvOfLocal(xy);
  if (u_flat_beyond_edge && (uv.x < 0.0 || uv.x > 1.0 || uv.y < 0.0 || uv.y > 1.0)) return vec3(0.0, 0.0, 1.0);
  return normalize(sampleMap(uv).xyz);
}

vec3 shade(vec3 n, vec3 view_dir, float lit) {
  float diffuse = max(dot(n, u_light_local), 0.0) * lit;
  vec3 h = normalize(u_light_local - view_dir);
  float specular = lit > 0.0 ? u_specular * pow(max(dot(n, h), 0.0), 32.0) : 0.0;
  return u_albedo * (u_ambient + diffuse) + vec3(specular);
}

#ifdef MODE_RELIEF
// First depth along the ray (xy moves by xy_per_depth per metre of depth) at or below the
// surface: a linear search from the plane, then a binary refinement of the last interval.
float intersectRelief(vec2 xy0, vec2 xy_per_depth) {
  float step = u_max_depth / float(u_linear_steps);
  float above = 0.0, below = 0.0;
  bool found = false;
  for (int k = 0; k <= u_linear_steps; ++k) {
    float d = float(k) * step;
    if (d >= depthAt(xy0 + xy_per_depth * d)) {
      below = d;
      found = true;
      break;
    }
    above = d;
  }
  if (!found) return u_max_depth;
  if (below == 0.0) return 0.0;
  for (int k = 0; k < u_binary_steps; ++k) {
    float mid = 0.5 * (above + below);
    if (mid >= depthAt(xy0 + xy_per_depth * mid)) below = mid;
    else above = mid;
  }
  return below;
}

// 1 when nothing of the relief stands above the ray from the hit towards the light, else 0.
float lightReaches(vec3 hit) {
  if (u_shadow_steps <= 0 || hit.z >= 0.0 || u_light_local.z <= 0.0) return 1.0;
  vec2 xy_per_rise = u_light_local.xy / u_light_local.z;
  float depth = -hit.z;
  // The hit lies up to one final search interval below the true surface: without this margin a
  // coarse search shadows its own hit (acne).
  float bias = u_max_depth * (1e-3 + 1.0 / (float(u_linear_steps) * exp2(float(u_binary_steps))));
  for (int k = 1; k <= u_shadow_steps; ++k) {
    float d = depth * (1.0 - float(k) / float(u_shadow_steps + 1));
    if (depthAt(hit.xy + xy_per_rise * (depth - d)) < d - bias) return 0.0;
  }
  return 1.0;
}
#endif

void main() {
  vec3 view_dir = normalize(v_local - u_camera_local);  // per pixel: one vector per vertex is wrong near the eye
#if defined(MODE_RELIEF)
  // Grazing rays: |v.z| is bounded so the offset stays finite.
  float down = max(-view_dir.z, 0.02);
  vec2 xy_per_depth = view_dir.xy / down;
  float depth = intersectRelief(v_local.xy, xy_per_depth);
  vec3 hit = vec3(v_local.xy + xy_per_depth * depth, -depth);
  vec3 n = normalAt(hit.xy);
  o_colour = vec4(shade(n, view_dir, lightReaches(hit)), 1.0);
  vec4 clip = u_plane_to_clip * vec4(hit, 1.0);
  // Objects and the pen tip sit in the grooves: the depth buffer gets the relief, not the plane.
  gl_FragDepth = clamp(0.5 * clip.z / clip.w + 0.5, 0.0, 1.0);
  o_hit = vec4(uvOfLocal(hit.xy), depth, 1.0);
#elif defined(MODE_MESH)
  o_colour = vec4(shade(normalize(v_normal_local), view_dir, 1.0), 1.0);
  o_hit = vec4(uvOfLocal(v_local.xy), -v_local.z, 1.0);
#else
  o_colour = vec4(shade(normalAt(v_local.xy), view_dir, 1.0), 1.0);
  o_hit = vec4(uvOfLocal(v_local.xy), 0.0, 1.0);
#endif
}
