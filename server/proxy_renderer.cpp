#include "server/proxy_renderer.hpp"

#include <cmath>
#include <numbers>

namespace thx::srv {

namespace {
constexpr double kDegToRad = std::numbers::pi / 180.0;
}

ProxyRenderer::ProxyRenderer(const tex::TexturedSurface& surface, const RendererConfig& config)
    : surface_(&surface), config_(config) {
  derive();
}

void ProxyRenderer::retarget(const tex::TexturedSurface& surface, const RendererConfig& config) {
  surface_ = &surface;
  config_ = config;
  derive();
  reset();
}

void ProxyRenderer::derive() {
  crease_cos_ = std::cos(config_.crease_angle_deg * kDegToRad);
  // Neighbours whose normals turn by at most asin(half the crease angle's sine) are all Smooth
  // with a wide margin over rounding. Off for a crease angle under 1 degree (there even equal
  // normals, normalised, may read as a crease) or over 90 (the sine turns back).
  const double crease = config_.crease_angle_deg;
  smooth_sine_ = crease >= 1.0 && crease <= 90.0 ? 0.5 * std::sin(crease * kDegToRad) : 0.0;
  deriveFromSurface();
}

void ProxyRenderer::deriveFromSurface() {
  // Texel centres of two walls meeting at a crease sit about a texel * sin(angle) inside each
  // other's half-spaces; a thousandth of a texel separates that from coplanar rounding.
  concave_tolerance_m_ = 1e-3 * surface_->texelSize();
}

void ProxyRenderer::reset() {
  in_contact_ = false;
  prev_planes_ = LocalPlanes{};
  prev_active_ = LocalPlanes{};
  e_rendered_prev_.setZero();
  recovery_offset_.setZero();
  recovery_left_ = 0;
  held_plane_ = LocalPlanes{};
  held_ticks_left_ = 0;
}

void ProxyRenderer::moveFrame(const Eigen::Isometry3d& old_to_new) {
  const Eigen::Matrix3d r = old_to_new.linear();
  auto movePlanes = [&](LocalPlanes& p) {
    for (int i = 0; i < p.count; ++i) {
      Halfspace& h = p.h[std::size_t(i)];
      p.q[std::size_t(i)] = old_to_new * p.q[std::size_t(i)];
      h.n = r * h.n;
      h.d = h.n.dot(p.q[std::size_t(i)]);
    }
  };
  proxy_local_ = old_to_new * proxy_local_;
  movePlanes(prev_planes_);
  movePlanes(prev_active_);
  movePlanes(held_plane_);
  e_rendered_prev_ = r * e_rendered_prev_;
  recovery_offset_ = r * recovery_offset_;
  deriveFromSurface();  // the chart's scale moved with it; the configuration did not
}

ProxyRenderer::LocalPlanes ProxyRenderer::singlePlaneAt(const tex::SurfacePoint& s, double x, double y) const {
  LocalPlanes p;
  p.q[0] = Eigen::Vector3d(x, y, s.height_m);
  p.h[0].n = s.n_local;
  p.h[0].d = s.n_local.dot(p.q[0]);
  p.count = 1;
  return p;
}

bool ProxyRenderer::concavePair(const Halfspace& a, const Eigen::Vector3d& qa, const Halfspace& b,
                                const Eigen::Vector3d& qb) const {
  // Concave (a valley): each plane's surface point lies inside the other's half-space, so holding
  // both cuts off no surface. At a ridge the points lie outside and holding both would.
  return a.n.dot(qb) - a.d > concave_tolerance_m_ && b.n.dot(qa) - b.d > concave_tolerance_m_;
}

double ProxyRenderer::planeHeightAt(const tex::TexelPoint& t, double x, double y) {
  const Eigen::Vector3d& n = t.n_local;
  if (!(n.z() > 1e-9)) return t.q_local.z();  // a vertical texel plane has no height: its centre's
  return t.q_local.z() - (n.x() * (x - t.q_local.x()) + n.y() * (y - t.q_local.y())) / n.z();
}

ProxyRenderer::LocalPlanes ProxyRenderer::planesAround(double x, double y) const {
  // Neighbours in the order +x, -x, +y, -y (texel indices): k ^ 1 is the opposite of k.
  static constexpr int kNeighbours[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  long long i = 0, j = 0;
  surface_->texelContaining(x, y, i, j);
  // Every neighbour within the crease angle (the map's slope steps tell without reading them):
  // no crease and no ridge, so the one interpolated plane below, as the reading would end.
  if (smooth_sine_ > 0.0 && surface_->neighboursTurnWithin(i, j, smooth_sine_))
    return singlePlaneAt(surface_->at(x, y), x, y);
  tex::TexelPoint c = surface_->texelPoint(i, j);
  Halfspace hc{c.n_local, c.n_local.dot(c.q_local)};
  std::array<tex::TexelPoint, 4> nbs;
  std::array<Bend, 4> bends{};
  auto readAround = [&] {
    for (std::size_t k = 0; k < 4; ++k) nbs[k] = surface_->texelPoint(i + kNeighbours[k][0], j + kNeighbours[k][1]);
    for (std::size_t k = 0; k < 4; ++k) {
      const tex::TexelPoint& t = nbs[k];
      if (c.n_local.dot(t.n_local) >= crease_cos_) {
        bends[k] = Bend::Smooth;
      } else if (concavePair(hc, c.q_local, Halfspace{t.n_local, t.n_local.dot(t.q_local)}, t.q_local)) {
        bends[k] = Bend::Concave;
      } else if (!config_.sided_ridges) {
        bends[k] = Bend::Convex;
      } else {
        // A ridge, or a smooth convex bend sampled coarsely (a sine's top at a few texels per
        // period bends as sharply between two texels)? Two samples cannot tell; a ridge is
        // the sharpest bend in its line: on both sides the next texel continues the wall.
        const double bend = (c.n_local - t.n_local).norm();
        auto continues = [&](const tex::TexelPoint& a, const tex::TexelPoint& b) {
          return (a.n_local - b.n_local).norm() * kRidgeContrast <= bend ||
                 concavePair(Halfspace{a.n_local, a.n_local.dot(a.q_local)}, a.q_local,
                             Halfspace{b.n_local, b.n_local.dot(b.q_local)}, b.q_local);
        };
        const tex::TexelPoint& c_back = nbs[k ^ 1u];
        bool ridge = continues(c_back, c);
        if (ridge) {
          const tex::TexelPoint t_next = surface_->texelPoint(i + 2 * kNeighbours[k][0], j + 2 * kNeighbours[k][1]);
          ridge = continues(t, t_next);
        }
        bends[k] = ridge ? Bend::Ridge : Bend::Convex;
      }
    }
  };
  readAround();
  if (config_.sided_ridges) {
    // Which side of a ridge (x, y) lies on: next to it the surface is the lower of the two texel
    // planes, so (x, y) belongs to the ridge neighbour whose plane is lower there than this
    // texel's. Each hop lowers the height at (x, y), so it cannot cycle; two hops cover a point
    // whose texel centre lies across a ridge in x and in y.
    for (int hop = 0; hop < 2; ++hop) {
      int best = -1;
      double best_z = planeHeightAt(c, x, y) - concave_tolerance_m_;
      for (std::size_t k = 0; k < 4; ++k) {
        if (bends[k] != Bend::Ridge) continue;
        const double z = planeHeightAt(nbs[k], x, y);
        if (z < best_z) {
          best_z = z;
          best = int(k);
        }
      }
      if (best < 0) break;
      i += kNeighbours[best][0];
      j += kNeighbours[best][1];
      c = nbs[std::size_t(best)];
      hc = Halfspace{c.n_local, c.n_local.dot(c.q_local)};
      readAround();
    }
  }
  LocalPlanes p;
  p.h[0] = hc;
  p.q[0] = c.q_local;
  p.count = 1;
  bool ridge = false;
  for (std::size_t k = 0; k < 4; ++k) {
    ridge = ridge || bends[k] == Bend::Ridge;
    if (bends[k] != Bend::Concave) continue;  // smooth here, or convex: one plane is right
    const tex::TexelPoint& t = nbs[k];
    const Halfspace ht{t.n_local, t.n_local.dot(t.q_local)};
    bool redundant = false;
    for (int m = 1; m < p.count; ++m) redundant = redundant || p.h[std::size_t(m)].n.dot(ht.n) >= crease_cos_;
    if (redundant || p.count == kMaxHalfspaces) continue;
    p.h[std::size_t(p.count)] = ht;
    p.q[std::size_t(p.count)] = t.q_local;
    ++p.count;
  }
  p.ridge = ridge;
  if (p.count > 1) return p;
  // Next to a ridge: this side's texel plane; the interpolated normal would blend both walls.
  if (ridge) return p;
  // No crease: one plane from the interpolated normal, so smooth textures feel smooth.
  return singlePlaneAt(surface_->at(x, y), x, y);
}

bool ProxyRenderer::mergeConcave(LocalPlanes& into, const LocalPlanes& from) const {
  bool added = false;
  for (int k = 0; k < from.count && into.count < kMaxHalfspaces; ++k) {
    const Halfspace& h = from.h[std::size_t(k)];
    const Eigen::Vector3d& q = from.q[std::size_t(k)];
    bool accept = true;
    for (int m = 0; m < into.count && accept; ++m) {
      const Halfspace& g = into.h[std::size_t(m)];
      accept = g.n.dot(h.n) < crease_cos_ && concavePair(g, into.q[std::size_t(m)], h, q);
    }
    if (!accept) continue;
    into.h[std::size_t(into.count)] = h;
    into.q[std::size_t(into.count)] = q;
    ++into.count;
    added = true;
  }
  return added;
}

Eigen::Vector3d ProxyRenderer::applyRecovery(const Eigen::Vector3d& t, const Eigen::Vector3d& e_target,
                                             bool& recovering) {
  if (config_.recovery_ticks > 0 && e_rendered_prev_.squaredNorm() > 0.0) {
    // A plane change is what last tick's planes cannot explain: project this tick's tip onto
    // them and compare. The tip's own motion, however fast (a tap into a wall), moves both alike
    // and never counts; a flipped normal or a lost contact does.
    Eigen::Vector3d e_predicted = Eigen::Vector3d::Zero();
    if (prev_planes_.count > 0) {
      const Projection p = projectOntoHalfspaces(t, prev_planes_.h, prev_planes_.count);
      if (p.solved && !p.inside) e_predicted = p.x - t;
    }
    if (config_.stiffness_n_per_m * (e_target - e_predicted).norm() > config_.recovery_jump_n) {
      recovery_offset_ = e_rendered_prev_ - e_target;  // keep the current penetration ...
      recovery_left_ = config_.recovery_ticks;         // ... then move to the new one
    }
  }
  Eigen::Vector3d e = e_target;
  recovering = false;
  if (recovery_left_ > 0) {
    e += recovery_offset_ * (double(recovery_left_) / double(config_.recovery_ticks));
    --recovery_left_;
    recovering = true;
  }
  e_rendered_prev_ = e;
  return e;
}

RenderOutput ProxyRenderer::render(const Eigen::Vector3d& tip_world, const Eigen::Vector3d& v_world) {
  RenderOutput out = renderForce(tip_world, v_world);
  describeContact(out);
  return out;
}

const tex::SurfacePoint& ProxyRenderer::tipPoint() {
  if (!have_at_tip_) {
    at_tip_ = surface_->at(tip_local_.x(), tip_local_.y());
    have_at_tip_ = true;
  }
  return at_tip_;
}

void ProxyRenderer::describeContact(RenderOutput& out) {
  const Eigen::Vector3d& t = tip_local_;
  const Eigen::Vector3d& v = v_local_;
  const tex::SurfacePoint& at_tip = tipPoint();
  out.p_proj_world = surface_->toWorld(Eigen::Vector3d(t.x(), t.y(), 0.0));
  out.uv = at_tip.uv;
  out.texel = tex::texelOf(surface_->map(), at_tip.uv, surface_->sampling().address);
  out.n_geom_world = surface_->directionToWorld(Eigen::Vector3d::UnitZ());
  out.tangent_world = surface_->directionToWorld(Eigen::Vector3d::UnitX());
  out.bitangent_world = surface_->directionToWorld(Eigen::Vector3d::UnitY());
  out.n_sampled_world = surface_->directionToWorld(at_tip.n_local);
  out.relief_depth_m = -at_tip.height_m;
  out.v_tangent_world = surface_->directionToWorld(Eigen::Vector3d(v.x(), v.y(), 0.0));
}

RenderOutput ProxyRenderer::renderForce(const Eigen::Vector3d& tip_world, const Eigen::Vector3d& v_world) {
  RenderOutput out;
  tip_local_ = surface_->toLocal(tip_world);
  v_local_ = surface_->directionToLocal(v_world);
  have_at_tip_ = false;
  const Eigen::Vector3d& t = tip_local_;
  const Eigen::Vector3d& v = v_local_;

  LocalPlanes planes;
  Eigen::Vector3d proxy = t;
  bool contact = false;
  if (!t.allFinite()) {
    // Nothing sensible to render from a non-finite tip; the safety stage handles the fault.
  } else if (!config_.crease_handling && config_.plane_hold_ticks > 1) {
    // The paper's loop: a new plane through the surface point under the tip once per frame,
    // whether or not the tip touches; in between, the tip meets that plane wherever it goes.
    if (held_ticks_left_ <= 0) {
      held_plane_ = singlePlaneAt(tipPoint(), t.x(), t.y());
      held_ticks_left_ = config_.plane_hold_ticks;
    }
    --held_ticks_left_;
    const double penetration = held_plane_.h[0].d - held_plane_.h[0].n.dot(t);
    if (penetration > 0.0) {
      planes = held_plane_;
      proxy = t + penetration * planes.h[0].n;
      contact = true;
      out.active_mask = 1;
    }
  } else if (!config_.crease_handling) {
    if (t.z() < tipPoint().height_m) {
      planes = singlePlaneAt(tipPoint(), t.x(), t.y());
      const double penetration = planes.h[0].d - planes.h[0].n.dot(t);
      proxy = t + penetration * planes.h[0].n;
      contact = true;
      out.active_mask = 1;
    }
  } else {
    // Entering: below the bilinear surface, or (sided ridges, relief) next to a ridge, whose
    // texel planes rise above the bilinear depth by up to slope x half a texel there: the
    // projection below tells whether the tip is below them. planesAround only hops to planes
    // lower at (x, y) than the plane of the texel under the tip, so a tip above that one plane
    // (one texel read) is above the surface there, and the plane set is not built for it.
    bool entering = !in_contact_ && t.z() < tipPoint().height_m;
    bool have_planes = false;
    if (!in_contact_ && !entering && config_.sided_ridges && surface_->usesRelief()) {
      long long i = 0, j = 0;
      surface_->texelContaining(t.x(), t.y(), i, j);
      if (t.z() < planeHeightAt(surface_->texelPoint(i, j), t.x(), t.y())) {
        planes = planesAround(t.x(), t.y());
        have_planes = true;
        entering = planes.ridge;
      }
    }
    if (in_contact_ || entering) {
      const double ax = entering ? t.x() : proxy_local_.x();
      const double ay = entering ? t.y() : proxy_local_.y();
      if (!have_planes) planes = planesAround(ax, ay);
      // The planes that held the proxy last tick stay (if still a concave set): without this
      // memory a deep tip can make the proxy alternate between two plane sets on every tick.
      if (!entering) mergeConcave(planes, prev_active_);
      Projection p = projectOntoHalfspaces(t, planes.h, planes.count);
      long long ai = 0, aj = 0;
      surface_->texelContaining(ax, ay, ai, aj);
      for (int merge = 0; merge < kMaxMerges && p.solved && !p.inside; ++merge) {
        long long pi = 0, pj = 0;
        surface_->texelContaining(p.x.x(), p.x.y(), pi, pj);
        if (pi == ai && pj == aj) break;
        ai = pi;
        aj = pj;
        if (!mergeConcave(planes, planesAround(p.x.x(), p.x.y()))) break;
        p = projectOntoHalfspaces(t, planes.h, planes.count);
      }
      if (!p.solved) {
        // Degenerate plane set (should not happen after deduplication): fall back to the centre plane.
        const double penetration = planes.h[0].d - planes.h[0].n.dot(t);
        proxy = penetration > 0.0 ? Eigen::Vector3d(t + penetration * planes.h[0].n) : t;
        contact = penetration > 0.0;
        out.active_mask = contact ? 1u : 0u;
      } else if (!p.inside) {
        proxy = p.x;
        contact = true;
        out.active_mask = p.active_mask;
      }
    }
  }

  bool recovering = false;
  const Eigen::Vector3d e =
      applyRecovery(t, contact ? Eigen::Vector3d(proxy - t) : Eigen::Vector3d::Zero(), recovering);
  prev_planes_ = contact ? planes : LocalPlanes{};
  prev_active_ = LocalPlanes{};
  for (int i = 0; contact && i < planes.count; ++i) {
    if (!(out.active_mask & (1u << i))) continue;
    prev_active_.h[std::size_t(prev_active_.count)] = planes.h[std::size_t(i)];
    prev_active_.q[std::size_t(prev_active_.count)] = planes.q[std::size_t(i)];
    ++prev_active_.count;
  }
  in_contact_ = contact;
  proxy_local_ = contact ? proxy : t;

  const double length = e.norm();
  Eigen::Vector3d f_local = Eigen::Vector3d::Zero();
  if (length > 0.0) {
    const Eigen::Vector3d dir = e / length;
    double magnitude = config_.stiffness_n_per_m * length - config_.damping_ns_per_m * v.dot(dir);
    if (magnitude < 0.0) magnitude = 0.0;  // a damper must never pull the pen into the surface
    f_local = magnitude * dir;
  }

  out.in_contact = length > 0.0;
  out.recovering = recovering;
  out.depth_m = length;
  out.force_world = surface_->directionToWorld(f_local);
  out.proxy_world = surface_->toWorld(proxy_local_);
  out.proxy_held = contact;
  const Eigen::Isometry3d& T = surface_->mapping().plane_to_world;
  out.num_planes = planes.count;
  for (int i = 0; i < planes.count; ++i) {
    dev::PlaneProxy& pp = out.planes[std::size_t(i)];
    pp.n_world = T.linear() * planes.h[std::size_t(i)].n;
    pp.d_m = planes.h[std::size_t(i)].d + pp.n_world.dot(T.translation());
    pp.k_n_per_m = config_.stiffness_n_per_m;
    pp.b_ns_per_m = config_.damping_ns_per_m;
  }
  out.f_normal_n = planes.count > 0 ? f_local.dot(planes.h[0].n) : f_local.z();
  return out;
}

}  // namespace thx::srv
