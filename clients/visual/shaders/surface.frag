#version 330 core
#extension GL_ARB_texture_gather : enable
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

#ifdef SEARCH_MAXMIP
// The accelerated search (--search maxmip): the ray walks the max-mipmap (max_mipmap.hpp) in
// cell coordinates m, skipping every box whose highest point the ray passes above, descending
// into the others, and meets the surface exactly in a level-0 cell (the bilinear patch from its
// four corners: a quadratic along the ray, as the CPU reference; nearest: a flat-topped texel).
// It never steps over a wall, however thin. Depths here are fractions of u_max_depth (h in
// [0, 1]). One fetch per step: level 0 holds the corners, the levels above the bound.
uniform sampler2D u_maxmip;      // RGBA32F (max_mipmap.hpp)
uniform int u_maxmip_top;        // the coarsest level
uniform ivec2 u_maxmip_cells;    // real level-0 cells
uniform float u_grid_shift;      // texel coordinates - u_grid_shift = m
uniform bool u_maxmip_pow2;      // both sides of level 0 are powers of two
const int kMaxMipIterations = 400;

vec2 gridOfLocal(vec2 xy) {
  vec2 uv = uvOfLocal(xy);
  return vec2(uv.x * float(u_texels_size.x), (1.0 - uv.y) * float(u_texels_size.y)) - u_grid_shift;
}

// Grid cells per metre of plane-local displacement (the grid's rows run down the image).
vec2 gridPerLocal() { return vec2(u_texels_size) / u_plane_size * vec2(1.0, -1.0); }

vec4 boxDepths(ivec2 k, int level) {
  ivec2 n;
  if (u_wrap) {
    n = u_maxmip_cells >> level;
    // Powers of two (the shipped maps): a mask; else the floor division.
    k = u_maxmip_pow2 ? (k & (n - 1)) : k - n * ivec2(floor(vec2(k) / vec2(n)));
  } else {
    n = (u_maxmip_cells + (1 << level) - 1) >> level;
    k = clamp(k, ivec2(0), n - 1);
  }
  return texelFetch(u_maxmip, k, level) / u_max_depth;
}

// First s in [0, s_end] at which the ray's depth h_in + slope * s is at or below the patch with
// corner depths z (00, 10, 01, 11), the ray entering at a (cell-local) and moving by b per unit
// s; -1 if it stays above. Flat-topped texels have four equal corners.
float cellHit(vec4 z, vec2 a, vec2 b, float h_in, float slope, float s_end) {
  float A = z.y - z.x, B = z.z - z.x, C = z.x - z.y - z.z + z.w;
  // f(s) = ray depth - surface depth = c0 + c1 s + c2 s^2; the hit is the first s with f >= 0.
  float c0 = h_in - (z.x + A * a.x + B * a.y + C * a.x * a.y);
  float c1 = slope - (A * b.x + B * b.y + C * (a.x * b.y + a.y * b.x));
  float c2 = -C * b.x * b.y;
  float best = s_end + 1.0;
  float disc = c1 * c1 - 4.0 * c2 * c0;
  if (abs(c2) * s_end <= 1e-6 * abs(c1)) {
    float r = -c0 / c1;
    if (r >= 0.0) best = r;
  } else if (disc >= 0.0) {
    float q = -0.5 * (c1 + (c1 >= 0.0 ? sqrt(disc) : -sqrt(disc)));
    float r1 = q / c2, r2 = c0 / q;
    best = min(r1 >= 0.0 ? r1 : best, r2 >= 0.0 ? r2 : best);
  }
  if (c0 >= 0.0) best = 0.0;
  if (best <= s_end) return best;
  return c0 + s_end * (c1 + s_end * c2) >= 0.0 ? s_end : -1.0;  // rounding at a tangent root
}

