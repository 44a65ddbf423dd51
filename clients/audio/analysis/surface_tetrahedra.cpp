#include "clients/audio/analysis/surface_tetrahedra.hpp"

#include <gmsh.h>

#include <exception>
#include <map>
#include <unordered_map>
#include <utility>
#include <vector>

#include "clients/audio/analysis/modal_error.hpp"
#include "meshes/mesh_check.hpp"

namespace thx::audio {
namespace {

constexpr int kGmshTriangle = 2, kGmshTet4 = 4;

// Gmsh is one global model per process: initialised for one call, finalised on every way out.
class GmshSession {
 public:
  GmshSession() {
    gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    gmsh::option::setNumber("General.Terminal", 0);  // its messages come back as our errors
    gmsh::model::add("thx");
  }
  ~GmshSession() {
    try {
      gmsh::finalize();
    } catch (...) {  // nothing to do about a failing cleanup
    }
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

// One node per distinct position: a texture seam's split copies are the same point of the solid.
struct Welded {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<std::size_t, 3>> triangles;
};

Welded weld(const mesh::TexturedMesh& surface) {
  Welded w;
  std::map<std::array<double, 3>, std::size_t> index;
  std::vector<std::size_t> of(surface.positions.size());
  for (std::size_t i = 0; i < surface.positions.size(); ++i) {
    const Eigen::Vector3d& p = surface.positions[i];
    const auto [it, inserted] = index.try_emplace({p.x(), p.y(), p.z()}, w.points.size());
    if (inserted) w.points.push_back(p);
    of[i] = it->second;
  }
  w.triangles.reserve(surface.triangles.size());
  for (const mesh::Triangle& t : surface.triangles) w.triangles.push_back({of[t[0]], of[t[1]], of[t[2]]});
  return w;
}

double signedVolume6(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                     const Eigen::Vector3d& d) {
  return (b - a).dot((c - a).cross(d - a));
}

// Quadratic elements: a node at the middle of every edge, shared by the tets around it, in
// tet_mesh.hpp's order.
void addEdgeMidpoints(TetMesh& mesh) {
  std::unordered_map<std::uint64_t, int> midpoint;
  for (auto& tet : mesh.tets) {
    for (std::size_t e = 0; e < kTet10Edges.size(); ++e) {
      const int a = tet[std::size_t(kTet10Edges[e][0])], b = tet[std::size_t(kTet10Edges[e][1])];
      const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b));
      const auto [it, inserted] = midpoint.try_emplace(key, int(mesh.nodes.size()));
      if (inserted) mesh.nodes.push_back(0.5 * (mesh.nodes[std::size_t(a)] + mesh.nodes[std::size_t(b)]));
      tet[4 + e] = it->second;
    }
  }
}

ModalError cannotFill(const std::string& who, const std::string& reason) {
  return ModalError(who + ": Gmsh could not fill the surface with tetrahedra (" + reason +
                    "): is the surface free of self-intersections, and every part thick enough for it?");
}

}  // namespace

TetMesh tetrahedraOfSurface(const std::string& name, const mesh::TexturedMesh& surface,
                            const TetrahedraSettings& settings) {
  const std::string who = surface.source.empty() || surface.source == name ? name : name + " (" + surface.source + ")";
  try {
    mesh::MeshLimits limits;
    limits.require_closed = true;
    mesh::checkMesh(surface, limits);
  } catch (const Error& e) {
    throw ModalError(who + ": modal analysis needs the closed surface of a solid: " + e.what());
  }
  const Welded w = weld(surface);

  TetMesh out;
  out.name = name;
  out.order = settings.order;
  try {
    GmshSession session;
    gmsh::option::setNumber("Mesh.Algorithm3D", 1);  // Delaunay
    gmsh::option::setNumber("Mesh.Optimize", 1);     // Gmsh's tetrahedron optimiser
    if (settings.max_edge_m > 0.0) gmsh::option::setNumber("Mesh.MeshSizeMax", settings.max_edge_m);
    const int surf = gmsh::model::addDiscreteEntity(2);
    std::vector<std::size_t> tags(w.points.size());
    std::vector<double> xyz;
    xyz.reserve(3 * w.points.size());
    for (std::size_t i = 0; i < w.points.size(); ++i) {
      tags[i] = i + 1;
      xyz.insert(xyz.end(), {w.points[i].x(), w.points[i].y(), w.points[i].z()});
    }
    gmsh::model::mesh::addNodes(2, surf, tags, xyz);
    std::vector<std::size_t> corners;
    corners.reserve(3 * w.triangles.size());
    for (const auto& t : w.triangles) corners.insert(corners.end(), {t[0] + 1, t[1] + 1, t[2] + 1});
    gmsh::model::mesh::addElementsByType(surf, kGmshTriangle, {}, corners);
    const int loop = gmsh::model::geo::addSurfaceLoop({surf});
    gmsh::model::geo::addVolume({loop});
    gmsh::model::geo::synchronize();
    gmsh::model::mesh::generate(3);

    std::vector<std::size_t> node_tags;
    std::vector<double> coords, parametric;
    gmsh::model::mesh::getNodes(node_tags, coords, parametric);
    std::unordered_map<std::size_t, int> node_index;
    out.nodes.reserve(node_tags.size());
    for (std::size_t i = 0; i < node_tags.size(); ++i) {
      node_index.emplace(node_tags[i], int(out.nodes.size()));
      out.nodes.emplace_back(coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]);
    }
    std::vector<std::size_t> tet_tags, tet_nodes;
    gmsh::model::mesh::getElementsByType(kGmshTet4, tet_tags, tet_nodes);
    if (tet_tags.empty()) throw ModalError(who + ": Gmsh made no tetrahedra inside the surface");
    if (tet_tags.size() > settings.max_tets) {
      throw ModalError(who + ": " + std::to_string(tet_tags.size()) + " tetrahedra, more than the limit of " +
                       std::to_string(settings.max_tets) + ": give a larger max_edge_m or a coarser surface");
    }
    out.tets.reserve(tet_tags.size());
    for (std::size_t k = 0; k < tet_tags.size(); ++k) {
      std::array<int, 10> tet{};
      for (std::size_t c = 0; c < 4; ++c) tet[c] = node_index.at(tet_nodes[4 * k + c]);
      // Positive volume in the element's corner order (tet_element.hpp expects it).
      if (signedVolume6(out.nodes[std::size_t(tet[0])], out.nodes[std::size_t(tet[1])], out.nodes[std::size_t(tet[2])],
                        out.nodes[std::size_t(tet[3])]) < 0.0)
        std::swap(tet[1], tet[2]);
      out.tets.push_back(tet);
    }
  } catch (const ModalError&) {
    throw;
  } catch (const std::string& reason) {
    // Gmsh 4.8's API reports a surface it cannot fill (self-intersecting, too thin) by throwing
    // its last error as a std::string.
    throw cannotFill(who, reason);
  } catch (const std::exception& e) {
    throw cannotFill(who, e.what());
  } catch (...) {
    throw cannotFill(who, "no reason given");
  }
  if (settings.order == ElementOrder::Quadratic) addEdgeMidpoints(out);
  out.clamped.assign(out.nodes.size(), 0);  // a free body
  return out;
}

}  // namespace thx::audio
