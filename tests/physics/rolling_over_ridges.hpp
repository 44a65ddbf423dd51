#pragma once
// The reference a ball rolling across a relief is held to (tests/physics/test_relief_mesh_ridges.cpp):
// a rigid ball of radius r rolling without slipping and without bouncing across parallel ridges,
// a periodic height profile h(x) (period P) that does not vary along them.
//
// Its centre follows the curve its sphere meets, y_c(x) = max over xi of h(xi) + sqrt(r^2 - (x - xi)^2),
// touching at the xi that gives the max. Where that touch moves continuously, the rolling keeps
// its energy, (7/10) v^2 + g y_c (I = 2/5 m r^2; the centre's speed v = omega r about the touch).
// Where it jumps (a trough sharper than the ball, a ridge profile's inside corner), the ball is
// held at both places for an instant and rolls on about the new one: an impact that keeps the
// angular momentum about the new touch, v' = v (2 + 5 cos phi) / 7, phi the angle between the two
// touches' normals (the classical law of a ball rolling onto a step's edge). So the speed a ball
// loses crossing the ridges is set by their shape alone.
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace thx::phys::test::ridges {

class RollingOverRidges {
 public:
  // h over one period from x = 0; samples along the period, each touch searched among as many
  // points over a period around the centre.
  RollingOverRidges(std::function<double(double)> h, double period_m, double radius_m, int samples = 4000)
      : p_(period_m), centre_(std::size_t(samples) + 1), factor_(std::size_t(samples), 1.0) {
    std::vector<double> touch(centre_.size());
    double highest = -1e300;
    for (int j = 0; j < samples; ++j) highest = std::max(highest, h(p_ * j / samples));
    for (int k = 0; k <= samples; ++k) {
      const double x = p_ * k / samples;
      double best = -1e300, best_xi = x;
      for (int j = 0; j <= samples; ++j) {
        const double xi = x - 0.5 * p_ + p_ * j / samples;
        const double d = x - xi;
        if (std::fabs(d) >= radius_m) continue;
        const double y = h(xi) + std::sqrt(radius_m * radius_m - d * d);
        if (y > best) best = y, best_xi = xi;
      }
      centre_[std::size_t(k)] = best;
      touch[std::size_t(k)] = best_xi;
      lowest_m_ = std::min(lowest_m_, best - radius_m - highest);
    }
    // A touch that moves by more than a few search steps between neighbouring samples jumped.
    const double step = p_ / samples;
    for (int k = 0; k < samples; ++k) {
      const std::size_t i = std::size_t(k);
      if (std::fabs(touch[i + 1] - touch[i]) <= 4.0 * step) continue;
      const double x0 = p_ * k / samples, x1 = p_ * (k + 1) / samples;
      const double a0 = std::atan2(x0 - touch[i], centre_[i] - h(touch[i]));
      const double a1 = std::atan2(x1 - touch[i + 1], centre_[i + 1] - h(touch[i + 1]));
      const double phi = std::fabs(a1 - a0);
      factor_[i] = (2.0 + 5.0 * std::cos(phi)) / 7.0;
      ++jumps_;
      largest_jump_rad_ = std::max(largest_jump_rad_, phi);
    }
  }

  // Touches that jump in a period, the largest angle between two touches' normals there, and the
  // speed kept through all of a period's jumps.
  int jumps() const { return jumps_; }
  double largestJumpAngle() const { return largest_jump_rad_; }
  double speedKeptPerPeriod() const {
    double kept = 1.0;
    for (double f : factor_) kept *= f;
    return kept;
  }
  // The centre's lowest height less r, below the ridges' highest point (m, negative).
  double lowest() const { return lowest_m_; }

  // The mean speed along x over each of `periods` successive periods of a ball that starts at
  // x = 0 at v (m/s); shorter where it can no longer climb a crest.
  std::vector<double> periodMeanSpeeds(double v, int periods) const {
    constexpr double g = 9.81;
    std::vector<double> out;
    const std::size_t m = factor_.size();
    double energy = 0.7 * v * v + g * centre_[0];
    for (int k = 0; k < periods; ++k) {
      double t = 0.0;
      for (std::size_t i = 0; i < m; ++i) {
        const double v2 = (energy - g * 0.5 * (centre_[i] + centre_[i + 1])) / 0.7;
        if (!(v2 > 0.0)) return out;
        t += std::hypot(p_ / double(m), centre_[i + 1] - centre_[i]) / std::sqrt(v2);
        if (factor_[i] < 1.0) {
          const double after = factor_[i] * std::sqrt(std::max(0.0, (energy - g * centre_[i + 1]) / 0.7));
          energy = 0.7 * after * after + g * centre_[i + 1];
        }
      }
      out.push_back(p_ / t);
    }
    return out;
  }

 private:
  double p_;
  std::vector<double> centre_;
  std::vector<double> factor_;  // the speed kept between sample i and i + 1
  int jumps_ = 0;
  double largest_jump_rad_ = 0.0;
  double lowest_m_ = 0.0;
};

}  // namespace thx::phys::test::ridges
