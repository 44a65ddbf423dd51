// importMesh / importMeshFromMemory (meshes/mesh_import.hpp): the small files of
// tests/data/meshes/ in each format, units, projections, files beside a .gltf, and each refusal
// with its message. The bounds on what a file can make the import allocate are tested with the
// fuzz target (tests/fuzz/test_fuzz_mesh_import.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <set>
#include <sstream>

#include "base/error.hpp"
#include "meshes/mesh_check.hpp"
#include "meshes/mesh_import.hpp"
#include "tests/support/temp_dir.hpp"

namespace test_mesh_import {

using namespace thx;
using namespace thx::mesh;

namespace {

const std::string kDir = std::string(THX_TEST_DATA_DIR) + "/meshes/";

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TexturedMesh fromText(const std::string& text, const std::string& hint, const ImportOptions& options = {}) {
  return importMeshFromMemory(text.data(), text.size(), hint, "memory." + hint, options);
}

// "Config: <message>", "Io: <message>" or "accepted".
std::string verdict(const std::function<TexturedMesh()>& import) {
  try {
    import();
    return "accepted";
  } catch (const Error& e) {
    return std::string(e.kind() == Error::Kind::Io ? "Io: " : e.kind() == Error::Kind::Config ? "Config: " : "Usage: ") +
           e.what();
  }
}

std::string fileVerdict(const std::string& path, const ImportOptions& options = {}) {
  return verdict([&] { return importMesh(path, options); });
}

bool startsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

void expectBounds(const TexturedMesh& m, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  Eigen::Vector3d a = m.positions[0], b = m.positions[0];
  for (const Eigen::Vector3d& p : m.positions) a = a.cwiseMin(p), b = b.cwiseMax(p);
  EXPECT_TRUE(a.isApprox(lo, 1e-12) && b.isApprox(hi, 1e-12)) << a.transpose() << " / " << b.transpose();
}

// The cube of cube.obj and cube.ply: side 2 file units, one tile per face; on the top face
// (z = 1) u = (x + 1) / 2 and v = (y + 1) / 2.
void expectCube(const TexturedMesh& m, double unit_m) {
  ASSERT_EQ(m.triangles.size(), 12u);
  ASSERT_TRUE(m.hasFrames());
  expectBounds(m, Eigen::Vector3d::Constant(-unit_m), Eigen::Vector3d::Constant(unit_m));
  std::set<std::array<double, 5>> corners;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const Eigen::Vector3d& p = m.positions[v];
    const Eigen::Vector2d& t = m.uvs[v];
    corners.insert({p.x(), p.y(), p.z(), t.x(), t.y()});
    EXPECT_TRUE((t.x() == 0 || t.x() == 1) && (t.y() == 0 || t.y() == 1)) << t.transpose();
  }
  EXPECT_EQ(corners.size(), 20u);  // 24 face corners, 4 of which share position and uv with another
  int top = 0;
  for (const Triangle& tri : m.triangles) {
    if (m.positions[tri[0]].z() < unit_m || m.positions[tri[1]].z() < unit_m || m.positions[tri[2]].z() < unit_m) continue;
    ++top;
    for (std::uint32_t v : tri) {
      EXPECT_EQ(m.uvs[v], Eigen::Vector2d((m.positions[v].x() / unit_m + 1) / 2, (m.positions[v].y() / unit_m + 1) / 2));
      EXPECT_TRUE(m.normals[v].isApprox(Eigen::Vector3d::UnitZ()));  // faces outward, the box's edges kept hard
    }
  }
  EXPECT_EQ(top, 2);
  MeshLimits closed;
  closed.require_closed = true;
  EXPECT_NO_THROW(checkMesh(m, closed));
}

// The tetrahedron of tetra.gltf under its node (scale 2, then +1 along z).
void expectTetrahedron(const TexturedMesh& m) {
  ASSERT_EQ(m.triangles.size(), 4u);
  expectBounds(m, {-2, -2, -1}, {2, 2, 3});
  // glTF's texture coordinates have v down from the top; Assimp gives v up, as OBJ and PLY have
  // it: the corner with (0, 0) in the file reads (0, 1).
  int found = 0;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    if (m.positions[v] == Eigen::Vector3d(2, 2, 3)) {
      EXPECT_EQ(m.uvs[v], Eigen::Vector2d(0, 1));
      ++found;
    }
  }
  EXPECT_GE(found, 1);
  MeshLimits closed;
  closed.require_closed = true;
  EXPECT_NO_THROW(checkMesh(m, closed));
}

