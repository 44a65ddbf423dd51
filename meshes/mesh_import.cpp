#include "meshes/mesh_import.hpp"

#include <assimp/BaseImporter.h>
#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/importerdesc.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "base/error.hpp"
#include "base/number_text.hpp"
#include "meshes/ply_guard.hpp"

namespace thx::mesh {
namespace {

constexpr const char* kExpectedFormats = "expected one of OBJ, PLY, glTF 2.0, STL (.obj, .ply, .gltf, .glb, .stl)";

[[noreturn]] void refuse(Error::Kind kind, const std::string& source, const std::string& what) {
  throw Error(kind, "mesh " + source + ": " + what);
}

struct Format {
  std::string hint;  // the extension Assimp picks its reader by
  const char* name;
  const char* reader;  // Assimp's name for that reader
};

Format formatOf(const std::string& extension, const std::string& source) {
  std::string e = extension;
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (e == "obj") return {e, "OBJ", "Wavefront Object Importer"};
  if (e == "ply") return {e, "PLY", "Stanford Polygon Library (PLY) Importer"};
  if (e == "stl") return {e, "STL", "Stereolithography (STL) Importer"};
  if (e == "gltf" || e == "glb") return {e, "glTF 2.0", "glTF2 Importer"};
  refuse(Error::Kind::Config, source,
         (e.empty() ? std::string("no file extension to tell the format") : "unknown mesh format '." + ply::shown(e) + "'") +
             "; " + kExpectedFormats);
}

// What Assimp may open: the mesh's bytes, from memory, under the name `main` (Assimp picks the
// reader by its extension), and the files the mesh names beside itself (a .gltf's .bin buffers)
// from `folder`, regular files of at most `max_bytes` only; with no folder (bytes in memory) none.
// Never a material library (.mtl): materials are not used, and Assimp's MTL parser writes through
// a null pointer on a texture line before any material (found by libFuzzer through Assimp's own
// memory reader, which answers the OBJ reader's fallback name "<mesh>.mtl" with the OBJ's bytes).
class MeshFiles : public Assimp::IOSystem {
 public:
  MeshFiles(std::string main, const void* data, std::size_t size, std::filesystem::path folder, std::size_t max_bytes)
      : main_(std::move(main)), data_(static_cast<const std::uint8_t*>(data)), size_(size), folder_(std::move(folder)),
        max_bytes_(max_bytes) {}

  bool Exists(const char* file) const override { return file != nullptr && (main_ == file || !beside(file).empty()); }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (file == nullptr || std::strpbrk(mode, "wa+") != nullptr) return nullptr;
    if (main_ == file) return new Assimp::MemoryIOStream(data_, size_);
    const std::string path = beside(file);
    return path.empty() ? nullptr : files_.Open(path.c_str(), mode);
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }

 private:
  std::string beside(const char* file) const {
    const std::filesystem::path name(file);
    std::string extension = name.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (folder_.empty() || extension == ".mtl") return {};
    std::error_code ec;
    const std::filesystem::path path = folder_ / name;  // an absolute name stays as it is
    if (!std::filesystem::is_regular_file(path, ec)) return {};
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    return ec || size > max_bytes_ ? std::string() : path.string();
  }
  std::string main_;
  const std::uint8_t* data_;
  std::size_t size_;
  std::filesystem::path folder_;
  std::size_t max_bytes_;
  Assimp::DefaultIOSystem files_;
};

// An importer with only the reader for `format`: whatever the bytes are, no other of Assimp's
// parsers (some 40 formats) sees them, and Assimp never guesses the format from the contents.
std::unique_ptr<Assimp::Importer> importerFor(const Format& format, const std::string& source) {
  auto importer = std::make_unique<Assimp::Importer>();
  for (std::size_t i = importer->GetImporterCount(); i-- > 0;) {
    const aiImporterDesc* info = importer->GetImporterInfo(i);
    if (info != nullptr && std::strcmp(info->mName, format.reader) == 0) continue;
    std::unique_ptr<Assimp::BaseImporter> reader(importer->GetImporter(i));  // unregistering does not delete
    importer->UnregisterLoader(reader.get());
  }
  if (importer->GetImporterCount() != 1) {
    refuse(Error::Kind::Config, source, std::string("this build of Assimp has no ") + format.name + " reader");
  }
  return importer;
}

// Each mesh's primitive types as its faces have them. Assimp's readers declare them, and its
// post-processing trusts the declaration with assertions that abort the process (this build of
// Assimp keeps them): the first short fuzzing run stopped in TriangulateProcess ("numOut !=
// pMesh->mNumFaces") on a PLY face of no corners, which validation lets through when the reader
// declares no types. Such a face is refused here.
void declarePrimitiveTypes(const aiScene& scene, const std::string& source) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    aiMesh& part = *scene.mMeshes[m];  // the meshes are the importer's to change: only the scene is const
    unsigned types = 0;
    for (unsigned f = 0; f < part.mNumFaces; ++f) {
      const unsigned n = part.mFaces[f].mNumIndices;
      if (n == 0) {
        refuse(Error::Kind::Config, source, "face " + std::to_string(f) + " of part " + std::to_string(m) +
                                                " has no vertices; expected at least one");
      }
      types |= n == 1   ? aiPrimitiveType_POINT
               : n == 2 ? aiPrimitiveType_LINE
               : n == 3 ? aiPrimitiveType_TRIANGLE
                        : aiPrimitiveType_POLYGON;
    }
    part.mPrimitiveTypes = types;
  }
}

