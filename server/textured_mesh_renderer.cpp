#include "server/textured_mesh_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thx::srv {
namespace {

// How far Phong's triangles stand off the flat ones, at most over the centroids and the edges'
// midpoints, with a margin: where a tip outside the flat faces may still be under the surface.
double phongBulge(const mesh::TexturedMesh& mesh) {
  double worst = 0.0;
  const Eigen::Vector3d samples[] = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.5, 0.5, 0.0}, {0.0, 0.5, 0.5}, {0.5, 0.0, 0.5}};
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    for (const Eigen::Vector3d& b : samples) {
      const double d = (mesh::frameAt(mesh, t, b, mesh::FrameMode::InterpolatedPhong).point -
                        mesh::frameAt(mesh, t, b, mesh::FrameMode::Interpolated).point)
                           .norm();
      worst = std::max(worst, d);
    }
  }
  return 1.25 * worst;
}

}  // namespace

TexturedMeshRenderer::TexturedMeshRenderer(const mesh::TexturedMesh& mesh, const TriangleBvh& bvh,
                                           const MeshTexture& texture, const Eigen::Isometry3d& mesh_to_world,
                                           const RendererConfig& config, mesh::FrameMode frames)
    : mesh_(&mesh),
      bvh_(&bvh),
      texture_(texture),
      mesh_to_world_(mesh_to_world),
      world_to_mesh_(mesh_to_world.inverse()),
      config_(config),
      frames_(frames),
      bulge_m_(frames == mesh::FrameMode::InterpolatedPhong ? phongBulge(mesh) : 0.0),
      neighbours_(mesh::triangleNeighbours(mesh)),
      local_(bvh) {
  // Only a textured mesh renders on a chart; an untextured one has its smooth planes.
  if (texture.map) {
    chart_ = tex::TexturedSurface(*texture.map, tex::PlaneMapping{}, texture.sampling, texture.use_relief);
    chart_.setSlopeSteps(texture.slope_steps);
    chart_renderer_.emplace(chart_, config);
  }
}

void TexturedMeshRenderer::reset() {
  have_proxy_ = false;
  have_texture_proxy_ = false;
  chart_valid_ = false;
  if (chart_renderer_) chart_renderer_->reset();
  contact_ = {};
  last_sweeps_ = 0;
  local_.reset();
  next_tick_pending_ = false;
}

void TexturedMeshRenderer::prepareNextTick() {
  if (!next_tick_pending_) return;
  next_tick_pending_ = false;
  if (use_local_) local_.advance(proxy_);
  // The faces around the anchor's, which the next tick's anchor walks onto, asked for now.
  if (contact_.valid) {
    for (const std::uint32_t next : neighbours_[contact_.triangle]) {
      if (next == mesh::kNoNeighbour) continue;
      __builtin_prefetch(&bvh_->plane(next));
      for (const std::uint32_t v : mesh_->triangles[next]) {
        __builtin_prefetch(&mesh_->positions[v]);
        __builtin_prefetch(&mesh_->normals[v]);
        __builtin_prefetch(&mesh_->tangents[v]);
        __builtin_prefetch(&mesh_->uvs[v]);
      }
    }
  }
}

void TexturedMeshRenderer::locate(const Eigen::Vector3d& x, std::uint32_t held, std::uint32_t& triangle,
                                  Eigen::Vector3d& barycentric) const {
  // Walk across edges toward x while it projects outside the face, onto faces that continue the
  // held one smoothly. Across a crease (an inside corner, a box's edge) or a border the walk
  // stops and the face keeps its own frame, clamped to its border: the god object holds the
  // other face. A bounded number of hops (x moves a fraction of a face per tick).
  const Eigen::Vector3d& n_held = bvh_->plane(held).n;
  for (int hop = 0; hop < kMaxHops; ++hop) {
    const mesh::Triangle& t = mesh_->triangles[triangle];
    const Eigen::Vector3d& p0 = mesh_->positions[t[0]];
    const Eigen::Vector3d e1 = mesh_->positions[t[1]] - p0, e2 = mesh_->positions[t[2]] - p0, w = x - p0;
    const Eigen::Vector3d n = e1.cross(e2);
    const double inv = 1.0 / n.squaredNorm();
    const double l1 = w.cross(e2).dot(n) * inv, l2 = e1.cross(w).dot(n) * inv;
    const Eigen::Vector3d b(1.0 - l1 - l2, l1, l2);
    int worst = 0;
    for (int k = 1; k < 3; ++k) worst = b[k] < b[worst] ? k : worst;
    if (b[worst] >= 0.0) {
      barycentric = b;
      return;
    }
    const std::uint32_t next = neighbours_[triangle][std::size_t(worst)];
    if (next == mesh::kNoNeighbour || bvh_->plane(next).n.dot(n_held) < kSmoothNeighbourCos) break;
    triangle = next;
  }
  barycentric = mesh::closestBarycentric(*mesh_, triangle, x);
}

