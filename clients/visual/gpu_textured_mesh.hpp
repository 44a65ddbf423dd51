#pragma once
// A TexturedMesh uploaded once into one interleaved vertex buffer and an index buffer, in float
// (the GPU's precision; the mesh keeps double): position (location 0), normal (1), tangent with
// the handedness in w (2), uv in tiles (3).
#include "clients/visual/gl_api.hpp"
#include "meshes/textured_mesh.hpp"

namespace thx::visual {

class GpuTexturedMesh {
 public:
  explicit GpuTexturedMesh(const mesh::TexturedMesh& mesh);  // needs hasFrames()
  ~GpuTexturedMesh();
  GpuTexturedMesh(const GpuTexturedMesh&) = delete;
  GpuTexturedMesh& operator=(const GpuTexturedMesh&) = delete;
  void draw() const;

 private:
  GLuint vao_ = 0, buffers_[2] = {0, 0};
  GLsizei index_count_ = 0;
};

}  // namespace thx::visual
