#include "server/local_triangle_set.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace thx::srv {

LocalTriangleSet::LocalTriangleSet(const TriangleBvh& bvh)
    : bvh_(&bvh), half_side_(0.5 * bvh.typicalLeafExtent()), min_half_side_(0.125 * bvh.typicalLeafExtent()) {}

void LocalTriangleSet::reset() {
  regions_[0].complete = false;
  regions_[1].complete = false;
  gathering_ = false;
  have_last_ = false;
  failed_ = false;
}

bool LocalTriangleSet::covers(const Region& r, const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
  if (!r.complete) return false;
  for (int k = 0; k < 3; ++k)
    if (std::min(a[k], b[k]) < r.lo[k] || std::max(a[k], b[k]) > r.hi[k]) return false;
  return true;
}

TriangleBvh::Hit LocalTriangleSet::firstEntry(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                              const std::uint32_t* skip, int n_skip) const {
  const Region& region = active();
  if (!a.allFinite() || !b.allFinite() || !covers(region, a, b)) {
    ++hierarchy_answers_;
    return bvh_->firstEntry(a, b, skip, n_skip);
  }
  ++local_answers_;
  const SweepSegment seg = sweepSegment(a, b);
  TriangleBvh::Best best;
  auto scan = [&](int i) {
    double t_enter = 0.0;
    if (!slabEntry(region.leaf_lo[std::size_t(i)], region.leaf_hi[std::size_t(i)], seg, std::min(1.0, best.t), t_enter))
      return;
    if (enterLeaf(region, i, a, b, skip, n_skip, best)) hint_leaf_ = i;
  };
  // The leaf of the last answer first: the proxy re-enters the face it stands on, and once that
  // entry is known every box and plane farther along is passed over. The order changes which
  // tests run, not the answer (the least t, ties to the lower triangle, over every leaf).
  const int hint = hint_leaf_ < region.leaves ? hint_leaf_ : -1;
  if (hint >= 0) scan(hint);
  for (int i = 0; i < region.leaves; ++i)
    if (i != hint) scan(i);
  return TriangleBvh::hitOf(best, a, b);
}

bool LocalTriangleSet::enterLeaf(const Region& region, int leaf, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                 const std::uint32_t* skip, int n_skip, TriangleBvh::Best& best) {
  bool changed = false;
  const std::uint32_t first = region.first[std::size_t(leaf)], end = first + region.count[std::size_t(leaf)];
  for (std::uint32_t k = first; k < end; ++k) {
    const EntryTriangle& tri = region.triangles[k];
    double t = 0.0;
    if (TriangleBvh::skipped(skip, n_skip, tri.index) || !entersTriangle(tri, a, b, best.t, t)) continue;
    changed = TriangleBvh::keepIfFirst(best, t, tri.index) || changed;
  }
  return changed;
}

void LocalTriangleSet::startGathering(const Eigen::Vector3d& centre) {
  Region& next = gathered();
  next.centre = centre;
  next.lo = centre - Eigen::Vector3d::Constant(half_side_);
  next.hi = centre + Eigen::Vector3d::Constant(half_side_);
  next.leaves = 0;
  next.triangle_count = 0;
  next.complete = false;
  overflowed_ = false;
  bvh_->startWalk(walk_, next.lo, next.hi);
  gathering_ = true;
  ++gathers_;
}

void LocalTriangleSet::advance(const Eigen::Vector3d& proxy) {
  if (!proxy.allFinite()) return;
  const Eigen::Vector3d motion = have_last_ ? Eigen::Vector3d(proxy - last_proxy_) : Eigen::Vector3d::Zero();
  last_proxy_ = proxy;
  have_last_ = true;
  if (!gathering_) {
    const bool far = !active().complete || (proxy - active().centre).cwiseAbs().maxCoeff() > 0.25 * half_side_;
    if (!far) return;
    // Where even the smallest region overflowed, not again until the proxy has moved on.
    if (failed_ && (proxy - failed_centre_).cwiseAbs().maxCoeff() <= 0.25 * half_side_) return;
    // Centred where the proxy will be when the region is ready (a few ticks of its last motion),
    // at most a quarter of the side ahead.
    Eigen::Vector3d ahead = 4.0 * motion;
    const double reach = ahead.cwiseAbs().maxCoeff();
    if (reach > 0.25 * half_side_) ahead *= 0.25 * half_side_ / reach;
    startGathering(proxy + ahead);
  }
  Region& next = gathered();
  const bool done = bvh_->stepWalk(walk_, kNodesPerTick,
                                   [&](std::uint32_t first, std::uint32_t count, const std::array<double, 3>& lo,
                                       const std::array<double, 3>& hi) {
                                     if (next.leaves == kMaxLeaves ||
                                         next.triangle_count + int(count) > kMaxTriangles) {
                                       overflowed_ = true;
                                       return;
                                     }
                                     const auto i = std::size_t(next.leaves++);
                                     next.leaf_lo[i] = lo;
                                     next.leaf_hi[i] = hi;
                                     next.first[i] = std::uint32_t(next.triangle_count);
                                     next.count[i] = count;
                                     // Copied now, ahead of the pen and after a tick's force:
                                     // the sweeps then read them from here, not from the mesh.
                                     for (std::uint32_t k = first; k < first + count; ++k)
                                       next.triangles[std::size_t(next.triangle_count++)] =
                                           bvh_->entryTriangle(bvh_->leafTriangle(k));
                                   });
  if (!done && !overflowed_) return;
  gathering_ = false;
  if (overflowed_) {
    // Too many leaves for the scan to be cheap: a smaller region next time (the hierarchy
    // answers meanwhile).
    failed_ = half_side_ == min_half_side_;
    failed_centre_ = next.centre;
    half_side_ = std::max(min_half_side_, 0.5 * half_side_);
    return;
  }
  failed_ = false;
  next.complete = true;
  active_index_ = 1 - active_index_;
  hint_leaf_ = -1;
}

}  // namespace thx::srv