// The ray m(s) = m0 + dm s, depth h(s) = h0 + slope s, for s in [s_begin, s_end]: the first s at
// which it is at or below the surface, -1 if none (or, after kMaxMipIterations, where it got).
float walkMaxMip(vec2 m0, vec2 dm, float h0, float slope, float s_begin, float s_end) {
  // A zero component would divide by zero at the box walls; this one never reaches a wall.
  dm = mix(dm, vec2(1e-12), equal(dm, vec2(0.0)));
  vec2 nudge = sign(dm) * 2e-3;  // the box after a wall the ray sits on (cells, above float noise)
  vec2 upper = step(0.0, dm);
  vec2 inv_dm = 1.0 / dm;
  // Boxes wider than the ray's whole footprint skip nothing more than the one that holds it; and
  // starting at the finest level costs nothing on a plateau (the bricks' tops: a hit at once).
  float footprint = max(abs(dm.x), abs(dm.y)) * (s_end - s_begin);
  int top_level = min(u_maxmip_top, int(ceil(log2(footprint + 1.0))) + 1);
  int level = 0;
  float s = s_begin;
  for (int it = 0; it < kMaxMipIterations; ++it) {
    float size = float(1 << level);
    ivec2 k = ivec2(floor((m0 + dm * s + nudge) * (1.0 / size)));
    vec2 leave = ((vec2(k) + upper) * size - m0) * inv_dm;
    float s_exit = min(min(leave.x, leave.y), s_end);
    vec4 z = boxDepths(k, level);
    float top = min(min(z.x, z.y), min(z.z, z.w));
    // The ray's deepest point over this box's column: where it leaves (down) or enters (up).
    float deepest = h0 + slope * (slope > 0.0 ? s_exit : s);
    if (deepest >= top) {
      // Down, nothing above the box's highest point can be hit.
      if (slope > 0.0) s = max(s, top - h0);  // slope is +1 or -1
      if (level > 0) {
        --level;
        continue;
      }
      float hit = cellHit(z, m0 + dm * s - vec2(k), dm, h0 + slope * s, slope, s_exit - s);
      if (hit >= 0.0) return s + hit;
    }
    if (s_exit >= s_end) return -1.0;
    s = s_exit;
    // Up a level only when the ray leaves the parent box too: inside it, the parent's bound said
    // "descend" and still would.
    ivec2 wall = k + ivec2(upper);
    bvec2 crossed = lessThanEqual(leave, vec2(s_exit));
    if ((crossed.x && (wall.x & 1) == 0) || (crossed.y && (wall.y & 1) == 0)) level = min(level + 1, top_level);
  }
  return slope > 0.0 ? s : -1.0;
}

float intersectMaxMip(vec2 xy0, vec2 xy_per_depth) {
  if (u_max_depth <= 0.0) return 0.0;
  vec2 dm = xy_per_depth * u_max_depth * gridPerLocal();
  float h = walkMaxMip(gridOfLocal(xy0), dm, 0.0, 1.0, 0.0, 1.0);
  return (h < 0.0 ? 1.0 : h) * u_max_depth;
}

float lightReachesMaxMip(vec3 hit) {
  if (u_shadow_steps <= 0 || hit.z >= 0.0 || u_light_local.z <= 0.0) return 1.0;
  vec2 dm = u_light_local.xy / u_light_local.z * u_max_depth * gridPerLocal();
  float h0 = -hit.z / u_max_depth;
  // From just above the hit until the ray rises out of the relief. 1e-3 of the maximum depth
  // along the light (the CPU reference, in double: 1e-4): the float hit can land that far below
  // the surface, and its own cell then shadows it (isolated dark pixels on the pebbles).
  float s0 = 1e-3 * u_light_local.z;
  if (s0 >= h0) return 1.0;
  return walkMaxMip(gridOfLocal(hit.xy), dm, h0, -1.0, s0, h0) >= 0.0 ? 0.0 : 1.0;
}
#endif
#endif

void main() {
  vec3 view_dir = normalize(v_local - u_camera_local);  // per pixel: one vector per vertex is wrong near the eye
#if defined(MODE_RELIEF)
  // Grazing rays: |v.z| is bounded so the offset stays finite.
  float down = max(-view_dir.z, 0.02);
  vec2 xy_per_depth = view_dir.xy / down;
#ifdef SEARCH_MAXMIP
  float depth = intersectMaxMip(v_local.xy, xy_per_depth);
  vec3 hit = vec3(v_local.xy + xy_per_depth * depth, -depth);
  vec3 n = normalAt(hit.xy);
  // A point facing away from the light is in its own shadow: no walk towards the light.
  float lit = dot(n, u_light_local) > 0.0 ? lightReachesMaxMip(hit) : 0.0;
#else
  float depth = intersectRelief(v_local.xy, xy_per_depth);
  vec3 hit = vec3(v_local.xy + xy_per_depth * depth, -depth);
  float lit = lightReaches(hit);
  vec3 n = normalAt(hit.xy);
#endif
  o_colour = vec4(shade(n, view_dir, lit), 1.0);
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
