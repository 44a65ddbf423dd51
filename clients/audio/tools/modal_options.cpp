#include "clients/audio/tools/modal_options.hpp"

#include <cstdlib>
#include <sstream>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "clients/audio/analysis/surface_tetrahedra.hpp"
#include "meshes/builtin_shapes.hpp"
#include "meshes/mesh_import.hpp"

namespace thx::audio {

const char* const kModalHelp = R"(usage: modal-analyze --shape SHAPE [dimensions] [options]
       modal-analyze --mesh FILE|BUILTIN [mesh options] [options]
       modal-analyze --scene FILE [options]

Offline modal analysis of one object: a structured tetrahedral mesh (or the solid inside a closed
triangle mesh, filled with tetrahedra by Gmsh), linear elasticity with consistent mass,
K x = lambda M x solved by ARPACK in shift-invert mode (negative shift, sparse Cholesky of
K - sigma M), the 6 rigid-body modes of a free body dropped, Rayleigh damping from the material,
the audible band, the psychoacoustic merge of close modes and truncation. Prints one line per
audible mode; results are cached (docs/audio.md), so a second run is fast.

Scene:
  --scene FILE           analyse a scene's surface slab (surface.thickness, surface.held), or on
                         a mesh scene (surface.mesh) the solid its closed mesh encloses (Gmsh; a
                         built-in shape at no more than 48 segments), each moving object and the
                         pen (device.pen) (Tet10, the scene's materials; fixed obstacles skipped, a
                         capsule as a cylinder of its overall length); prints one summary line per
                         body
  --slab-thickness M     the surface slab's thickness (default: the scene's surface.thickness)
  --slab-cells N         slab cells per side, in the plane (default 20)
  --slab-layers N        slab cells through the thickness (default 2)

Shape (SI units):
  --shape S              box | slab | sphere | cylinder
  --size X,Y,Z           box: edge lengths; slab: extent x, extent y, thickness (m)
  --radius R             sphere, cylinder (m)
  --length L             cylinder: full length along its axis (m)
  --cells N[,N,N]        grid cells: box/slab NX,NY,NZ; sphere N (per side of the mapped cube);
                         cylinder N,NZ (cross-section side, along the axis). Default: box/slab
                         sized from the shortest edge, sphere 4, cylinder 2,16
  --element E            tet10 (default, quadratic) | tet4 (linear; needs fine meshes)
  --clamp-edges          slab or scene: hold the slab's four side faces (default: a free
                         body, or the scene's surface.held)
  --name NAME            the object's name in messages (default: the shape)

Mesh (any closed triangle mesh; docs/audio.md, "Modes of a closed triangle mesh"):
  --mesh FILE|BUILTIN    a mesh file (OBJ, PLY, glTF 2.0, STL) or a built-in shape (sphere,
                         cylinder, torus, bowl, vase, box, room, plate; docs/meshes.md): the solid
                         it encloses, tetrahedralised by Gmsh (3D Delaunay, optimised); it must be
                         closed and consistently wound
  --mesh-unit U          metres per file unit (default 1; 0.001 for a file in millimetres)
  --radius R             a built-in shape's size (its radius; default 0.05 m)
  --segments N           a built-in shape's divisions around its axis (default 48)
  --max-edge M           longest tetrahedron edge inside (default: sized from the surface)

