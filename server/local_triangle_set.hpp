#pragma once
// The hierarchy's leaves around the pen, kept between servo ticks so that the god object's sweeps
// (mesh_god_object.hpp) test a few dozen boxes instead of descending a deep hierarchy: at
// 500,000 triangles two root-to-leaf descents per tick were the largest part of a tick, and
// what a descent touched that the last tick's had not was most of its tail (docs/meshes.md).
// The region keeps its leaves' triangles too, as the entry test reads them (EntryTriangle),
// copied while it is gathered: a sweep then reads a few kilobytes written ahead of the pen, not
// planes and corners spread over the mesh's arrays.
//
// Exact: the set holds every leaf whose box meets a region box R; a segment inside R can only
// enter triangles of those leaves (a triangle's entry point lies inside its leaf's padded box), so
// firstEntry() answers as TriangleBvh::firstEntry does (the same triangle, t and point: the same
// primitive test and tie rule); a segment not inside R is asked of the hierarchy.
// No bursts: the next region is gathered ahead of the pen by an incremental walk of the
// hierarchy (TriangleBvh::BoxWalk), at most kNodesPerTick nodes per advance(), and swapped in
// when complete; a pen that outruns it is answered by the hierarchy meanwhile (still exact).
// The region's half side starts at half the typical leaf's extent (the median over the leaves of
// their boxes' largest side: a region a leaf across, about ten leaves; measured against one and
// two leaves across, docs/meshes.md) and halves whenever a region holds more than kMaxLeaves.
//
// Real-time safe once built: the constructor allocates (the leaves' extents, to size the region;
// built off the servo thread with its renderer); firstEntry() and advance() allocate nothing, take no lock, and their work is bounded (kMaxLeaves leaves, or the
// hierarchy's sweep; kNodesPerTick nodes).
#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "server/triangle_bvh.hpp"

namespace thx::srv {

class LocalTriangleSet {
 public:
  static constexpr int kMaxLeaves = 48;
  // The triangles a region keeps (four per leaf at the hierarchy's default leaf size): a region
  // with more has overflowed, as one with more leaves has.
  static constexpr int kMaxTriangles = 4 * kMaxLeaves;
  static constexpr int kNodesPerTick = 32;

  explicit LocalTriangleSet(const TriangleBvh& bvh);

  // The first front-face entry of a -> b, as TriangleBvh::firstEntry.
  TriangleBvh::Hit firstEntry(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const std::uint32_t* skip = nullptr,
                              int n_skip = 0) const;
  // Once per tick with the proxy's position: starts gathering the next region when the proxy has
  // moved a quarter of the half side from the current one's centre (ahead by its last motion),
  // and moves the gathering on.
  void advance(const Eigen::Vector3d& proxy);
  void reset();  // forget every region (a new proxy far from the last)

  // For tests and benchmarks.
  bool hasRegion() const { return active().complete; }
  double halfSide() const { return half_side_; }
  long long localAnswers() const { return local_answers_; }
  long long hierarchyAnswers() const { return hierarchy_answers_; }
  long long gathers() const { return gathers_; }
  int leaves() const { return active().leaves; }

 private:
  struct Region {
    Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero(), centre = Eigen::Vector3d::Zero();
    int leaves = 0;
    bool complete = false;
    std::array<std::array<double, 3>, kMaxLeaves> leaf_lo{}, leaf_hi{};
    std::array<std::uint32_t, kMaxLeaves> first{}, count{};  // each leaf's slots in `triangles`
    int triangle_count = 0;
    std::array<EntryTriangle, kMaxTriangles> triangles{};
  };
  // A leaf's triangles tested as TriangleBvh::enterLeaf tests them (the same test and tie rule),
  // read from the region's own records.
  static bool enterLeaf(const Region& region, int leaf, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                        const std::uint32_t* skip, int n_skip, TriangleBvh::Best& best);
  bool covers(const Region& r, const Eigen::Vector3d& a, const Eigen::Vector3d& b) const;
  void startGathering(const Eigen::Vector3d& centre);
  // Two regions, the one answering and the one being gathered; swapping is flipping the index
  // (a region is a few kilobytes: copying one would be a burst of its own).
  const Region& active() const { return regions_[std::size_t(active_index_)]; }
  Region& gathered() { return regions_[std::size_t(1 - active_index_)]; }

  const TriangleBvh* bvh_;
  double half_side_;
  double min_half_side_;
  std::array<Region, 2> regions_{};
  int active_index_ = 0;
  TriangleBvh::BoxWalk walk_;
  bool gathering_ = false;
  bool overflowed_ = false;
  bool failed_ = false;  // the smallest region overflowed around failed_centre_
  Eigen::Vector3d failed_centre_ = Eigen::Vector3d::Zero();
  bool have_last_ = false;
  Eigen::Vector3d last_proxy_ = Eigen::Vector3d::Zero();
  mutable long long local_answers_ = 0, hierarchy_answers_ = 0;
  mutable int hint_leaf_ = -1;  // the leaf of the last hit in the active region
  long long gathers_ = 0;
};

}  // namespace thx::srv