MeshContact TexturedMeshRenderer::anchor(std::uint32_t held, const MeshContact* previous, const Eigen::Vector3d& start,
                                         const Eigen::Vector3d& from) const {
  MeshContact at;
  at.valid = true;
  if (previous) {
    at = *previous;  // last tick's anchor: the fixed point moves little per tick
  } else {
    at.triangle = held;
    at.barycentric = mesh::closestBarycentric(*mesh_, held, start);
    at.frame = mesh::frameAt(*mesh_, at.triangle, at.barycentric, frames_);
  }
  Eigen::Vector3d last_foot = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  for (int k = 0; k < kAnchorSteps && frames_ != mesh::FrameMode::PerTriangle; ++k) {
    // The foot of `from` on the tangent plane, then back onto the surface.
    const Eigen::Vector3d foot = from - at.frame.normal * at.frame.normal.dot(from - at.frame.point);
    if ((foot - last_foot).squaredNorm() < kAnchorToleranceM * kAnchorToleranceM) break;
    last_foot = foot;
    locate(foot, held, at.triangle, at.barycentric);
    at.frame = mesh::frameAt(*mesh_, at.triangle, at.barycentric, frames_);
  }
  return at;
}

Halfspace TexturedMeshRenderer::planeAt(const MeshContact& at, Eigen::Vector3d& n_sampled, double& relief_depth) const {
  const mesh::SurfaceFrame& f = at.frame;
  n_sampled = f.normal;
  relief_depth = 0.0;
  if (texture_.map) {
    const tex::Sample s = tex::sample(*texture_.map, {f.uv.x(), f.uv.y()}, texture_.sampling);
    Eigen::Vector3d n = s.normal.cast<double>();
    if (texture_.normals_made_for_m.minCoeff() > 0.0)  // as on the chart (TexturedSurface::setNormalsMadeFor)
      n = tex::scaleSlopes(n, texture_.normals_made_for_m.cwiseQuotient(localScale(at)));
    n_sampled = mesh::fromTangentSpace(f, n);
    if (texture_.use_relief) relief_depth = double(s.depth);
  }
  const Eigen::Vector3d q = f.point - relief_depth * f.normal;
  return Halfspace{n_sampled, n_sampled.dot(q)};
}

bool TexturedMeshRenderer::smoothlyJoined(const std::uint32_t* held, int count) const {
  for (int i = 0; i < count; ++i)
    for (int j = i + 1; j < count; ++j)
      if (bvh_->plane(held[i]).n.dot(bvh_->plane(held[j]).n) < kSmoothNeighbourCos) return false;
  return true;
}

Eigen::Vector2d TexturedMeshRenderer::localScale(const MeshContact& at) const {
  return mesh::metresPerUv(*mesh_, at.triangle, at.frame);
}

tex::PlaneMapping TexturedMeshRenderer::chartAt(const MeshContact& at) const {
  const mesh::SurfaceFrame& f = at.frame;
  const Eigen::Vector2d scale = localScale(at);
  const double sx = scale.x(), sy = scale.y();
  tex::PlaneMapping m;
  m.size_m = {sx, sy};
  Eigen::Matrix3d axes;
  axes.col(0) = f.tangent;
  axes.col(1) = f.bitangent;
  axes.col(2) = f.normal;
  m.plane_to_world.linear() = axes;
  m.plane_to_world.translation() = f.point - f.tangent * ((f.uv.x() - 0.5) * sx) - f.bitangent * ((f.uv.y() - 0.5) * sy);
  return m;
}

