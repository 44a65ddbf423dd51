#pragma once
// Ground truth for the force-error benchmark: analytic height fields, the same ones the texture
// generators rasterise (textures/generators/sine.cpp, vvalley.cpp), and the exact penalty force of
// a probe under them: F = k (q - p), q the closest point of the continuous surface to p (so F lies
// along the true surface normal at q wherever that normal exists).
//
// Frames: the generators work in texture coordinates X = x + extent/2, Y = y + extent/2 (from the
// map's bottom-left corner); the relief surface in the plane frame is z = h(X, Y) - h_top, h_top
// = the largest h over the texel centres of a map of the given size (textures/generators/common.hpp
// rasterize(): depth = h_top - h). So the truth depends on the size only through h_top.
#include <Eigen/Core>
#include <string>

#include "textures/generators.hpp"

namespace thx::bench {

// VValleySurface::region's names.
inline constexpr const char* kRegionNames[3] = {"floor", "ridge", "wall"};

class ExactSurface {
 public:
  virtual ~ExactSurface() = default;
  virtual std::string name() const = 0;
  virtual std::string description() const = 0;
  virtual tex::GenerateRequest request(int size) const = 0;
  double extent() const { return extent_m_; }

  // Sets h_top for a map of `size` texels per side.
  void setSize(int size);
  // Plane-frame height of the continuous surface at plane-local (x, y).
  double z(double x, double y) const { return h(x + extent_m_ / 2, y + extent_m_ / 2) - h_top_; }
  // The closest point of the continuous surface to a probe p at or below it (plane frame).
  // Accurate to better than 1e-9 m (sine: Newton on the distance's gradient to |step| < 1e-13 m
  // from the best point of a grid; vvalley: exact projection onto each wall segment).
  virtual Eigen::Vector3d closest(const Eigen::Vector3d& p) const = 0;

 protected:
  explicit ExactSurface(double extent_m) : extent_m_(extent_m) {}
  virtual double h(double X, double Y) const = 0;
  double h_top_ = 0.0;
  double extent_m_;
};

// h = A sin(k X) sin(k Y), k = 2 pi / period (generator "sine").
class SineSurface final : public ExactSurface {
 public:
  SineSurface(double amplitude_m, double period_m, double extent_m);
  std::string name() const override { return "sine"; }
  std::string description() const override;
  tex::GenerateRequest request(int size) const override;
  Eigen::Vector3d closest(const Eigen::Vector3d& p) const override;

 private:
  double h(double X, double Y) const override;
  double a_, period_, k_;
};

// Parallel V valleys along y (generator "vvalley"): ridges at X = m period, floors half way.
class VValleySurface final : public ExactSurface {
 public:
  VValleySurface(double angle_deg, double period_m, double extent_m);
  std::string name() const override { return "vvalley"; }
  std::string description() const override;
  tex::GenerateRequest request(int size) const override;
  Eigen::Vector3d closest(const Eigen::Vector3d& p) const override;
  // The same by golden-section search on each wall (for the self-check).
  Eigen::Vector3d closestGolden(const Eigen::Vector3d& p) const;
  // Where plane-local x lies: 0 within `reach` (horizontally) of a floor line, 1 of a ridge line,
  // 2 on a wall away from both (kRegionNames).
  int region(double x, double reach) const;
  double period() const { return period_; }

 private:
  double h(double X, double Y) const override;
  double angle_deg_, period_, slope_;
};

}  // namespace thx::bench