Material (scenes' materials table, docs/scenes.md; any value can be overridden):
  --material NAME        default steel
  --density KG_M3  --youngs PA  --poisson NU  --alpha PER_S  --beta S

Solver:
  --modes N              elastic modes to compute (default 30; a free body's 6 rigid modes on top)
  --shift-hz F           sigma = -(2 pi F)^2 (default 20)
  --tolerance T          ARPACK relative tolerance (default 1e-10)
  --max-iterations N     ARPACK implicit restarts (default 1000)
  --lanczos-vectors N    ARPACK ncv (default max(2 nev + 1, nev + 40), nev the modes
                         asked of ARPACK, rigid ones included)
  --factorization F      of K - sigma M: cholmod (default; CHOLMOD supernodal Cholesky) | ldlt
                         (Eigen's SimplicialLDLT, AMD ordering; slower on large meshes)

Audible modes:
  --min-hz F             default 20
  --max-hz F             default 16000 (always below the Nyquist frequency)
  --sample-rate HZ       default 44100
  --merge-hz F           merge modes closer than max(F, REL x f) (default 2)
  --merge-rel REL        default 0.003
  --no-merge             keep every mode
  --max-modes N          keep at most the N lowest after merging (default: all)

Output:
  --csv FILE             the audible modes: mode, frequency_hz, decay_per_s, damping_ratio, t60_s, members
  --cache-dir DIR        default $XDG_CACHE_HOME/texhaptics/modal (or ~/.cache/texhaptics/modal)
  --no-cache             always solve, write nothing
  --quiet                no progress lines on stderr
  -h, --help             this text

Examples: the free-free steel bar of docs/audio.md; a ceramic vase of 4,968 triangles
  modal-analyze --shape box --size 0.3,0.02,0.01 --cells 30,2,1 --modes 6
  modal-analyze --mesh vase --radius 0.05 --segments 46 --material ceramic
)";

namespace {

std::vector<double> parseList(const std::string& option, const std::string& text, std::size_t min_count,
                              std::size_t max_count, const cli::Range& range) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(cli::parseNumber(option, item, range));
  if (out.size() < min_count || out.size() > max_count)
    throw UsageError(option + ": expected " + std::to_string(min_count) +
                     (max_count > min_count ? " to " + std::to_string(max_count) : std::string()) +
                     " comma-separated values, got '" + text + "'");
  return out;
}

}  // namespace

ModalOptions parseModalOptions(const std::vector<std::string>& args) {
  ModalOptions o;
  std::string material = "steel";
  std::optional<double> density, youngs, poisson, alpha, beta;
  bool shape_given = false, no_cache = false;
  std::optional<std::string> cache_dir;
  const cli::Range length{0, 100, true, "m"};
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) throw UsageError(a + ": missing value");
      return args[++i];
    };
    if (a == "-h" || a == "--help") {
      o.help = true;
    } else if (a == "--scene") {
      o.scene = value();
    } else if (a == "--slab-thickness") {
      o.slab_thickness = cli::parseNumber(a, value(), length);
    } else if (a == "--slab-cells") {
      o.slab_cells = int(cli::parseInteger(a, value(), 1, 400));
    } else if (a == "--slab-layers") {
      o.slab_layers = int(cli::parseInteger(a, value(), 1, 40));
    } else if (a == "--shape") {
      const std::string v = value();
      if (v == "box") o.shape = ShapeKind::Box;
      else if (v == "slab") o.shape = ShapeKind::Slab;
      else if (v == "sphere") o.shape = ShapeKind::Sphere;
      else if (v == "cylinder") o.shape = ShapeKind::Cylinder;
      else throw UsageError("--shape: expected box, slab, sphere or cylinder, got '" + v + "'");
      shape_given = true;
    } else if (a == "--size") {
      const auto v = parseList(a, value(), 3, 3, length);
      o.size = {v[0], v[1], v[2]};
    } else if (a == "--radius") {
      o.radius = cli::parseNumber(a, value(), length);
    } else if (a == "--length") {
      o.length = cli::parseNumber(a, value(), length);
    } else if (a == "--cells") {
      for (double c : parseList(a, value(), 1, 3, {1, 400, false, ""})) {
        if (c != double(int(c))) throw UsageError("--cells: expected whole numbers, got " + std::to_string(c));
        o.cells.push_back(int(c));
      }
    } else if (a == "--mesh") {
      o.mesh = value();
      o.shape = ShapeKind::Mesh;
      shape_given = true;
    } else if (a == "--mesh-unit") {
      o.mesh_unit = cli::parseNumber(a, value(), {0, 1e3, true, "m"});
    } else if (a == "--segments") {
      o.segments = int(cli::parseInteger(a, value(), 8, 4096));
    } else if (a == "--max-edge") {
      o.max_edge = cli::parseNumber(a, value(), length);
    } else if (a == "--element") {
      const std::string v = value();
      if (v == "tet10") o.order = ElementOrder::Quadratic;
      else if (v == "tet4") o.order = ElementOrder::Linear;
      else throw UsageError("--element: expected tet4 or tet10, got '" + v + "'");
    } else if (a == "--clamp-edges") {
      o.clamp_edges = true;
    } else if (a == "--name") {
      o.name = value();
    } else if (a == "--material") {
      material = value();
    } else if (a == "--density") {
      density = cli::parseNumber(a, value(), {0, 1e6, true, "kg/m^3"});
    } else if (a == "--youngs") {
      youngs = cli::parseNumber(a, value(), {0, 1e13, true, "Pa"});
    } else if (a == "--poisson") {
      // The material check names the limit 0.5 with its reason; here only a number is required.
      poisson = cli::parseNumber(a, value(), {-1, 1, true, ""});
    } else if (a == "--alpha") {
      alpha = cli::parseNumber(a, value(), {0, 1e6, false, "1/s"});
    } else if (a == "--beta") {
      beta = cli::parseNumber(a, value(), {0, 1, false, "s"});
    } else if (a == "--modes") {
      o.settings.elastic_modes = int(cli::parseInteger(a, value(), 1, 2000));
    } else if (a == "--shift-hz") {
      o.settings.shift_hz = cli::parseNumber(a, value(), {0, 1e5, true, "Hz"});
    } else if (a == "--tolerance") {
      o.settings.tolerance = cli::parseNumber(a, value(), {0, 1e-2, true, ""});
    } else if (a == "--max-iterations") {
      o.settings.max_iterations = int(cli::parseInteger(a, value(), 1, 1000000));
    } else if (a == "--lanczos-vectors") {
      o.settings.lanczos_vectors = int(cli::parseInteger(a, value(), 2, 100000));
    } else if (a == "--factorization") {
      const std::string v = value();
      if (v == "cholmod") o.settings.factorization = Factorization::CholmodSupernodal;
      else if (v == "ldlt") o.settings.factorization = Factorization::SimplicialLdlt;
      else throw UsageError("--factorization: expected cholmod or ldlt, got '" + v + "'");
    } else if (a == "--min-hz") {
      o.audible.min_hz = cli::parseNumber(a, value(), {0, 1e5, false, "Hz"});
    } else if (a == "--max-hz") {
      o.audible.max_hz = cli::parseNumber(a, value(), {0, 1e6, true, "Hz"});
    } else if (a == "--sample-rate") {
      o.audible.sample_rate_hz = cli::parseNumber(a, value(), {1000, 1e6, false, "Hz"});
    } else if (a == "--merge-hz") {
      o.audible.merge_abs_hz = cli::parseNumber(a, value(), {0, 1e4, false, "Hz"});
    } else if (a == "--merge-rel") {
      o.audible.merge_rel = cli::parseNumber(a, value(), {0, 1, false, ""});
    } else if (a == "--no-merge") {
      o.audible.merge = false;
    } else if (a == "--max-modes") {
      o.audible.max_modes = int(cli::parseInteger(a, value(), 1, 100000));
    } else if (a == "--csv") {
      o.csv = value();
    } else if (a == "--cache-dir") {
      cache_dir = value();
    } else if (a == "--no-cache") {
      no_cache = true;
    } else if (a == "--quiet") {
      o.quiet = true;
    } else {
      throw UsageError("unknown option '" + a + "'");
    }
  }
  if (o.help) return o;
  if (!o.scene.empty() && shape_given) throw UsageError("--scene and --shape or --mesh: give one of them");
  if (o.scene.empty() && !shape_given)
    throw UsageError("--shape: missing (box, slab, sphere or cylinder), or --mesh FILE, or --scene FILE");
  const scene::Material* m = scene::findMaterial(material);
  if (!m) {
    std::string names;
    for (const scene::Material& x : scene::materials()) names += (names.empty() ? "" : ", ") + x.name;
    throw UsageError("--material: unknown material '" + material + "', expected one of " + names);
  }
  o.material = *m;
  if (density || youngs || poisson || alpha || beta) o.material.name += " (custom)";
  if (density) o.material.density_kg_per_m3 = *density;
  if (youngs) o.material.youngs_modulus_pa = *youngs;
  if (poisson) o.material.poisson_ratio = *poisson;
  if (alpha) o.material.rayleigh_alpha_per_s = *alpha;
  if (beta) o.material.rayleigh_beta_s = *beta;

  if (!no_cache) o.cache_dir = cache_dir ? *cache_dir : defaultModalCacheDir();
  if (!o.scene.empty()) return o;
  if (o.shape == ShapeKind::Mesh) {
    if (!o.cells.empty()) throw UsageError("--cells: a mesh's tetrahedra come from Gmsh; give --max-edge instead");
    if (o.clamp_edges) throw UsageError("--clamp-edges: only a slab can be held at its edges");
    if (o.radius <= 0) o.radius = 0.05;
    if (o.name.empty()) o.name = o.mesh;
    return o;
  }
  const bool boxy = o.shape == ShapeKind::Box || o.shape == ShapeKind::Slab;
  if (boxy && o.size.minCoeff() <= 0) throw UsageError("--size: missing (X,Y,Z in metres) for a box or slab");
  if (!boxy && o.radius <= 0) throw UsageError("--radius: missing for a sphere or cylinder");
  if (o.shape == ShapeKind::Cylinder && o.length <= 0) throw UsageError("--length: missing for a cylinder");
  if (o.clamp_edges && o.scene.empty() && o.shape != ShapeKind::Slab) throw UsageError("--clamp-edges: only a slab can be held at its edges");
  const std::size_t want = boxy ? 3 : (o.shape == ShapeKind::Sphere ? 1 : 2);
  if (!o.cells.empty() && o.cells.size() != want)
    throw UsageError("--cells: expected " + std::to_string(want) + " value(s) for this shape, got " +
                     std::to_string(o.cells.size()));
  if (o.name.empty()) {
    static const char* const kNames[] = {"box", "slab", "sphere", "cylinder"};
    o.name = kNames[int(o.shape)];
  }
  return o;
}