void checkOptions(const ImportOptions& o, const std::string& source) {
  if (!(std::isfinite(o.unit_m) && o.unit_m > 0.0)) {
    refuse(Error::Kind::Config, source, "unit_m = " + numberText(o.unit_m) + "; expected metres per file unit > 0");
  }
  if (o.projection != UvProjection::None && !(std::isfinite(o.tile_m) && o.tile_m > 0.0)) {
    refuse(Error::Kind::Config, source, "tile_m = " + numberText(o.tile_m) + "; expected metres per texture tile > 0");
  }
}

struct Copied {
  TexturedMesh mesh;
  bool project = false;  // the file has no texture coordinates: they are zero until projected
};

// The triangles of every mesh of the flattened scene, scaled to metres. Texture coordinates are
// channel 0's when every part has them, otherwise zero (for a projection) or a refusal.
Copied copyTriangles(const aiScene& scene, const std::string& source, const ImportOptions& o) {
  std::size_t triangles = 0, vertices = 0, without_uv = 0, parts = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh* part = scene.mMeshes[m];
    if (!(part->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;  // points and lines (SortByPType)
    triangles += part->mNumFaces;
    vertices += part->mNumVertices;
    ++parts;
    if (!part->HasTextureCoords(0)) ++without_uv;
  }
  if (triangles == 0) {
    refuse(Error::Kind::Config, source, "no triangles (only points, lines or nothing); expected a triangle mesh");
  }
  if (triangles > o.limits.max_triangles) {
    refuse(Error::Kind::Config, source, std::to_string(triangles) + " triangles, more than the limit of " +
                                            std::to_string(o.limits.max_triangles) + " (max_triangles)");
  }
  if (vertices > std::numeric_limits<std::uint32_t>::max()) {
    refuse(Error::Kind::Config, source, std::to_string(vertices) + " vertices; expected fewer than 2^32");
  }
  if (without_uv > 0 && o.projection == UvProjection::None) {
    const std::string which = without_uv == parts ? "no texture coordinates"
                                                  : "no texture coordinates on " + std::to_string(without_uv) + " of its " +
                                                        std::to_string(parts) + " parts";
    refuse(Error::Kind::Config, source,
           which + "; give a projection (planar, cylindrical, spherical) or a file with texture coordinates");
  }
  const bool file_uv = without_uv == 0;

  Copied out;
  out.project = !file_uv;
  TexturedMesh& mesh = out.mesh;
  mesh.source = source;
  mesh.positions.reserve(vertices);
  mesh.uvs.reserve(vertices);
  mesh.triangles.reserve(triangles);
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh* part = scene.mMeshes[m];
    if (!(part->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const auto offset = std::uint32_t(mesh.positions.size());
    for (unsigned v = 0; v < part->mNumVertices; ++v) {
      const aiVector3D& p = part->mVertices[v];
      mesh.positions.emplace_back(double(p.x) * o.unit_m, double(p.y) * o.unit_m, double(p.z) * o.unit_m);
      mesh.uvs.emplace_back(file_uv ? Eigen::Vector2d(part->mTextureCoords[0][v].x, part->mTextureCoords[0][v].y)
                                    : Eigen::Vector2d::Zero());
    }
    for (unsigned f = 0; f < part->mNumFaces; ++f) {
      const aiFace& face = part->mFaces[f];
      if (face.mNumIndices != 3) continue;  // SortByPType leaves none; a guard, not a case
      mesh.triangles.push_back({offset + face.mIndices[0], offset + face.mIndices[1], offset + face.mIndices[2]});
    }
  }
  return out;
}

// Texture coordinates from the positions (metres): planar (x, y) / tile; cylindrical about the z
// axis, u the angle from +x times the mean distance of the vertices from the axis, v = z; spherical
// about the origin, u the longitude and v the latitude, each times the mean distance of the vertices
// from the origin. All divided by tile_m. Around the axis u jumps by 2 pi r / tile_m where the
// angle wraps; a triangle across that line gets its own copies of the vertices on the far side,
// moved by one turn, so no triangle spans the whole texture backwards, and a corner on the axis
// (a pole) takes the mean u of the triangle's other corners. The texture meets itself across the
// line only if 2 pi r / tile_m is a whole number of tiles.
void project(TexturedMesh& mesh, UvProjection projection, double tile_m) {
  const std::size_t nv = mesh.positions.size();
  std::vector<Eigen::Vector2d> base(nv);
  if (projection == UvProjection::Planar) {
    for (std::size_t v = 0; v < nv; ++v) base[v] = mesh.positions[v].head<2>() / tile_m;
    mesh.uvs = std::move(base);
    return;
  }
  const bool cylinder = projection == UvProjection::Cylindrical;
  double radius = 0.0, max_axis_distance = 0.0;
  for (const Eigen::Vector3d& p : mesh.positions) {
    radius += (cylinder ? p.head<2>().norm() : p.norm()) / double(nv);
    max_axis_distance = std::max(max_axis_distance, p.head<2>().norm());
  }
  const double turn = 2.0 * M_PI * radius / tile_m;
  std::vector<bool> on_axis(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    const Eigen::Vector3d& p = mesh.positions[v];
    const double rho = p.head<2>().norm();
    on_axis[v] = rho <= 1e-9 * max_axis_distance;
    const double along = cylinder ? p.z() : std::atan2(p.z(), rho) * radius;
    base[v] = {on_axis[v] ? 0.0 : std::atan2(p.y(), p.x()) * radius / tile_m, along / tile_m};
  }

  // Every corner's coordinates, then one vertex per distinct (vertex, u).
  struct Key {
    std::uint32_t vertex;
    double u;
    bool operator==(const Key& k) const { return vertex == k.vertex && u == k.u; }
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t bits;
      std::memcpy(&bits, &k.u, sizeof bits);
      return std::hash<std::uint64_t>()(bits * 0x9e3779b97f4a7c15ull ^ k.vertex);
    }
  };
  std::unordered_map<Key, std::uint32_t, KeyHash> index_of;
  index_of.reserve(nv);
  std::vector<Eigen::Vector3d> positions;
  std::vector<Eigen::Vector2d> uvs;
  positions.reserve(nv);
  uvs.reserve(nv);
  for (Triangle& tri : mesh.triangles) {
    std::array<double, 3> u{};
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t k = 0; k < 3; ++k) {
      u[k] = base[tri[k]].x();
      if (!on_axis[tri[k]]) lo = std::min(lo, u[k]), hi = std::max(hi, u[k]);
    }
    if (hi - lo > 0.5 * turn) {  // across the wrap: the corners on the negative side move one turn up
      for (std::size_t k = 0; k < 3; ++k)
        if (!on_axis[tri[k]] && u[k] < 0.0) u[k] += turn;
    }
    double sum = 0.0;
    int off_axis = 0;
    for (std::size_t k = 0; k < 3; ++k)
      if (!on_axis[tri[k]]) sum += u[k], ++off_axis;
    for (std::size_t k = 0; k < 3; ++k) {
      if (on_axis[tri[k]] && off_axis > 0) u[k] = sum / off_axis;
      const auto [it, added] = index_of.try_emplace(Key{tri[k], u[k]}, std::uint32_t(positions.size()));
      if (added) {
        positions.push_back(mesh.positions[tri[k]]);
        uvs.emplace_back(u[k], base[tri[k]].y());
      }
      tri[k] = it->second;
    }
  }
  mesh.positions = std::move(positions);
  mesh.uvs = std::move(uvs);
}