std::string decodeBase64(const std::string& text) {
  std::string out;
  int bits = 0;
  std::uint32_t acc = 0;
  for (char c : text) {
    const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const char* at = std::strchr(digits, c);
    if (c == '=' || at == nullptr) break;
    acc = acc << 6 | std::uint32_t(at - digits);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += char((acc >> bits) & 0xff);
    }
  }
  return out;
}

// tetra.gltf split into its JSON without the buffer's data URI, and the buffer's bytes.
std::pair<std::string, std::string> splitGltf() {
  std::string json = readText(kDir + "tetra.gltf");
  const std::size_t uri = json.find("\"uri\"");
  const std::size_t data = json.find("base64,", uri) + 7;
  const std::size_t end = json.find('"', data);
  const std::string buffer = decodeBase64(json.substr(data, end - data));
  const std::size_t comma = json.rfind(',', uri);
  json.erase(comma, end + 1 - comma);
  return {json, buffer};
}

// A binary glTF (.glb): header, JSON chunk, BIN chunk, each chunk padded to 4 bytes.
std::string glbOf(std::string json, std::string bin) {
  json.resize((json.size() + 3) / 4 * 4, ' ');
  bin.resize((bin.size() + 3) / 4 * 4, '\0');
  std::string out;
  const auto u32 = [&](std::uint32_t v) {
    for (int k = 0; k < 4; ++k) out += char(v >> (8 * k));
  };
  out += "glTF";
  u32(2);
  u32(std::uint32_t(12 + 8 + json.size() + 8 + bin.size()));
  u32(std::uint32_t(json.size()));
  out += "JSON" + json;
  u32(std::uint32_t(bin.size()));
  out += std::string("BIN\0", 4) + bin;
  return out;
}

// A closed tube about z without texture coordinates (n segments, closed by two fans at the ends
// around centre vertices on the axis), as OBJ text.
std::string capsuleObj(int n, double radius, double height) {
  std::ostringstream obj;
  obj.precision(17);
  for (int ring = 0; ring < 2; ++ring)
    for (int k = 0; k < n; ++k)
      obj << "v " << radius * std::cos(2 * M_PI * k / n) << " " << radius * std::sin(2 * M_PI * k / n) << " "
          << height * ring << "\n";
  obj << "v 0 0 0\nv 0 0 " << height << "\n";
  for (int k = 0; k < n; ++k) {
    const int a = 1 + k, b = 1 + (k + 1) % n, c = a + n, d = b + n;
    obj << "f " << a << " " << b << " " << d << " " << c << "\n";
    obj << "f " << b << " " << a << " " << 2 * n + 1 << "\n";
    obj << "f " << c << " " << d << " " << 2 * n + 2 << "\n";
  }
  return obj.str();
}

// No triangle of a projected mesh spans more than half a turn of u, and a corner on the axis
// takes the mean u of the other two.
void expectUnwrapped(const TexturedMesh& m, double turn) {
  for (const Triangle& tri : m.triangles) {
    double lo = 1e300, hi = -1e300;
    for (std::uint32_t v : tri) lo = std::min(lo, m.uvs[v].x()), hi = std::max(hi, m.uvs[v].x());
    EXPECT_LT(hi - lo, 0.5 * turn);
    for (std::size_t k = 0; k < 3; ++k) {
      if (m.positions[tri[k]].head<2>().norm() > 0) continue;
      EXPECT_NEAR(m.uvs[tri[k]].x(), 0.5 * (m.uvs[tri[(k + 1) % 3]].x() + m.uvs[tri[(k + 2) % 3]].x()), 1e-12);
    }
  }
}

}  // namespace

TEST(MeshImport, ObjCube) {
  const TexturedMesh m = importMesh(kDir + "cube.obj");
  EXPECT_EQ(m.source, kDir + "cube.obj");
  expectCube(m, 1.0);
}

TEST(MeshImport, PlyCube) { expectCube(importMesh(kDir + "cube.ply"), 1.0); }

