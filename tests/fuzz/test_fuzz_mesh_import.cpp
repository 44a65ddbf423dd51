// Mesh files (OBJ, PLY, STL and glTF 2.0 through Assimp): the fuzz body's seeds and short run
// (mesh_import_body.hpp), and the bounds on what a file's numbers can make the import allocate.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>

#include "tests/fuzz/mesh_import_body.hpp"
#include "tests/fuzz/seed_writer.hpp"
#include "tests/fuzz/short_run.hpp"
#include "tests/support/temp_dir.hpp"

// Assimp 5.2.5's OBJ reader leaks the meshes it has built when a later part of the file makes it
// throw (ObjFileImporter::CreateNodes keeps them in a local array of raw pointers): about 1.4 KB
// per part of such a refused file, found by a libFuzzer run (a group of faces, then a face with
// an index out of range). It is Assimp's, so LeakSanitizer is told to ignore leaks it allocated;
// the sanitizer half of `make test` would otherwise fail whenever the short run's inputs include
// such a file. Only this executable has the function; it does nothing outside the sanitizer tree.
extern "C" const char* __lsan_default_suppressions();
extern "C" const char* __lsan_default_suppressions() { return "leak:libassimp.so\n"; }

namespace test_fuzz_mesh_import {

using namespace thx;
using namespace thx::fuzz;

namespace {

const std::string kTarget = "mesh_import";

Bytes withMode(std::uint8_t mode, const std::string& file) {
  Bytes b{mode};
  b.insert(b.end(), file.begin(), file.end());
  return b;
}

std::string dataFile(const std::string& name) {
  const Bytes b = readBytes(std::filesystem::path(THX_TEST_DATA_DIR) / "meshes" / name);
  return std::string(b.begin(), b.end());
}

// The test files of tests/data/meshes/ in OBJ, PLY, STL and glTF (mode 0: OBJ, 1: PLY, 8: STL,
// 9: glTF; +2: planar projection, +4: closed), one without texture coordinates, and a binary PLY.
std::vector<std::pair<std::string, Bytes>> seeds() {
  const std::string cube_ply = dataFile("cube.ply");
  std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                       "property float z\nproperty float s\nproperty float t\nelement face 1\n"
                       "property list uchar uint vertex_indices\nend_header\n";
  const float v[15] = {0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  binary.append(reinterpret_cast<const char*>(v), sizeof v);
  const std::uint32_t f[3] = {0, 1, 2};
  binary += char(3);
  binary.append(reinterpret_cast<const char*>(f), sizeof f);
  return {{"obj_cube", withMode(4, dataFile("cube.obj"))},
          {"obj_flipped_face", withMode(0, dataFile("flipped_face.obj"))},
          {"obj_nan_vertex", withMode(0, dataFile("nan_vertex.obj"))},
          {"obj_lines_only", withMode(0, dataFile("lines_only.obj"))},
          {"obj_no_uv_planar", withMode(2, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n")},
          {"ply_cube", withMode(5, cube_ply)},
          {"ply_binary_triangle", withMode(1, binary)},
          {"stl_cube_planar", withMode(8 | 2 | 4, dataFile("cube.stl"))},
          {"gltf_tetra", withMode(9 | 4, dataFile("tetra.gltf"))}};
}

// What the import says about `text` read as `hint`: "accepted" or the error's message.
std::string verdict(const std::string& text, const std::string& hint, const mesh::ImportOptions& options = {}) {
  try {
    mesh::importMeshFromMemory(text.data(), text.size(), hint, "x." + hint, options);
    return "accepted";
  } catch (const Error& e) {
    return e.what();
  }
}

const std::string kPlyHead = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\nproperty float s\nproperty float t\n";
const std::string kVertices = "0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n";

}  // namespace

TEST(FuzzMeshImport, WriteSeedCorpusWhenAsked) { writeSeedsWhenAsked(seeds()); }

TEST(FuzzMeshImport, CheckedInSeedsAreTheGeneratedOnes) {
  const std::vector<Bytes> corpus = loadCorpus(kTarget);
  for (const auto& [name, bytes] : seeds())
    EXPECT_NE(std::find(corpus.begin(), corpus.end(), bytes), corpus.end()) << name << " missing from the corpus";
}

TEST(FuzzMeshImport, SeedsHoldTheProperties) { expectSeedsHold(kTarget, &fuzzMeshImportOnce); }

TEST(FuzzMeshImport, CorpusReachesEveryReaderAndTheFrames) {
  // Guards the corpus's value: OBJ, PLY (ASCII and binary), STL and glTF seeds that import whole,
  // so mutations start past the readers, in the check and the frames.
  std::map<std::string, int> whole;
  for (const Bytes& seed : loadCorpus(kTarget)) {
    mesh::ImportOptions o;
    if (seed[0] & 2) o.projection = mesh::UvProjection::Planar;
    try {
      mesh::importMeshFromMemory(seed.data() + 1, seed.size() - 1, meshFuzzFormat(seed[0]), "seed", o);
      ++whole[meshFuzzFormat(seed[0])];
    } catch (const Error&) {  // the seeds of refusals
    }
  }
  EXPECT_EQ(whole["obj"], 2);
  EXPECT_EQ(whole["ply"], 2);
  EXPECT_EQ(whole["stl"], 1);
  EXPECT_EQ(whole["gltf"], 1);
}

TEST(FuzzMeshImport, ShortRun) { shortRun(kTarget, &fuzzMeshImportOnce, 300); }

TEST(FuzzMeshImport, RefusesFilesAboveMaxFileBytes) {
  const std::string obj = dataFile("cube.obj");
  mesh::ImportOptions o;
  o.max_file_bytes = obj.size() - 1;
  EXPECT_EQ(verdict(obj, "obj", o), "mesh x.obj: " + std::to_string(obj.size()) + " bytes, more than the limit of " +
                                        std::to_string(obj.size() - 1) + " (max_file_bytes)");
  o.max_file_bytes = obj.size();
  EXPECT_EQ(verdict(obj, "obj", o), "accepted");
}

TEST(FuzzMeshImport, RefusesTrianglesAboveTheLimitBeforeCopying) {
  mesh::ImportOptions o;
  o.limits.max_triangles = 11;
  EXPECT_EQ(verdict(dataFile("cube.obj"), "obj", o), "mesh x.obj: 12 triangles, more than the limit of 11 (max_triangles)");
}

TEST(FuzzMeshImport, RefusesPlyElementCountsTheDataCannotHold) {
  // Assimp 5.2.5 allocates an element's instances from its count before reading them: this
  // 200-byte file made it take 24 GB. Refused from the data present, before Assimp runs.
  const std::string ascii = "ply\nformat ascii 1.0\nelement vertex 2000000000\nproperty float x\nproperty float y\n"
                            "property float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_EQ(verdict(ascii, "ply"), "mesh x.ply: PLY data ends in element 'vertex' (instance 3 of 2000000000); expected "
                                   "the values the header declares");
  std::string binary = ascii;
  binary.replace(binary.find("ascii"), 5, "binary_little_endian");
  binary.resize(binary.find("end_header\n") + 11 + 36, '\0');
  EXPECT_EQ(verdict(binary, "ply"), "mesh x.ply: PLY data ends in element 'vertex' (instance 3 of 2000000000, byte 36 of "
                                    "the data); expected the values the header declares");
  EXPECT_EQ(verdict("ply\nformat ascii 1.0\nelement vertex 4294967296\nproperty float x\nend_header\n", "ply"),
            "mesh x.ply: PLY header line 3 ('element vertex 4294967296'): expected 'element NAME COUNT' with COUNT a "
            "whole number below 2^32");
  EXPECT_EQ(verdict("ply\nformat ascii 1.0\nelement vertex 4000000000\nend_header\n", "ply"),
            "mesh x.ply: PLY element 'vertex' has instances but no properties");
}

TEST(FuzzMeshImport, RefusesPlyListCountsTheDataCannotHold) {
  // Assimp sizes a list from its count before reading the values; an ASCII count is read as a
  // 32-bit number whatever its type (-1 as 4294967295): 32 GB for one face.
  const std::string face = "element face 1\nproperty list uint int vertex_indices\nend_header\n";
  EXPECT_EQ(verdict(kPlyHead + face + kVertices + "4294967295 0 1 2\n", "ply"),
            "mesh x.ply: PLY data ends in element 'face' (instance 0 of 1); expected the values the header declares");
  const std::string signed_face = "element face 1\nproperty list int int vertex_indices\nend_header\n";
  EXPECT_EQ(verdict(kPlyHead + signed_face + kVertices + "-1 0 1 2\n", "ply"),
            "mesh x.ply: PLY list 'vertex_indices' in element 'face' (instance 0) has a negative count");
  EXPECT_EQ(verdict(kPlyHead + "element face 1\nproperty list uchar int vertex_indices\nend_header\n" + kVertices +
                        "256 0 1 2\n", "ply"),
            "mesh x.ply: PLY value '256' in element 'face' (instance 0) is not a number of type uchar");
  // Binary: the count is checked against the bytes after it.
  std::string binary = "ply\nformat binary_big_endian 1.0\nelement face 1\nproperty list int int vertex_indices\n"
                       "end_header\n";
  binary += std::string("\x7f\xff\xff\xff", 4) + std::string(12, '\0');
  EXPECT_EQ(verdict(binary, "ply"), "mesh x.ply: PLY data ends in element 'face' (instance 0 of 1, byte 4 of the data); "
                                    "expected the values the header declares");
  binary.replace(binary.size() - 16, 4, "\xff\xff\xff\xff");
  EXPECT_EQ(verdict(binary, "ply"), "mesh x.ply: PLY list 'vertex_indices' in element 'face' (instance 0) has a negative count");
}

TEST(FuzzMeshImport, PlyElementsAssimpWouldMisreadAreLeftOut) {
  // Assimp reads an element of a name it does not know as having no instances, and then the next
  // element's values from that element's data. Only vertex, face and tristrips reach it.
  const std::string ply = "ply\nformat ascii 1.0\ncomment TextureFile stone.png\nelement camera 2\nproperty float f\n" +
                          kPlyHead.substr(kPlyHead.find("element vertex")) +
                          "element face 1\nproperty list uchar int vertex_indices\nend_header\n7\n8\n" + kVertices +
                          "3 0 1 2\n";
  const mesh::TexturedMesh m = mesh::importMeshFromMemory(ply.data(), ply.size(), "ply", "x.ply");
  ASSERT_EQ(m.triangles.size(), 1u);
  const mesh::Triangle& t = m.triangles[0];
  EXPECT_EQ(m.positions[t[1]], Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(m.uvs[t[2]], Eigen::Vector2d(0, 1));
}

TEST(FuzzMeshImport, AFaceWithoutVerticesIsRefused) {
  // Found by the first short run (input 682), regress-empty-ply-face: a binary PLY face with a
  // list count of 0 reached Assimp's triangulation, whose assertion aborted the process.
  const Bytes seed = readBytes(fuzzDir() / "corpus" / "mesh_import" / "regress-empty-ply-face");
  EXPECT_FALSE(fuzzMeshImportOnce(seed));
  EXPECT_EQ(verdict(kPlyHead + "element face 2\nproperty list uchar int vertex_indices\nend_header\n" + kVertices +
                        "3 0 1 2\n0\n", "ply"),
            "mesh x.ply: face 1 of part 0 has no vertices; expected at least one");
}

TEST(FuzzMeshImport, NoMaterialLibraryIsRead) {
  // Found by libFuzzer (SEGV in Assimp, 51 351 executions into a first run),
  // regress-mtl-texture-before-material: "mtllib 4" then "map_Ps". The library cannot be opened,
  // so Assimp's OBJ reader tries "<its file name>.mtl", which Assimp's memory reader answered
  // with the OBJ's own bytes; its MTL parser then wrote through a null pointer at "map_Ps".
  // No .mtl is opened now, from memory or beside a file.
  const Bytes seed = readBytes(fuzzDir() / "corpus" / "mesh_import" / "regress-mtl-texture-before-material");
  EXPECT_FALSE(fuzzMeshImportOnce(seed));
  test::TempDir dir("thx_fuzz_mesh");
  std::ofstream(dir.file("cube.mtl")) << "map_Ps x.png\nnewmtl m\n";
  std::ofstream(dir.file("cube.obj")) << "mtllib cube.mtl\n" << dataFile("cube.obj");
  EXPECT_EQ(mesh::importMesh(dir.file("cube.obj")).triangles.size(), 12u);
}

}  // namespace test_fuzz_mesh_import
