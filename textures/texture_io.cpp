#include "textures/texture_io.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "textures/png_io.hpp"
#include "textures/texture_error.hpp"

namespace thx::tex {

namespace {

constexpr const char* kKeyKind = "thx.kind";
constexpr const char* kKeyMaxDepth = "thx.max_depth_m";
constexpr const char* kKeyExtent = "thx.extent_m";
constexpr const char* kKeyParams = "thx.params";
constexpr const char* kKeyGreen = "thx.green";

std::string formatDouble(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

// Strict: the whole string must be one finite number.
bool parseDouble(const std::string& s, double& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  while (end && (*end == ' ' || *end == '\t')) ++end;
  return end && *end == '\0' && std::isfinite(out);
}


const char* channelDescription(int channels) {
  switch (channels) {
    case 1: return "1 channel (grayscale)";
    case 2: return "2 channels (grayscale + alpha)";
    case 3: return "3 channels (RGB)";
    default: return "4 channels (RGBA)";
  }
}

double readMaxDepth(const std::string& path, const RawImage& raw, const LoadOptions& options) {
  if (options.max_depth_m) {
    const double d = *options.max_depth_m;
    if (!std::isfinite(d) || d <= 0.0) {
      throw TextureError(path, "maximum depth override", formatDouble(d), "a finite depth > 0 in metres");
    }
    return d;
  }
  const auto it = raw.text.find(kKeyMaxDepth);
  if (it == raw.text.end()) {
    throw TextureError(path, "relief map has no maximum depth", "no '" + std::string(kKeyMaxDepth) + "' text chunk",
                       "the chunk, or an explicit max_depth (scene surface.max_depth, texturetool --max-depth)");
  }
  double d = 0.0;
  if (!parseDouble(it->second, d) || d <= 0.0) {
    throw TextureError(path, "bad '" + std::string(kKeyMaxDepth) + "' text chunk", "'" + it->second + "'",
                       "a finite depth > 0 in metres");
  }
  return d;
}

struct BadTexel {
  int i, j;
  bool degenerate;  // else: points into the surface
};

void repair(TextureMap& map, const std::vector<BadTexel>& bad, const std::vector<std::uint8_t>& is_bad) {
  for (const BadTexel& b : bad) {
    Eigen::Vector3f sum = Eigen::Vector3f::Zero();
    for (int dj = -1; dj <= 1; ++dj) {
      for (int di = -1; di <= 1; ++di) {
        const int i = b.i + di, j = b.j + dj;
        if ((di == 0 && dj == 0) || i < 0 || j < 0 || i >= map.width() || j >= map.height()) continue;
        if (is_bad[std::size_t(j) * std::size_t(map.width()) + std::size_t(i)]) continue;
        sum += map.normal(i, j);
      }
    }
    // The mean of outward unit normals is outward (z > 0) unless empty.
    map.setNormal(b.i, b.j, sum.z() > 1e-6f ? sum : Eigen::Vector3f(0, 0, 1));
  }
}

}  // namespace

const char* toString(GreenConvention g) { return g == GreenConvention::DirectX ? "directx" : "opengl"; }

TextureMap loadTexture(const std::string& path, const LoadOptions& options, LoadReport* report) {
  return decodeTexture(readPng(path), path, options, report);
}

TextureMap decodeTexture(const RawImage& raw, const std::string& path, const LoadOptions& options,
                         LoadReport* report) {
  if (raw.channels != 3 && raw.channels != 4) {
    throw TextureError(path, "wrong channel count", channelDescription(raw.channels),
                       "3 channels (RGB normal map) or 4 (RGBA relief map: alpha = depth)");
  }
  const bool file_is_relief = raw.channels == 4;
  Representation representation = file_is_relief ? Representation::Relief : Representation::Normal;
  if (options.representation) {
    if (*options.representation == Representation::Relief && !file_is_relief) {
      throw TextureError(path, "a relief map was asked for but the file is a normal map", channelDescription(3),
                         "an RGBA PNG whose alpha channel holds depth");
    }
    representation = *options.representation;
  }
  const double max_depth = representation == Representation::Relief ? readMaxDepth(path, raw, options) : 0.0;

  TextureMap map(raw.width, raw.height, representation, max_depth);
  LoadReport local;
  LoadReport& rep = report ? *report : local;
  rep = LoadReport{};
  rep.bit_depth = raw.bit_depth;

  const float scale = 2.0f / float(raw.maxValue());
  const float green_sign = options.green == GreenConvention::DirectX ? -1.0f : 1.0f;
  std::vector<BadTexel> bad;
  std::vector<std::uint8_t> is_bad(std::size_t(raw.width) * std::size_t(raw.height), 0);
  for (int j = 0; j < raw.height; ++j) {
    for (int i = 0; i < raw.width; ++i) {
      const Eigen::Vector3f n(raw.at(i, j, 0) * scale - 1.0f, green_sign * (raw.at(i, j, 1) * scale - 1.0f),
                              raw.at(i, j, 2) * scale - 1.0f);
      const float len = n.norm();
      const bool degenerate = !(len >= 0.5f && len <= 1.5f);
      if (degenerate || n.z() <= 0.0f) {
        bad.push_back({i, j, degenerate});
        is_bad[std::size_t(j) * std::size_t(raw.width) + std::size_t(i)] = 1;
        (degenerate ? rep.degenerate_texels : rep.into_surface_texels)++;
      } else {
        map.setNormal(i, j, n);
      }
      if (map.isRelief()) {
        const std::uint16_t a = raw.at(i, j, 3);
        map.setDepthCode(i, j, raw.bit_depth == 16 ? a : std::uint16_t(a * 257));
      }
    }
  }
  if (!bad.empty()) {
    if (options.bad_texels == BadTexelPolicy::Reject) {
      const BadTexel& first = bad.front();
      const Eigen::Vector3f c(raw.at(first.i, first.j, 0), raw.at(first.i, first.j, 1), raw.at(first.i, first.j, 2));
      char rgb[96];
      std::snprintf(rgb, sizeof rgb, "RGB (%d, %d, %d)", int(c.x()), int(c.y()), int(c.z()));
      throw TextureError(path,
                         std::to_string(bad.size()) + " bad texel(s): " + std::to_string(rep.degenerate_texels) +
                             " degenerate, " + std::to_string(rep.into_surface_texels) +
                             " pointing into the surface; first at " + texelName(first.i, first.j) + " is " +
                             (first.degenerate ? "degenerate" : "pointing into the surface"),
                         rgb,
                         "decoded normals of length 0.5..1.5 with z > 0 (or load with the repair policy, "
                         "e.g. texturetool info reports them)");
    }
    repair(map, bad, is_bad);
    rep.repaired_texels = int(bad.size());
    rep.warnings.push_back(path + ": repaired " + std::to_string(bad.size()) + " bad texel(s)");
  }

  TextureMeta& meta = map.meta();
  meta.kind = "file";
  if (auto it = raw.text.find(kKeyKind); it != raw.text.end()) meta.kind = it->second;
  if (auto it = raw.text.find(kKeyParams); it != raw.text.end()) meta.params = it->second;
  if (auto it = raw.text.find(kKeyExtent); it != raw.text.end()) {
    double x = 0, y = 0;
    char tail = 0;
    if (std::sscanf(it->second.c_str(), "%lf %lf %c", &x, &y, &tail) == 2 && std::isfinite(x) && std::isfinite(y) &&
        x > 0 && y > 0) {
      meta.extent_x_m = x;
      meta.extent_y_m = y;
    } else {
      rep.warnings.push_back(path + ": ignored malformed '" + std::string(kKeyExtent) + "' chunk '" + it->second +
                             "' (expected two positive lengths in metres)");
    }
  }
  if (auto it = raw.text.find(kKeyGreen); it != raw.text.end() && it->second != toString(options.green)) {
    rep.warnings.push_back(path + ": file says its green channel follows '" + it->second + "' but it was read as '" +
                           toString(options.green) + "'");
  }
  return map;
}

void saveTexture(const std::string& path, const TextureMap& map, const SaveOptions& options) {
  writePng(path, encodeTexture(map, path, options));
}

RawImage encodeTexture(const TextureMap& map, const std::string& path, const SaveOptions& options) {
  if (options.bit_depth != 8 && options.bit_depth != 16) {
    throw TextureError(path, "unsupported bit depth", std::to_string(options.bit_depth), "8 or 16");
  }
  RawImage raw;
  raw.width = map.width();
  raw.height = map.height();
  raw.channels = map.isRelief() ? 4 : 3;
  raw.bit_depth = options.bit_depth;
  raw.samples.resize(std::size_t(raw.width) * std::size_t(raw.height) * std::size_t(raw.channels));
  const double max_value = raw.maxValue();
  const float green_sign = options.green == GreenConvention::DirectX ? -1.0f : 1.0f;
  auto encode = [&](float c) {
    return std::uint16_t(std::lround(std::fmin(1.0, std::fmax(0.0, (c + 1.0) * 0.5)) * max_value));
  };
  std::size_t k = 0;
  for (int j = 0; j < map.height(); ++j) {
    for (int i = 0; i < map.width(); ++i) {
      const Eigen::Vector3f n = map.normal(i, j);
      raw.samples[k++] = encode(n.x());
      raw.samples[k++] = encode(green_sign * n.y());
      std::uint16_t z = encode(n.z());
      if (z <= std::uint16_t(max_value / 2)) z = std::uint16_t(max_value / 2 + 1);  // keep z > 0 after encoding
      raw.samples[k++] = z;
      if (map.isRelief()) {
        const std::uint16_t code = map.depthCode(i, j);
        raw.samples[k++] = options.bit_depth == 16 ? code : std::uint16_t(std::lround(code / 257.0));
      }
    }
  }
  const TextureMeta& meta = map.meta();
  raw.text[kKeyKind] = meta.kind;
  raw.text[kKeyGreen] = toString(options.green);
  if (map.isRelief()) raw.text[kKeyMaxDepth] = formatDouble(map.maxDepth());
  if (meta.extent_x_m > 0 && meta.extent_y_m > 0) {
    raw.text[kKeyExtent] = formatDouble(meta.extent_x_m) + " " + formatDouble(meta.extent_y_m);
  }
  if (!meta.params.empty()) raw.text[kKeyParams] = meta.params;
  return raw;
}

}  // namespace thx::tex