TEST(MeshImport, PlyTextureCoordinateNames) {
  // Assimp reads s/t, u/v and texture_u/texture_v (and tx/ty) as texture coordinates.
  for (const std::string names : {"u v", "texture_u texture_v"}) {
    const std::string u = names.substr(0, names.find(' ')), v = names.substr(names.find(' ') + 1);
    const std::string ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                            "property float z\nproperty float " + u + "\nproperty float " + v +
                            "\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                            "0 0 0 0.25 0.5\n1 0 0 0.75 0.5\n0 1 0 0.25 1\n3 0 1 2\n";
    const TexturedMesh m = fromText(ply, "ply");
    ASSERT_EQ(m.triangles.size(), 1u) << names;
    const Triangle& t = m.triangles[0];
    EXPECT_EQ(m.uvs[t[0]], Eigen::Vector2d(0.25, 0.5)) << names;
    EXPECT_EQ(m.uvs[t[1]], Eigen::Vector2d(0.75, 0.5)) << names;
    EXPECT_EQ(m.uvs[t[2]], Eigen::Vector2d(0.25, 1)) << names;
  }
}

TEST(MeshImport, BinaryPlyReadsAsItsAsciiTwin) {
  // cube.ply as binary little- and big-endian PLY: the same mesh.
  const TexturedMesh ascii = importMesh(kDir + "cube.ply");
  for (const bool big : {false, true}) {
    std::string text = readText(kDir + "cube.ply");
    std::istringstream lines(text.substr(text.find("end_header\n") + 11));
    std::string header = text.substr(0, text.find("end_header\n") + 11);
    header.replace(header.find("ascii"), 5, big ? "binary_big_endian" : "binary_little_endian");
    std::string body;
    const auto put = [&](const void* p, std::size_t n) {
      std::string b(static_cast<const char*>(p), n);
      if (big) std::reverse(b.begin(), b.end());
      body += b;
    };
    for (int v = 0; v < 24; ++v) {
      for (int k = 0; k < 5; ++k) {
        float f;
        lines >> f;
        put(&f, 4);
      }
    }
    for (int f = 0; f < 6; ++f) {
      int n, index;
      lines >> n;
      body += char(n);
      for (int k = 0; k < n; ++k) lines >> index, put(&index, 4);
    }
    const TexturedMesh m = fromText(header + body, "ply");
    EXPECT_EQ(m.positions, ascii.positions) << big;
    EXPECT_EQ(m.uvs, ascii.uvs) << big;
    EXPECT_EQ(m.triangles, ascii.triangles) << big;
  }
}

TEST(MeshImport, StlHasNoTextureCoordinatesButTakesAProjection) {
  const std::string path = kDir + "cube.stl";
  EXPECT_EQ(fileVerdict(path), "Config: mesh " + path + ": no texture coordinates; give a projection (planar, "
                                                         "cylindrical, spherical) or a file with texture coordinates");
  ImportOptions o;
  o.projection = UvProjection::Planar;
  o.tile_m = 0.5;
  const TexturedMesh m = importMesh(path, o);
  EXPECT_EQ(m.triangles.size(), 12u);
  expectBounds(m, Eigen::Vector3d::Constant(-1), Eigen::Vector3d::Constant(1));
  for (std::size_t v = 0; v < m.positions.size(); ++v) EXPECT_EQ(m.uvs[v], m.positions[v].head<2>() / 0.5);
  MeshLimits closed;
  closed.require_closed = true;
  EXPECT_NO_THROW(checkMesh(m, closed));
}

TEST(MeshImport, GltfWithItsNodeTransform) { expectTetrahedron(importMesh(kDir + "tetra.gltf")); }

TEST(MeshImport, BinaryGltf) {
  const auto [json, bin] = splitGltf();
  expectTetrahedron(fromText(glbOf(json, bin), "glb"));
  thx::test::TempDir dir("thx_mesh_import");
  writeText(dir.file("TETRA.GLB"), glbOf(json, bin));  // the extension in any case
  expectTetrahedron(importMesh(dir.file("TETRA.GLB")));
}

