#include "textures/smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "textures/texture_error.hpp"

namespace thx::tex {

namespace {

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Pads by the kernel radius with the address mode's border, filters, crops back. Filtering the
// padded image (rather than passing a border type to the filter) is what makes BORDER_WRAP
// possible: OpenCV's filters do not accept it directly.
cv::Mat blur(const cv::Mat& image, const cv::Mat& kernel, int radius, Address address) {
  const int border = address == Address::Wrap ? cv::BORDER_WRAP : cv::BORDER_REPLICATE;
  cv::Mat padded, filtered;
  cv::copyMakeBorder(image, padded, radius, radius, radius, radius, border);
  cv::sepFilter2D(padded, filtered, CV_64F, kernel, kernel, cv::Point(-1, -1), 0.0, cv::BORDER_CONSTANT);
  return filtered(cv::Rect(radius, radius, image.cols, image.rows)).clone();
}

}  // namespace

TextureMap smoothTexture(const TextureMap& map, const SmoothOptions& options) {
  const std::string source = "smoothing";
  if (map.width() <= 0 || map.height() <= 0) throw TextureError(source, "empty texture", "0x0", "a loaded texture");
  if (!std::isfinite(options.sigma_texels) || options.sigma_texels < 0.0 ||
      options.sigma_texels > kMaxSmoothingSigma) {
    throw TextureError(source, "sigma out of range", "sigma=" + fmt(options.sigma_texels),
                       "a finite value in [0, " + fmt(kMaxSmoothingSigma) + "] texels");
  }
  if (!std::isfinite(options.max_slope) || !(options.max_slope > 0.0)) {
    throw TextureError(source, "slope bound out of range", "max_slope=" + fmt(options.max_slope),
                       "a finite value > 0");
  }
  if (options.sigma_texels == 0.0) return map;

  const int w = map.width(), h = map.height();
  cv::Mat sx(h, w, CV_64F), sy(h, w, CV_64F), depth(h, w, CV_64F);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const Eigen::Vector3f n = map.normal(i, j);
      const double nz = std::max(double(n.z()), 1e-9);  // stored normals have nz > 0; guard anyway
      sx.at<double>(j, i) = std::clamp(-double(n.x()) / nz, -options.max_slope, options.max_slope);
      sy.at<double>(j, i) = std::clamp(-double(n.y()) / nz, -options.max_slope, options.max_slope);
      depth.at<double>(j, i) = map.depth(i, j);
    }
  }

  const int radius = int(std::ceil(4.0 * options.sigma_texels));
  const cv::Mat kernel = cv::getGaussianKernel(2 * radius + 1, options.sigma_texels, CV_64F);
  sx = blur(sx, kernel, radius, options.address);
  sy = blur(sy, kernel, radius, options.address);
  if (map.isRelief()) depth = blur(depth, kernel, radius, options.address);

  TextureMap out(w, h, map.representation(), map.maxDepth());
  out.meta() = map.meta();
  out.meta().params += std::string(out.meta().params.empty() ? "" : " ") + "smoothed sigma=" +
                       fmt(options.sigma_texels) +
                       (options.address == Address::Wrap ? " address=wrap" : " address=clamp");
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      out.setNormal(i, j, Eigen::Vector3f(float(-sx.at<double>(j, i)), float(-sy.at<double>(j, i)), 1.0f));
      if (map.isRelief()) out.setDepth(i, j, depth.at<double>(j, i));
    }
  }
  return out;
}

}  // namespace thx::tex