void TexturedMeshRenderer::fillContact(RenderOutput& out, const MeshContact& at, const Eigen::Vector3d& n_sampled,
                                       double relief) const {
  const mesh::SurfaceFrame& f = at.frame;
  out.p_proj_world = f.point;
  out.uv = {f.uv.x(), f.uv.y()};
  if (texture_.map) out.texel = tex::texelOf(*texture_.map, out.uv, texture_.sampling.address);
  out.n_sampled_world = n_sampled;
  out.relief_depth_m = relief;
  fillPlace(out, at);
}

void TexturedMeshRenderer::fillPlace(RenderOutput& out, const MeshContact& at) const {
  out.triangle = std::int32_t(at.triangle);
  out.barycentric = at.barycentric;
  out.n_geom_world = at.frame.normal;  // the smooth surface's, at the anchor
  out.tangent_world = at.frame.tangent;
  out.bitangent_world = at.frame.bitangent;
}

RenderOutput TexturedMeshRenderer::renderOnChart(const MeshContact& at, const Eigen::Vector3d& tip,
                                                 const Eigen::Vector3d& v) {
  const tex::PlaneMapping m = chartAt(at);
  const Eigen::Isometry3d old_chart = chart_.mapping().plane_to_world;
  chart_ = tex::TexturedSurface(*texture_.map, m, texture_.sampling, texture_.use_relief);
  chart_.setNormalsMadeFor(texture_.normals_made_for_m);
  chart_.setSlopeSteps(texture_.slope_steps);
  if (chart_valid_) {
    chart_renderer_->moveFrame(chart_.worldToPlane() * old_chart);  // the inverse the chart has made
  } else {
    chart_renderer_->retarget(chart_, config_);
  }
  chart_valid_ = true;
  return chart_renderer_->renderForce(tip, v);
}

RenderOutput TexturedMeshRenderer::renderPlanes(const std::uint32_t* held, int count, const Eigen::Vector3d& from,
                                                const Eigen::Vector3d& tip, const Eigen::Vector3d& v) {
  RenderOutput out;
  std::array<Halfspace, kMaxHalfspaces> planes{};
  for (int i = 0; i < count; ++i) {
    const MeshContact at = anchor(held[i], nullptr, proxy_, from);
    Eigen::Vector3d n_sampled;
    double relief = 0.0;
    planes[std::size_t(i)] = planeAt(at, n_sampled, relief);
    if (i == 0) {
      contact_ = at;
      fillContact(out, at, n_sampled, relief);
    }
  }
  out.num_planes = count;
  for (int i = 0; i < count; ++i) {
    dev::PlaneProxy& pp = out.planes[std::size_t(i)];
    pp.n_world = planes[std::size_t(i)].n;
    pp.d_m = planes[std::size_t(i)].d;
    pp.k_n_per_m = config_.stiffness_n_per_m;
    pp.b_ns_per_m = config_.damping_ns_per_m;
  }
  out.v_tangent_world = v - out.n_sampled_world * out.n_sampled_world.dot(v);
  out.proxy_world = tip;
  const Projection pr = projectOntoHalfspaces(tip, planes, count);
  if (!pr.solved || pr.inside) return out;  // above the surface: held by no plane
  out.active_mask = pr.active_mask;
  const Eigen::Vector3d e = pr.x - tip;
  const double length = e.norm();
  if (!(length > 0.0)) return out;
  const Eigen::Vector3d dir = e / length;
  // Damping along the spring only, and never pulling the pen into the surface.
  const double magnitude = std::max(0.0, config_.stiffness_n_per_m * length - config_.damping_ns_per_m * v.dot(dir));
  out.in_contact = true;
  out.proxy_held = true;
  out.depth_m = length;
  out.force_world = magnitude * dir;
  out.proxy_world = pr.x;
  out.f_normal_n = out.force_world.dot(planes[0].n);
  return out;
}

RenderOutput TexturedMeshRenderer::render(const Eigen::Vector3d& tip_world, const Eigen::Vector3d& v_world) {
  RenderOutput out = renderForce(tip_world, v_world);
  describeContact(out);
  return out;
}