TEST(MeshImport, GltfBufferBesideTheFile) {
  auto [json, bin] = splitGltf();
  json.insert(json.find("\"byteLength\""), "\"uri\": \"tetra.bin\", ");
  thx::test::TempDir dir("thx_mesh_import");
  writeText(dir.file("tetra.gltf"), json);
  writeText(dir.file("tetra.bin"), bin);
  expectTetrahedron(importMesh(dir.file("tetra.gltf")));
  // Each file the mesh names is held to max_file_bytes too: a .bin one byte longer than the
  // .gltf (bytes past a buffer's byteLength are not read) makes the limit that passes the .gltf
  // refuse it.
  writeText(dir.file("tetra.bin"), bin + std::string(json.size() + 1 - bin.size(), '\0'));
  expectTetrahedron(importMesh(dir.file("tetra.gltf")));
  ImportOptions o;
  o.max_file_bytes = json.size();
  EXPECT_TRUE(startsWith(fileVerdict(dir.file("tetra.gltf"), o),
                         "Config: mesh " + dir.file("tetra.gltf") + ": Assimp could not read it as glTF 2.0: "))
      << fileVerdict(dir.file("tetra.gltf"), o);
  // From memory nothing is read from the file system.
  EXPECT_TRUE(startsWith(verdict([&text = json] { return fromText(text, "gltf"); }),
                         "Config: mesh memory.gltf: Assimp could not read it as glTF 2.0: "));
}

TEST(MeshImport, UnitScalesPositionsOnly) {
  ImportOptions o;
  o.unit_m = 0.001;
  expectCube(importMesh(kDir + "cube.obj", o), 0.001);
}

TEST(MeshImport, CylindricalProjection) {
  const int n = 12;
  const double r = 0.02, tile = 0.01;
  ImportOptions o;
  o.projection = UvProjection::Cylindrical;
  o.tile_m = tile;
  const TexturedMesh m = fromText(capsuleObj(n, r, 0.03), "obj", o);
  ASSERT_EQ(m.triangles.size(), std::size_t(4 * n));
  // The mean distance from the axis: 2n vertices at r, two centres at 0 (r as the float Assimp
  // reads it: the turns below are whole to float precision).
  const double radius = r * 2 * n / (2 * n + 2), turn = 2 * M_PI * radius / tile;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const Eigen::Vector3d& p = m.positions[v];
    EXPECT_NEAR(m.uvs[v].y(), p.z() / tile, 1e-12);
    if (p.head<2>().norm() == 0) continue;
    const double turns = (m.uvs[v].x() - std::atan2(p.y(), p.x()) * radius / tile) / turn;
    EXPECT_NEAR(turns, std::round(turns), 1e-6);
  }
  expectUnwrapped(m, turn);
}

TEST(MeshImport, SphericalProjection) {
  // An octahedron of radius 0.05 without texture coordinates: v is the latitude's arc length.
  const std::string obj = "v 0.05 0 0\nv 0 0.05 0\nv -0.05 0 0\nv 0 -0.05 0\nv 0 0 0.05\nv 0 0 -0.05\n"
                          "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 2 1 6\nf 3 2 6\nf 4 3 6\nf 1 4 6\n";
  ImportOptions o;
  o.projection = UvProjection::Spherical;
  o.tile_m = 0.01;
  const TexturedMesh m = fromText(obj, "obj", o);
  ASSERT_EQ(m.triangles.size(), 8u);
  const double radius = m.positions[0].norm();  // 0.05 as a float
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const Eigen::Vector3d& p = m.positions[v];
    EXPECT_NEAR(m.uvs[v].y(), std::atan2(p.z(), p.head<2>().norm()) * radius / 0.01, 1e-12);
  }
  expectUnwrapped(m, 2 * M_PI * 0.05 / 0.01);
}

TEST(MeshImport, MissingFile) {
  EXPECT_EQ(fileVerdict(kDir + "none.obj"), "Io: mesh " + kDir + "none.obj: cannot open: no such file");
  EXPECT_EQ(fileVerdict(kDir), "Config: mesh " + kDir + ": no file extension to tell the format; expected one of OBJ, "
                                                         "PLY, glTF 2.0, STL (.obj, .ply, .gltf, .glb, .stl)");
  thx::test::TempDir dir("thx_mesh_import");
  std::filesystem::create_directory(dir.file("folder.obj"));
  EXPECT_EQ(fileVerdict(dir.file("folder.obj")), "Io: mesh " + dir.file("folder.obj") + ": cannot read: not a regular file");
}

TEST(MeshImport, UnknownFormat) {
  thx::test::TempDir dir("thx_mesh_import");
  writeText(dir.file("cube.dae"), readText(kDir + "cube.obj"));
  EXPECT_EQ(fileVerdict(dir.file("cube.dae")), "Config: mesh " + dir.file("cube.dae") +
                                                   ": unknown mesh format '.dae'; expected one of OBJ, PLY, glTF 2.0, "
                                                   "STL (.obj, .ply, .gltf, .glb, .stl)");
  EXPECT_EQ(verdict([] { return fromText("v 0 0 0\n", "fbx"); }),
            "Config: mesh memory.fbx: unknown mesh format '.fbx'; expected one of OBJ, PLY, glTF 2.0, STL (.obj, .ply, "
            ".gltf, .glb, .stl)");
  // A file of one format named as another is read as the format its name says, and refused.
  EXPECT_TRUE(startsWith(verdict([] { return fromText(readText(kDir + "cube.ply"), "obj"); }),
                         "Config: mesh memory.obj: Assimp could not read it as OBJ: "));
}

