#include "textures/texture_stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace thx::tex {

namespace {
constexpr double kDegPerRad = 180.0 / 3.14159265358979323846;

double tiltDeg(double nz) { return std::acos(std::clamp(nz, -1.0, 1.0)) * kDegPerRad; }
}  // namespace

TextureStats computeStats(const TextureMap& map, double steep_threshold_deg) {
  TextureStats s;
  s.width = map.width();
  s.height = map.height();
  s.representation = map.representation();
  s.max_depth_m = map.maxDepth();
  s.steep_threshold_deg = steep_threshold_deg;
  if (map.width() <= 0 || map.height() <= 0) return s;

  // Compare n.z, not angles, per texel: acos is the slow part and is monotonic.
  const double steep_nz = std::cos(steep_threshold_deg / kDegPerRad);
  double depth_sum = 0.0, nz_sum = 0.0, tilt_sum = 0.0;
  double depth_min = INFINITY, depth_max = -INFINITY, nz_min = INFINITY;
  for (int j = 0; j < map.height(); ++j) {
    for (int i = 0; i < map.width(); ++i) {
      const double depth = map.depth(i, j);
      depth_sum += depth;
      depth_min = std::min(depth_min, depth);
      depth_max = std::max(depth_max, depth);
      // Stored normals are unit length up to snorm16 rounding; renormalise for exact angles.
      const Eigen::Vector3f n = map.normal(i, j);
      const double nz = double(n.z()) / double(n.norm());
      nz_sum += nz;
      tilt_sum += tiltDeg(nz);
      if (nz < nz_min) {
        nz_min = nz;
        s.steepest_texel = {i, j};
      }
      if (nz < steep_nz) ++s.steep_texels;
    }
  }
  const double count = double(map.width()) * double(map.height());
  s.depth_min_m = depth_min;
  s.depth_max_m = depth_max;
  s.depth_mean_m = depth_sum / count;
  s.mean_nz = nz_sum / count;
  s.min_nz = nz_min;
  s.steepest_deg = tiltDeg(nz_min);
  s.mean_tilt_deg = tilt_sum / count;
  return s;
}

std::string formatStats(const TextureStats& s) {
  char buf[1024];
  const double count = double(s.width) * double(s.height);
  std::string out;
  std::snprintf(buf, sizeof buf, "size:            %d x %d texels\n", s.width, s.height);
  out += buf;
  std::snprintf(buf, sizeof buf, "representation:  %s\n", toString(s.representation));
  out += buf;
  if (s.bit_depth > 0) {
    std::snprintf(buf, sizeof buf, "bit depth:       %d\n", s.bit_depth);
    out += buf;
  }
  if (s.representation == Representation::Relief) {
    std::snprintf(buf, sizeof buf,
                  "max depth:       %.6g m\n"
                  "depth:           min %.6g m, max %.6g m, mean %.6g m\n",
                  s.max_depth_m, s.depth_min_m, s.depth_max_m, s.depth_mean_m);
    out += buf;
  }
  std::snprintf(buf, sizeof buf,
                "normal n.z:      mean %.6f, min %.6f\n"
                "tilt:            mean %.3f deg, steepest %.3f deg at texel (%d, %d)\n"
                "steep texels:    %zu (%.3f %%) steeper than %.1f deg\n",
                s.mean_nz, s.min_nz, s.mean_tilt_deg, s.steepest_deg, s.steepest_texel.i, s.steepest_texel.j,
                s.steep_texels, count > 0 ? 100.0 * double(s.steep_texels) / count : 0.0, s.steep_threshold_deg);
  out += buf;
  return out;
}

}  // namespace thx::tex
