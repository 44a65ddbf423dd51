#version 330 core
// A textured triangle mesh (issue 28): the plane's normal mapping and relief mapping
// (surface.frag) carried onto the mesh by its tangent frames, so that the picture shows what the
// haptic renderer (server/textured_mesh_renderer.hpp) turns into force.
//
// The frame is interpolated per pixel as thx::mesh::frameAt(FrameMode::Interpolated) does it:
// the normal renormalised, the tangent made orthogonal to it (Gram-Schmidt) and renormalised, the
// bitangent = handedness * N x T. The texture's tangent-space normal n becomes
// n.x T + n.y B + n.z N. Relief (MODE_RELIEF) marches the view ray below the tangent plane at the
// pixel's point, in "tangent metres" (x along T, y along B: uv scaled by the face's metres per uv
// unit; depth along -N), with the plane's linear then binary search and its shadow ray.
// The face's metres per uv (thx::mesh::metresPerUv) come from the screen derivatives of the
// position and the uv: both are affine in the same barycentric coordinates, so dP/duv is exact
// whatever the perspective. The map's normals were made for u_tile; where the face lays the
// texture at another scale their slopes are turned by u_tile / scale, as the haptic chart turns
// them (TexturedSurface::setNormalsMadeFor), so what is seen is what is felt.
// Sampling follows textures/sampling.hpp (surface.frag explains it); the texture always wraps.
in vec3 v_position;  // mesh frame, metres
in vec3 v_normal;
in vec4 v_tangent;
in vec2 v_uv;

layout(location = 0) out vec4 o_colour;
layout(location = 1) out vec4 o_hit;  // u, v (tiles, wrapped), depth (m) of the shaded point, 1

uniform sampler2D u_texels;  // RGBA32F: tangent normal xyz, depth in metres in w
uniform sampler2D u_depths;  // R32F: depth in metres, GL_REPEAT, filtered as the scene samples
uniform ivec2 u_texels_size;
uniform vec2 u_tile;         // metres per uv unit the map's normals were made for
uniform bool u_bilinear;
uniform mat4 u_mesh_to_clip;
uniform vec3 u_camera_mesh;
uniform vec3 u_light_mesh;   // unit, towards the light, mesh frame
uniform vec3 u_albedo;
uniform float u_ambient;
uniform float u_specular;
uniform float u_max_depth;   // metres; the relief search spans [0, u_max_depth]
uniform int u_linear_steps;
uniform int u_binary_steps;
uniform int u_shadow_steps;  // 0 = no self-shadowing

// The pixel's uv, reduced to [0, 1): tangent-plane positions xy are measured from it.
vec2 g_uv0;
// The face's metres per uv unit along T and B, and the slope factor u_tile / g_scale.
vec2 g_scale;
vec2 g_slope;
// The light in the pixel's tangent frame (x along T, y along B, z along N).
vec3 g_light_t;

int wrapIndex(int k, int n) {
  // GLSL's % is undefined for negative operands.
  return k - n * int(floor(float(k) / float(n)));
}

vec4 texel(int i, int j) { return texelFetch(u_texels, ivec2(wrapIndex(i, u_texels_size.x), wrapIndex(j, u_texels_size.y)), 0); }

