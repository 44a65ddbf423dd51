#include "clients/visual/gpu_textured_mesh.hpp"

#include <cstddef>
#include <vector>

#include "clients/visual/gl_error.hpp"

namespace thx::visual {
namespace {

struct TexturedVertex {
  float position[3];
  float normal[3];
  float tangent[4];  // xyz, handedness
  float uv[2];
};

}  // namespace

GpuTexturedMesh::GpuTexturedMesh(const mesh::TexturedMesh& mesh)
    : index_count_(GLsizei(mesh.triangles.size() * 3)) {
  if (!mesh.hasFrames()) throw GlError(mesh.source + ": a textured mesh needs its vertex frames to be drawn");
  std::vector<TexturedVertex> vertices(mesh.positions.size());
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    const Eigen::Vector3d &p = mesh.positions[k], &n = mesh.normals[k], &t = mesh.tangents[k];
    const Eigen::Vector2d& uv = mesh.uvs[k];
    vertices[k] = {{float(p.x()), float(p.y()), float(p.z())},
                   {float(n.x()), float(n.y()), float(n.z())},
                   {float(t.x()), float(t.y()), float(t.z()), mesh.handedness[k]},
                   {float(uv.x()), float(uv.y())}};
  }
  static_assert(sizeof(mesh::Triangle) == 3 * sizeof(std::uint32_t), "tightly packed triangles");
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  glGenBuffers(2, buffers_);
  glBindBuffer(GL_ARRAY_BUFFER, buffers_[0]);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(TexturedVertex)), vertices.data(), GL_STATIC_DRAW);
  const auto attribute = [](GLuint index, GLint size, std::size_t offset) {
    glEnableVertexAttribArray(index);
    glVertexAttribPointer(index, size, GL_FLOAT, GL_FALSE, GLsizei(sizeof(TexturedVertex)),
                          reinterpret_cast<const void*>(offset));
  };
  attribute(0, 3, offsetof(TexturedVertex, position));
  attribute(1, 3, offsetof(TexturedVertex, normal));
  attribute(2, 4, offsetof(TexturedVertex, tangent));
  attribute(3, 2, offsetof(TexturedVertex, uv));
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers_[1]);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.triangles.size() * sizeof(mesh::Triangle)),
               mesh.triangles.data(), GL_STATIC_DRAW);
  glBindVertexArray(0);
  checkGl("GpuTexturedMesh()");
}

GpuTexturedMesh::~GpuTexturedMesh() {
  glDeleteBuffers(2, buffers_);
  glDeleteVertexArrays(1, &vao_);
}

void GpuTexturedMesh::draw() const {
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
}

}  // namespace thx::visual
