#include "clients/visual/gpu_mesh.hpp"

#include "clients/visual/gl_error.hpp"

namespace thx::visual {

GpuMesh::GpuMesh(const MeshData& mesh) : index_count_(GLsizei(mesh.indices.size())) {
  static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "tightly packed vertices");
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  glGenBuffers(3, buffers_);
  const auto attribute = [&](GLuint index, GLuint buffer, const std::vector<Eigen::Vector3f>& data) {
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size() * sizeof(Eigen::Vector3f)), data.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(index);
    glVertexAttribPointer(index, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  };
  attribute(0, buffers_[0], mesh.positions);
  attribute(1, buffers_[1], mesh.normals);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers_[2]);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)), mesh.indices.data(),
               GL_STATIC_DRAW);
  glBindVertexArray(0);
  checkGl("GpuMesh()");
}

GpuMesh::~GpuMesh() {
  glDeleteBuffers(3, buffers_);
  glDeleteVertexArrays(1, &vao_);
}

void GpuMesh::draw() const {
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
}

}  // namespace thx::visual