TexturedMesh importBytes(const void* data, std::size_t size, const Format& format, const std::string& source,
                         const std::filesystem::path& folder, const ImportOptions& options) {
  checkOptions(options, source);
  if (size > options.max_file_bytes) {
    refuse(Error::Kind::Io, source, std::to_string(size) + " bytes, more than the limit of " +
                                        std::to_string(options.max_file_bytes) + " (max_file_bytes)");
  }
  if (size == 0) refuse(Error::Kind::Config, source, std::string("empty file; expected a mesh in ") + format.name);

  std::vector<std::uint8_t> rewritten;
  if (format.hint == "ply") {
    rewritten = ply::rewrite(std::string_view(static_cast<const char*>(data), size), source);
    data = rewritten.data();
    size = rewritten.size();
  }

  const std::unique_ptr<Assimp::Importer> importer = importerFor(format, source);
  // Our own file system rather than ReadFileFromMemory's, whose reader of the bytes also answers
  // any name that starts like its own (MeshFiles).
  const std::string main = "mesh." + format.hint;
  importer->SetIOHandler(new MeshFiles(main, data, size, folder, options.max_file_bytes));  // the importer owns it
  // Read and validated first, post-processed after our repair of what the readers declare.
  const aiScene* scene = importer->ReadFile(main, aiProcess_ValidateDataStructure);
  if (scene != nullptr) {
    declarePrimitiveTypes(*scene, source);
    // No aiProcess_GenNormals or CalcTangentSpace: buildVertexFrames makes the frames. DropNormals
    // lets JoinIdenticalVertices join an STL's corners, which carry their facet's normal.
    constexpr unsigned kSteps = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices |
                                aiProcess_SortByPType | aiProcess_DropNormals;
    scene = importer->ApplyPostProcessing(kSteps);
  }
  if (scene == nullptr) {
    std::string why = importer->GetErrorString();  // it may name the bytes by our name for them
    for (std::size_t at; (at = why.find(main)) != std::string::npos;) why.replace(at, main.size(), "the file");
    refuse(Error::Kind::Config, source,
           std::string("Assimp could not read it as ") + format.name + ": " + ply::shown(why, 300));
  }

  Copied copied = copyTriangles(*scene, source, options);
  importer->FreeScene();
  TexturedMesh& mesh = copied.mesh;
  checkMesh(mesh, options.limits);  // before anything reads a position: finite, indices in range
  if (copied.project) {
    project(mesh, options.projection, options.tile_m);
    checkMesh(mesh, options.limits);
  }
  buildVertexFrames(mesh);
  return std::move(mesh);
}

}  // namespace

