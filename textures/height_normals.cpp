#include "textures/height_normals.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "textures/texture_error.hpp"

namespace thx::tex {

namespace {

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

void checkTexelSize(const Eigen::Vector2d& texel_m, const std::string& source) {
  for (int k = 0; k < 2; ++k) {
    if (!std::isfinite(texel_m[k]) || !(texel_m[k] > 0.0)) {
      throw TextureError(source, std::string("texel size along ") + (k == 0 ? "x" : "y"), fmt(texel_m[k]),
                         "a finite size > 0 in metres");
    }
  }
}

// Derivative of h along one axis at index k of n samples, `at(m)` reading sample m (0 <= m < n).
// Wrap: periodic central difference. Clamp: central inside, one-sided at the two ends.
template <class At>
double derivative(int k, int n, double step_m, Address address, At&& at) {
  if (address == Address::Wrap) {
    const int lo = k == 0 ? n - 1 : k - 1;
    const int hi = k == n - 1 ? 0 : k + 1;
    return (at(hi) - at(lo)) / (2.0 * step_m);
  }
  if (k == 0) return (at(1) - at(0)) / step_m;
  if (k == n - 1) return (at(n - 1) - at(n - 2)) / step_m;
  return (at(k + 1) - at(k - 1)) / (2.0 * step_m);
}

}  // namespace

void checkHeightField(const HeightField& field, const std::string& source) {
  if (field.width < kMinTextureSide || field.height < kMinTextureSide || field.width > kMaxTextureSide ||
      field.height > kMaxTextureSide) {
    throw TextureError(source, "size out of range", std::to_string(field.width) + "x" + std::to_string(field.height),
                       "each side in [" + std::to_string(kMinTextureSide) + ", " + std::to_string(kMaxTextureSide) +
                           "]");
  }
  const std::size_t expected = std::size_t(field.width) * std::size_t(field.height);
  if (field.heights_m.size() != expected) {
    throw TextureError(source, "sample count does not match the size", std::to_string(field.heights_m.size()),
                       std::to_string(expected) + " samples");
  }
  std::size_t bad = 0, first = 0;
  for (std::size_t k = 0; k < expected; ++k) {
    if (!std::isfinite(field.heights_m[k])) {
      if (bad == 0) first = k;
      ++bad;
    }
  }
  if (bad > 0) {
    const int i = int(first % std::size_t(field.width)), j = int(first / std::size_t(field.width));
    throw TextureError(source,
                       "non-finite height at sample (" + std::to_string(i) + ", " + std::to_string(j) + "), " +
                           std::to_string(bad) + " non-finite sample" + (bad == 1 ? "" : "s") + " in all",
                       fmt(field.heights_m[first]), "finite heights in metres");
  }
}

Eigen::Vector3d heightNormalAt(const HeightField& field, int i, int j, const Eigen::Vector2d& texel_m,
                               Address address) {
  const double dhdx =
      derivative(i, field.width, texel_m.x(), address, [&](int m) { return field.at(m, j); });
  // +y is image up: walking +y means decreasing the row, so read the row axis reversed.
  const int rows = field.height;
  const double dhdy = derivative(rows - 1 - j, rows, texel_m.y(), address,
                                 [&](int m) { return field.at(i, rows - 1 - m); });
  return Eigen::Vector3d(-dhdx, -dhdy, 1.0).normalized();
}

std::vector<Eigen::Vector3f> normalsFromHeight(const HeightField& field, const Eigen::Vector2d& texel_m,
                                               Address address, const std::string& source) {
  checkHeightField(field, source);
  checkTexelSize(texel_m, source);
  const int w = field.width, h = field.height;
  // Neighbour indices and difference spans per column / row, so the inner loop is plain
  // arithmetic (the same rule as heightNormalAt; this runs on 16-megatexel maps).
  struct Stencil {
    int lo, hi;
    double inv_span;  // 1 / (distance between lo and hi in metres)
  };
  auto stencils = [&](int n, double step) {
    std::vector<Stencil> st(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
      int lo = k - 1, hi = k + 1;
      if (address == Address::Wrap) {
        lo = lo < 0 ? n - 1 : lo;
        hi = hi == n ? 0 : hi;
        st[std::size_t(k)] = {lo, hi, 1.0 / (2.0 * step)};
      } else {
        lo = std::max(lo, 0);
        hi = std::min(hi, n - 1);
        st[std::size_t(k)] = {lo, hi, 1.0 / ((hi - lo) * step)};
      }
    }
    return st;
  };
  const std::vector<Stencil> cols = stencils(w, texel_m.x()), rows = stencils(h, texel_m.y());
  std::vector<Eigen::Vector3f> normals(field.heights_m.size());
  for (int j = 0; j < h; ++j) {
    const Stencil& r = rows[std::size_t(j)];
    // Row r.lo is above row j (+y), r.hi below.
    const double* above = &field.heights_m[std::size_t(r.lo) * std::size_t(w)];
    const double* below = &field.heights_m[std::size_t(r.hi) * std::size_t(w)];
    const double* row = &field.heights_m[std::size_t(j) * std::size_t(w)];
    for (int i = 0; i < w; ++i) {
      const Stencil& c = cols[std::size_t(i)];
      const double dhdx = (row[c.hi] - row[c.lo]) * c.inv_span;
      const double dhdy = (above[i] - below[i]) * r.inv_span;
      const double inv_len = 1.0 / std::sqrt(dhdx * dhdx + dhdy * dhdy + 1.0);
      normals[std::size_t(j) * std::size_t(w) + std::size_t(i)] =
          Eigen::Vector3f(float(-dhdx * inv_len), float(-dhdy * inv_len), float(inv_len));
    }
  }
  return normals;
}

TextureMap reliefFromHeight(const HeightField& field, const ReliefFromHeightOptions& options) {
  const std::vector<Eigen::Vector3f> normals =
      normalsFromHeight(field, options.texel_m, options.address, options.source);
  const auto [lo, hi] = std::minmax_element(field.heights_m.begin(), field.heights_m.end());
  const double h_max = *hi, range = *hi - *lo;

  TextureMap map(field.width, field.height, options.representation,
                 options.representation == Representation::Relief ? std::max(range, kFlatReliefDepth_m) : 0.0);
  for (int j = 0; j < field.height; ++j) {
    for (int i = 0; i < field.width; ++i) {
      map.setNormal(i, j, normals[std::size_t(j) * std::size_t(field.width) + std::size_t(i)]);
      map.setDepth(i, j, h_max - field.at(i, j));
    }
  }
  TextureMeta& meta = map.meta();
  meta.kind = "height";
  meta.extent_x_m = options.texel_m.x() * field.width;
  meta.extent_y_m = options.texel_m.y() * field.height;
  meta.params = "height_range_m=" + fmt(range) +
                " address=" + (options.address == Address::Wrap ? "wrap" : "clamp");
  return map;
}

}  // namespace thx::tex
