#include "server/mesh_god_object.hpp"

#include <algorithm>
#include <cmath>

namespace thx::srv {

namespace {

// The first entry along a -> b, asked first of a short prefix of the segment: a proxy in contact
// sits kGodObjectStandoffM above the face it will enter again, a few nanometres along a sweep as
// long as the pen is deep, and a short segment visits a handful of the hierarchy's boxes where
// the whole one crosses a millimetre of them (bench_mesh_force: the sweep was a third of a tick
// at 500,000 triangles). Exact: an entry within the prefix is the first of the whole segment, and
// the split is half-open (a plane crossed exactly at the split point enters in the rest).
constexpr double kPrefixM = 1e-5;
TriangleBvh::Hit sweep(const TriangleBvh& bvh, const LocalTriangleSet* local, const Eigen::Vector3d& a,
                       const Eigen::Vector3d& b, const std::uint32_t* skip, int n_skip) {
  return local ? local->firstEntry(a, b, skip, n_skip) : bvh.firstEntry(a, b, skip, n_skip);
}
TriangleBvh::Hit firstEntry(const TriangleBvh& bvh, const LocalTriangleSet* local, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const std::uint32_t* skip, int n_skip) {
  const double len = (b - a).norm();
  if (!(len > 2 * kPrefixM)) return sweep(bvh, local, a, b, skip, n_skip);
  const double split = kPrefixM / len;
  const Eigen::Vector3d m = a + split * (b - a);
  TriangleBvh::Hit hit = sweep(bvh, local, a, m, skip, n_skip);
  if (hit.hit) {
    hit.t *= split;
    return hit;
  }
  hit = sweep(bvh, local, m, b, skip, n_skip);
  if (hit.hit) hit.t = split + hit.t * (1.0 - split);
  return hit;
}

}  // namespace

GodObjectStep moveGodObject(const TriangleBvh& bvh, const Eigen::Vector3d& proxy, const Eigen::Vector3d& tip,
                            const LocalTriangleSet* local) {
  std::array<Halfspace, kMaxHalfspaces> planes{};
  std::array<std::uint32_t, kGodObjectMaxConstraints> ids{};
  int count = 0;
  Eigen::Vector3d p = proxy, goal = tip;
  int sweeps = 0;
  while (sweeps < kGodObjectMaxSweeps) {
    ++sweeps;
    // The first sweep re-enters the face the proxy stands on (a prefix finds it); the later ones
    // slide along held faces, short already.
    const TriangleBvh::Hit hit =
        count == 0 ? firstEntry(bvh, local, p, goal, ids.data(), count) : sweep(bvh, local, p, goal, ids.data(), count);
    if (!hit.hit) {
      p = goal;
      break;
    }
    // Stop short of the face, back along the sweep (the way it came is free), so that the proxy
    // stays kGodObjectStandoffM outside its plane even when the sweep grazes it.
    const Eigen::Vector3d seg = goal - p;
    const double len = seg.norm();
    const Halfspace& h = bvh.plane(hit.triangle);
    if (len > 0.0) {
      const double cos_in = std::fabs(h.n.dot(seg)) / len;
      const double back = std::min(hit.t * len, kGodObjectStandoffM / std::max(cos_in, 1e-3));
      p = hit.point - seg * (back / len);
    }
    if (count == kGodObjectMaxConstraints) break;  // a fourth face: a corner holds the proxy where it is
    planes[std::size_t(count)] = Halfspace{h.n, h.d + kGodObjectStandoffM};
    ids[std::size_t(count)] = hit.triangle;
    ++count;
    const Projection pr = projectOntoHalfspaces(tip, planes, count);
    if (!pr.solved) break;  // numerically degenerate set: stay where the sweep stopped
    int kept = 0;  // planes with a zero multiplier no longer hold the proxy
    for (int i = 0; i < count; ++i) {
      if (!(pr.active_mask & (1u << i))) continue;
      planes[std::size_t(kept)] = planes[std::size_t(i)];
      ids[std::size_t(kept)] = ids[std::size_t(i)];
      ++kept;
    }
    count = kept;
    goal = pr.x;
  }

  GodObjectStep step;
  step.proxy = p;
  step.planes = planes;
  step.triangles = ids;
  step.count = count;
  step.sweeps = sweeps;
  return step;
}

MeshGodObject::MeshGodObject(const TriangleBvh& bvh, const tex::PlaneMapping& mapping, const RendererConfig& config)
    : bvh_(&bvh),
      config_(config),
      plane_to_world_(mapping.plane_to_world),
      world_to_plane_(mapping.plane_to_world.inverse()) {}

void MeshGodObject::reset() {
  have_proxy_ = false;
  last_sweeps_ = 0;
}

RenderOutput MeshGodObject::render(const Eigen::Vector3d& tip_world, const Eigen::Vector3d& v_world) {
  RenderOutput out;
  const Eigen::Vector3d tip = world_to_plane_ * tip_world;
  const Eigen::Vector3d v = world_to_plane_.linear() * v_world;
  out.n_geom_world = plane_to_world_.linear().col(2);
  out.n_sampled_world = out.n_geom_world;
  out.p_proj_world = plane_to_world_ * Eigen::Vector3d(tip.x(), tip.y(), 0.0);
  if (!tip.allFinite()) {
    // Nothing sensible to render from a non-finite tip; the safety stage handles the fault.
    out.proxy_world = plane_to_world_ * proxy_;
    return out;
  }
  if (!have_proxy_) {
    proxy_ = tip;
    have_proxy_ = true;
  }

  const GodObjectStep step = moveGodObject(*bvh_, proxy_, tip);
  const Eigen::Vector3d& p = step.proxy;
  const auto& planes = step.planes;
  const int count = step.count;
  last_sweeps_ = step.sweeps;
  proxy_ = p;

  const Eigen::Vector3d e = p - tip;
  const double length = e.norm();
  Eigen::Vector3d f_local = Eigen::Vector3d::Zero();
  if (length > 0.0) {
    const Eigen::Vector3d dir = e / length;
    // Damping along the spring only, and never pulling the pen into the surface.
    const double magnitude = std::max(0.0, config_.stiffness_n_per_m * length - config_.damping_ns_per_m * v.dot(dir));
    f_local = magnitude * dir;
  }
  out.in_contact = length > 0.0;
  out.proxy_held = length > 0.0;
  out.depth_m = length;
  out.force_world = plane_to_world_.linear() * f_local;
  out.proxy_world = plane_to_world_ * p;
  out.v_tangent_world = plane_to_world_.linear() * Eigen::Vector3d(v.x(), v.y(), 0.0);
  out.num_planes = count;
  out.active_mask = (1u << count) - 1u;
  for (int i = 0; i < count; ++i) {
    dev::PlaneProxy& pp = out.planes[std::size_t(i)];
    pp.n_world = plane_to_world_.linear() * planes[std::size_t(i)].n;
    pp.d_m = planes[std::size_t(i)].d + pp.n_world.dot(plane_to_world_.translation());
    pp.k_n_per_m = config_.stiffness_n_per_m;
    pp.b_ns_per_m = config_.damping_ns_per_m;
  }
  out.f_normal_n = count > 0 ? f_local.dot(planes[0].n) : f_local.z();
  return out;
}

}  // namespace thx::srv
