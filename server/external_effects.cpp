#include "server/external_effects.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace thx::srv {

namespace {

Eigen::Vector3d vec(const double (&a)[3]) { return Eigen::Vector3d(a[0], a[1], a[2]); }

// A fixed orthonormal tangent pair for a unit normal (the texture's u, v axes).
void tangents(const Eigen::Vector3d& n, Eigen::Vector3d& t1, Eigen::Vector3d& t2) {
  const Eigen::Vector3d helper = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  t1 = n.cross(helper).normalized();
  t2 = n.cross(t1);
}

}  // namespace

ExternalEffectRenderer::ExternalEffectRenderer(double period_s) : period_s_(period_s) {}

bool ExternalEffectRenderer::anyActive() const {
  for (const ExternalPlane& p : effects_.planes)
    if (p.on) return true;
  return effects_.field.on || effects_.buzz.on;
}

double ExternalEffectRenderer::surfaceRaise(const Eigen::Vector3d& n, const Eigen::Vector3d& p) const {
  const ExternalSurfaceEffects& s = effects_.surface;
  if (!(s.texture_amplitude_m > 0.0) || !(s.texture_wavelength_m > 0.0)) return 0.0;
  Eigen::Vector3d t1, t2;
  tangents(n, t1, t2);
  const double w = 2.0 * std::numbers::pi / s.texture_wavelength_m;
  return s.texture_amplitude_m * std::sin(w * t1.dot(p)) * std::sin(w * t2.dot(p));
}

void ExternalEffectRenderer::takeCommands(const Eigen::Vector3d& p_world) {
  ExternalEffects fresh;
  if (!slot_.readIfNewer(fresh, slot_seq_)) return;
  for (int i = 0; i < kMaxExternalPlanes; ++i) {
    const ExternalPlane& old_plane = effects_.planes[std::size_t(i)];
    const ExternalPlane& new_plane = fresh.planes[std::size_t(i)];
    PlaneState& st = state_[std::size_t(i)];
    if (new_plane.version == st.version) continue;
    st.version = new_plane.version;
    if (!new_plane.on) {
      st = PlaneState{.version = new_plane.version};
      continue;
    }
    const bool keep_depth = st.was_on && old_plane.on && st.in_contact && new_plane.recovery_ticks > 1;
    if (keep_depth) {
      // Keep the depth the pen has now, measured along the new normal; then walk to the new
      // offset over recovery_ticks ticks (render() does the walking).
      const double depth_now = -(vec(old_plane.n).dot(p_world) + st.d_eff);
      st.d_eff = -vec(new_plane.n).dot(p_world) - depth_now;
      st.steps_left = new_plane.recovery_ticks;
    } else {
      st.d_eff = new_plane.d_m;
      st.steps_left = 0;
    }
    st.was_on = true;
  }
  if (fresh.buzz.version != buzz_version_) {
    buzz_version_ = fresh.buzz.version;
    buzz_start_tick_ = tick_;
  }
  effects_ = fresh;
}

ExternalOutput ExternalEffectRenderer::render(const Eigen::Vector3d& p, const Eigen::Vector3d& v, bool valid) {
  ExternalOutput out;
  out.scp_world = p;
  takeCommands(p);
  const double t = double(tick_) * period_s_;
  ++tick_;
  if (!valid) {
    for (PlaneState& st : state_) {
      st.in_contact = false;
      st.adhered = false;
      st.stuck_valid = false;
    }
    out.scp_world = Eigen::Vector3d::Zero();
    return out;
  }

  double deepest = 0.0;
  for (int i = 0; i < kMaxExternalPlanes; ++i) {
    const ExternalPlane& pl = effects_.planes[std::size_t(i)];
    PlaneState& st = state_[std::size_t(i)];
    if (!pl.on) continue;
    if (st.steps_left > 0) {
      st.d_eff += (pl.d_m - st.d_eff) / double(st.steps_left);
      --st.steps_left;
      out.recovering = true;
    }
    const Eigen::Vector3d n = vec(pl.n);
    const double raise = i == 0 ? surfaceRaise(n, p) : 0.0;
    const double depth = -(n.dot(p) + st.d_eff) + raise;
    const bool was_in_contact = st.in_contact;
    st.in_contact = depth > 0.0;

    if (!st.in_contact) {
      st.stuck_valid = false;
      // Normal adhesion (plane 0): after a contact, pull back until the pen is lifted past the
      // snap distance.
      const ExternalSurfaceEffects& s = effects_.surface;
      if (i == 0 && s.adhesion_k_n_per_m > 0.0) {
        if (was_in_contact) st.adhered = true;
        if (st.adhered && -depth < s.adhesion_snap_m) {
          out.force_world += n * (s.adhesion_k_n_per_m * depth);  // depth <= 0: toward the plane
        } else {
          st.adhered = false;
        }
      }
      continue;
    }
    st.adhered = false;

    double fn = pl.k_n_per_m * depth - pl.b_ns_per_m * v.dot(n);
    if (i == 0 && effects_.surface.buzz_amplitude_m > 0.0) {
      fn += pl.k_n_per_m * effects_.surface.buzz_amplitude_m *
            std::sin(2.0 * std::numbers::pi * effects_.surface.buzz_frequency_hz * t);
    }
    if (fn < 0.0) fn = 0.0;  // a surface pushes, never pulls
    Eigen::Vector3d f = n * fn;

    const Eigen::Vector3d on_plane = p + n * depth;
    if (pl.mu_static > 0.0 && pl.k_n_per_m > 0.0) {
      if (!st.stuck_valid) {
        st.stick = on_plane;
        st.stuck_valid = true;
      }
      Eigen::Vector3d e = st.stick - p;
      e -= n * n.dot(e);  // tangential part only
      Eigen::Vector3d ft = pl.k_n_per_m * e;
      const double ft_norm = ft.norm();
      if (ft_norm > pl.mu_static * fn && ft_norm > 0.0) {
        // Slip: the stick point is dragged so the tangential force equals mu_dynamic * F_n.
        const Eigen::Vector3d dir = e / e.norm();
        const double slip_len = pl.mu_dynamic * fn / pl.k_n_per_m;
        st.stick = on_plane + dir * slip_len;
        ft = dir * (pl.mu_dynamic * fn);
      }
      f += ft;
    } else {
      st.stuck_valid = false;
    }
    out.force_world += f;
    out.in_contact = true;
    if (depth > deepest) {
      deepest = depth;
      out.scp_world = on_plane;
    }
  }

  const ExternalField& fld = effects_.field;
  if (fld.on) {
    const Eigen::Vector3d dx = p - vec(fld.origin_m);
    if (dx.norm() <= fld.radius_m) {
      Eigen::Vector3d f = vec(fld.force_n);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) f[r] += fld.jacobian_n_per_m[r][c] * dx[c];
      out.force_world += f;
    }
  }

  const ExternalBuzz& bz = effects_.buzz;
  if (bz.on) {
    const double tb = double(tick_ - 1 - buzz_start_tick_) * period_s_;
    if (tb < bz.duration_s) {
      out.force_world +=
          vec(bz.direction) * (bz.amplitude_n * std::sin(2.0 * std::numbers::pi * bz.frequency_hz * tb));
    }
  }
  return out;
}

}  // namespace thx::srv