void TexturedMeshRenderer::describeContact(RenderOutput& out) {
  if (last_path_ == Path::NonFinite) return;  // renderForce() said all there is
  if (last_path_ == Path::Chart) {
    chart_renderer_->describeContact(out);
    // The plane renderer reports where the tip projects onto its chart; the anchor's point, uv and
    // face say where on the mesh that is.
    out.p_proj_world = contact_.frame.point;
    fillPlace(out, contact_);
  }
  // The mesh's frame to the world's (renderForce() has turned the force's fields).
  const Eigen::Matrix3d r = mesh_to_world_.linear();
  out.p_proj_world = mesh_to_world_ * out.p_proj_world;
  out.n_geom_world = r * out.n_geom_world;
  out.tangent_world = r * out.tangent_world;
  out.bitangent_world = r * out.bitangent_world;
  out.n_sampled_world = r * out.n_sampled_world;
  out.v_tangent_world = r * out.v_tangent_world;
}

RenderOutput TexturedMeshRenderer::renderForce(const Eigen::Vector3d& tip_world, const Eigen::Vector3d& v_world) {
  prepareNextTick();  // unless the caller has, since the last tick
  const Eigen::Vector3d tip = world_to_mesh_ * tip_world;
  const Eigen::Vector3d v = world_to_mesh_.linear() * v_world;
  const MeshContact previous = contact_;
  contact_ = {};
  RenderOutput out;
  out.p_proj_world = tip;
  out.proxy_world = tip;
  // Away from the mesh no place on it is meant: no triangle (-1), no frame.
  out.n_geom_world = Eigen::Vector3d::Zero();
  out.tangent_world = Eigen::Vector3d::Zero();
  out.bitangent_world = Eigen::Vector3d::Zero();
  out.n_sampled_world = Eigen::Vector3d::Zero();
  if (!tip.allFinite()) {
    // Nothing sensible to render from a non-finite tip; the safety stage handles the fault.
    out.proxy_world = mesh_to_world_ * proxy_;
    out.p_proj_world = tip_world;
    last_path_ = Path::NonFinite;
    return out;
  }
  if (!have_proxy_) {
    proxy_ = tip;
    have_proxy_ = true;
  }

  // 1. The god object on the flat faces; a tip just outside them but under Phong's surface is
  // held by the nearest face.
  const GodObjectStep step = moveGodObject(*bvh_, proxy_, tip, use_local_ ? &local_ : nullptr);
  proxy_ = step.proxy;
  last_sweeps_ = step.sweeps;
  next_tick_pending_ = true;
  std::array<std::uint32_t, kGodObjectMaxConstraints> held = step.triangles;
  int count = step.count;
  if (count == 0 && bulge_m_ > 0.0) {
    const TriangleBvh::Nearest near = bvh_->nearest(tip, bulge_m_);
    if (near.found) {
      held[0] = near.triangle;
      count = 1;
    }
  }

  // Faces held at a gentle concave edge (the inside of a bowl or a pipe: every edge there is an
  // inside crease of a few degrees) continue each other smoothly: one smooth surface, rendered on
  // the chart with its texture's crease handling. Only faces that meet at a crease (the inside
  // corner of a room) are rendered as several textured planes.
  if (count > 1 && smoothlyJoined(held.data(), count)) count = 1;

  const Eigen::Vector3d from = have_texture_proxy_ ? texture_proxy_ : tip;
  last_path_ = Path::Planes;  // or none held: what is said of the contact is said here, in the mesh's frame
  if (count == 0) {
    chart_valid_ = false;
  } else if (count == 1 && texture_.map) {
    contact_ = anchor(held[0], chart_valid_ ? &previous : nullptr, proxy_, from);
    out = renderOnChart(contact_, tip, v);
    last_path_ = Path::Chart;
  } else {
    chart_valid_ = false;
    out = renderPlanes(held.data(), count, from, tip, v);
  }
  have_texture_proxy_ = out.proxy_held;
  texture_proxy_ = out.proxy_world;

  // The force's fields from the mesh's frame to the world's (describeContact() turns the others).
  const Eigen::Matrix3d r = mesh_to_world_.linear();
  out.force_world = r * out.force_world;
  out.proxy_world = mesh_to_world_ * out.proxy_world;
  for (int i = 0; i < out.num_planes; ++i) {
    dev::PlaneProxy& pp = out.planes[std::size_t(i)];
    pp.n_world = r * pp.n_world;
    pp.d_m += pp.n_world.dot(mesh_to_world_.translation());
  }
  return out;
}

}  // namespace thx::srv