TEST(MeshImport, TooManyTriangles) {
  ImportOptions o;
  o.limits.max_triangles = 11;
  EXPECT_EQ(fileVerdict(kDir + "cube.obj", o),
            "Config: mesh " + kDir + "cube.obj: 12 triangles, more than the limit of 11 (max_triangles)");
}

TEST(MeshImport, FileLargerThanTheLimit) {
  ImportOptions o;
  o.max_file_bytes = 100;
  const std::string path = kDir + "cube.obj";
  EXPECT_EQ(fileVerdict(path, o), "Io: mesh " + path + ": " + std::to_string(std::filesystem::file_size(path)) +
                                      " bytes, more than the limit of 100 (max_file_bytes)");
}

TEST(MeshImport, NonFiniteCoordinates) {
  EXPECT_EQ(fileVerdict(kDir + "nan_vertex.obj"),
            "Config: mesh " + kDir + "nan_vertex.obj: vertex 2 has a non-finite position (nan, 1, 0); expected finite "
                                     "coordinates");
  // 1e39 is beyond a float, which Assimp reads coordinates into: an infinity.
  EXPECT_EQ(verdict([] { return fromText("v 0 0 0\nv 1e39 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n", "obj"); }),
            "Config: mesh memory.obj: vertex 1 has a non-finite position (inf, 0, 0); expected finite coordinates");
}

TEST(MeshImport, InconsistentWinding) {
  const std::string v = fileVerdict(kDir + "flipped_face.obj");
  EXPECT_TRUE(startsWith(v, "Config: mesh " + kDir + "flipped_face.obj: triangles ")) << v;
  EXPECT_NE(v.find(": inconsistent winding; expected neighbouring triangles to run a shared edge in opposite "
                   "directions (counter-clockwise seen from outside)"),
            std::string::npos)
      << v;
}

TEST(MeshImport, NoTriangles) {
  EXPECT_EQ(fileVerdict(kDir + "lines_only.obj"),
            "Config: mesh " + kDir + "lines_only.obj: no triangles (only points, lines or nothing); expected a triangle mesh");
  EXPECT_EQ(verdict([] { return fromText("", "obj"); }), "Config: mesh memory.obj: empty file; expected a mesh in OBJ");
}

TEST(MeshImport, BadOptions) {
  ImportOptions o;
  o.unit_m = 0;
  EXPECT_EQ(fileVerdict(kDir + "cube.obj", o), "Config: mesh " + kDir + "cube.obj: unit_m = 0; expected metres per file unit > 0");
  o = {};
  o.projection = UvProjection::Planar;
  o.tile_m = -1;
  EXPECT_EQ(fileVerdict(kDir + "cube.stl", o), "Config: mesh " + kDir + "cube.stl: tile_m = -1; expected metres per texture tile > 0");
}

TEST(MeshImport, ParseUvProjection) {
  EXPECT_EQ(parseUvProjection("none"), UvProjection::None);
  EXPECT_EQ(parseUvProjection("planar"), UvProjection::Planar);
  EXPECT_EQ(parseUvProjection("cylindrical"), UvProjection::Cylindrical);
  EXPECT_EQ(parseUvProjection("spherical"), UvProjection::Spherical);
  try {
    parseUvProjection("cubic");
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::Config);
    EXPECT_STREQ(e.what(), "uv projection 'cubic': expected none, planar, cylindrical or spherical");
  }
}

TEST(MeshImport, AssimpPrintsNothing) {
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  for (const char* file : {"cube.obj", "cube.ply", "cube.stl", "tetra.gltf", "nan_vertex.obj", "lines_only.obj"})
    fileVerdict(kDir + file);
  verdict([] { return fromText("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\nx\n", "ply"); });
  verdict([] { return fromText("{\"asset\": {\"version\": \"1.0\"}}", "gltf"); });
  verdict([] { return fromText("solid x\nfacet\n", "stl"); });
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

}  // namespace test_mesh_import