// Normal in xyz (not yet renormalised), depth in w.
vec4 sampleMap(vec2 uv) {
  uv -= floor(uv);
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

vec2 uvOfTangent(vec2 xy) { return g_uv0 + xy / g_scale; }

// The map's normal (not unit) with its slopes as laid on this face.
vec3 laidNormal(vec4 s) { return vec3(s.xy * g_slope, s.z); }

// The search loops' depth: one hardware-filtered fetch (surface.frag's depthAt).
float depthAt(vec2 xy) {
  vec2 uv = uvOfTangent(xy);
  return textureLod(u_depths, vec2(uv.x, 1.0 - uv.y), 0.0).r;
}

vec3 shade(vec3 n, vec3 view_dir, float lit) {
  float diffuse = max(dot(n, u_light_mesh), 0.0) * lit;
  vec3 h = normalize(u_light_mesh - view_dir);
  float specular = lit > 0.0 ? u_specular * pow(max(dot(n, h), 0.0), 32.0) : 0.0;
  return u_albedo * (u_ambient + diffuse) + vec3(specular);
}

#ifdef MODE_RELIEF
// surface.frag's intersectRelief and lightReaches, in the tangent plane.
float intersectRelief(vec2 xy_per_depth) {
  float step = u_max_depth / float(u_linear_steps);
  float above = 0.0, below = 0.0;
  bool found = false;
  for (int k = 0; k <= u_linear_steps; ++k) {
    float d = float(k) * step;
    if (d >= depthAt(xy_per_depth * d)) {
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
    if (mid >= depthAt(xy_per_depth * mid)) below = mid;
    else above = mid;
  }
  return below;
}

float lightReaches(vec3 hit) {
  if (u_shadow_steps <= 0 || hit.z >= 0.0 || g_light_t.z <= 0.0) return 1.0;
  vec2 xy_per_rise = g_light_t.xy / g_light_t.z;
  float depth = -hit.z;
  // The plane's margin: the hit lies up to one final search interval below the true surface.
  float bias = u_max_depth * (1e-3 + 1.0 / (float(u_linear_steps) * exp2(float(u_binary_steps))));
  for (int k = 1; k <= u_shadow_steps; ++k) {
    float d = depth * (1.0 - float(k) / float(u_shadow_steps + 1));
    if (depthAt(hit.xy + xy_per_rise * (depth - d)) < d - bias) return 0.0;
  }
  return 1.0;
}
#endif

void main() {
  vec3 N = normalize(v_normal);
  vec3 T = normalize(v_tangent.xyz - N * dot(N, v_tangent.xyz));
  // The corners of a triangle share one handedness (buildVertexFrames splits a mirrored chart).
  vec3 B = (v_tangent.w < 0.0 ? -1.0 : 1.0) * cross(N, T);
  g_uv0 = v_uv - floor(v_uv);
  {
    vec3 dpx = dFdx(v_position), dpy = dFdy(v_position);
    vec2 dux = dFdx(v_uv), duy = dFdy(v_uv);
    float det = dux.x * duy.y - duy.x * dux.y;
    // d position / d u and / d v projected on the pixel's frame, (dpx duy.y - dpy dux.y) / det . T
    // and (dpy dux.x - dpx duy.x) / det . B; a mapping that folds against the frame has no
    // meaningful scale: 1 m per uv unit there (thx::mesh::metresPerUv).
    g_scale = det != 0.0 ? vec2(dot(dpx, T) * duy.y - dot(dpy, T) * dux.y, dot(dpy, B) * dux.x - dot(dpx, B) * duy.x) / det
                         : vec2(1.0);
    if (!(g_scale.x > 0.0)) g_scale.x = 1.0;
    if (!(g_scale.y > 0.0)) g_scale.y = 1.0;
    g_slope = u_tile / g_scale;
  }
  vec3 view_dir = normalize(v_position - u_camera_mesh);
#ifdef MODE_RELIEF
  g_light_t = vec3(dot(u_light_mesh, T), dot(u_light_mesh, B), dot(u_light_mesh, N));
  vec3 view_t = vec3(dot(view_dir, T), dot(view_dir, B), dot(view_dir, N));
  // Grazing rays, and rays from behind the interpolated tangent plane near a silhouette: |v.z| is
  // bounded so the offset stays finite.
  float down = max(-view_t.z, 0.02);
  vec2 xy_per_depth = view_t.xy / down;
  float depth = intersectRelief(xy_per_depth);
  vec3 hit = vec3(xy_per_depth * depth, -depth);
  float lit = lightReaches(hit);
  vec3 n_t = normalize(laidNormal(sampleMap(uvOfTangent(hit.xy))));
  vec3 n = T * n_t.x + B * n_t.y + N * n_t.z;  // unit: T, B, N are orthonormal
  o_colour = vec4(shade(n, view_dir, lit), 1.0);
  // The depth buffer gets the relief, not the triangles (as the plane's relief mode).
  vec4 clip = u_mesh_to_clip * vec4(v_position + T * hit.x + B * hit.y + N * hit.z, 1.0);
  gl_FragDepth = clamp(0.5 * clip.z / clip.w + 0.5, 0.0, 1.0);
  o_hit = vec4(uvOfTangent(hit.xy), depth, 1.0);
#else
  vec3 n_t = normalize(laidNormal(sampleMap(g_uv0)));
  vec3 n = T * n_t.x + B * n_t.y + N * n_t.z;  // unit: T, B, N are orthonormal
  o_colour = vec4(shade(n, view_dir, 1.0), 1.0);
  o_hit = vec4(g_uv0, 0.0, 1.0);
#endif
}