TetMesh buildMesh(const ModalOptions& o, std::size_t* surface_triangles) {
  switch (o.shape) {
    case ShapeKind::Mesh: {
      mesh::TexturedMesh surface;
      if (mesh::isBuiltInShape(o.mesh)) {
        surface = mesh::builtInShape(o.mesh, o.radius, o.radius, o.segments).mesh;
      } else {
        mesh::ImportOptions io;
        io.unit_m = o.mesh_unit;
        io.projection = mesh::UvProjection::Planar;  // texture coordinates play no part in the modes
        surface = mesh::importMesh(o.mesh, io);
      }
      if (surface_triangles) *surface_triangles = surface.triangles.size();
      TetrahedraSettings ts;
      ts.order = o.order;
      ts.max_edge_m = o.max_edge;
      return tetrahedraOfSurface(o.name, surface, ts);
    }
    case ShapeKind::Box:
    case ShapeKind::Slab: {
      GridCells c;
      if (!o.cells.empty()) {
        c = {o.cells[0], o.cells[1], o.cells[2]};
      } else {
        // One element per shortest edge, cubes as near as the edges allow.
        const double h = o.size.minCoeff();
        c = {std::max(1, int(std::lround(o.size.x() / h))), std::max(1, int(std::lround(o.size.y() / h))),
             std::max(1, int(std::lround(o.size.z() / h)))};
      }
      if (o.shape == ShapeKind::Box) return boxMesh(o.name, o.size, c, o.order);
      return slabMesh(o.name, o.size.x(), o.size.y(), o.size.z(), c, o.order, o.clamp_edges);
    }
    case ShapeKind::Sphere:
      return sphereMesh(o.name, o.radius, o.cells.empty() ? 4 : o.cells[0], o.order);
    case ShapeKind::Cylinder:
      return cylinderMesh(o.name, o.radius, o.length, o.cells.empty() ? 2 : o.cells[0],
                          o.cells.empty() ? 16 : o.cells[1], o.order);
  }
  return {};
}

}  // namespace thx::audio