TexturedMesh importMeshFromMemory(const void* data, std::size_t size, const std::string& format_hint,
                                  const std::string& source, const ImportOptions& options) {
  return importBytes(data, size, formatOf(format_hint, source), source, {}, options);
}

TexturedMesh importMesh(const std::string& path, const ImportOptions& options) {
  const std::filesystem::path file(path);
  std::string extension = file.extension().string();
  if (!extension.empty()) extension.erase(0, 1);
  const Format format = formatOf(extension, path);
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (!std::filesystem::exists(status)) refuse(Error::Kind::Io, path, "cannot open: no such file");
  if (!std::filesystem::is_regular_file(status)) refuse(Error::Kind::Io, path, "cannot read: not a regular file");
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (ec) refuse(Error::Kind::Io, path, "cannot read: " + ec.message());
  if (size > options.max_file_bytes) {  // before reading it
    refuse(Error::Kind::Io, path, std::to_string(size) + " bytes, more than the limit of " +
                                      std::to_string(options.max_file_bytes) + " (max_file_bytes)");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) refuse(Error::Kind::Io, path, "cannot open: " + std::string(std::strerror(errno)));
  std::vector<char> bytes(static_cast<std::size_t>(size));
  if (!in.read(bytes.data(), std::streamsize(bytes.size()))) refuse(Error::Kind::Io, path, "cannot read all of its bytes");
  const std::filesystem::path folder = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
  return importBytes(bytes.data(), bytes.size(), format, path, folder, options);
}

UvProjection parseUvProjection(const std::string& text) {
  if (text == "none") return UvProjection::None;
  if (text == "planar") return UvProjection::Planar;
  if (text == "cylindrical") return UvProjection::Cylindrical;
  if (text == "spherical") return UvProjection::Spherical;
  throw Error(Error::Kind::Config,
              "uv projection '" + ply::shown(text) + "': expected none, planar, cylindrical or spherical");
}

}  // namespace thx::mesh
