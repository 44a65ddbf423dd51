#pragma once
// A MeshData uploaded once: vertex array with position (location 0) and normal (location 1).
#include "clients/visual/gl_api.hpp"
#include "clients/visual/mesh_builders.hpp"

namespace thx::visual {

class GpuMesh {
 public:
  explicit GpuMesh(const MeshData& mesh);
  ~GpuMesh();
  GpuMesh(const GpuMesh&) = delete;
  GpuMesh& operator=(const GpuMesh&) = delete;
  void draw() const;

 private:
  GLuint vao_ = 0, buffers_[3] = {0, 0, 0};
  GLsizei index_count_ = 0;
};

}  // namespace thx::visual
