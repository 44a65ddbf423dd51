#pragma once
// A textured mesh's triangles as Bullet reads them (btTriangleIndexVertexArray: int indices, float
// vertices), owned together so that they outlive the btBvhTriangleMeshShape built on them.
#include <BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h>

#include <memory>
#include <vector>

#include "meshes/textured_mesh.hpp"

namespace thx::phys {

struct BulletTriangles {
  std::vector<int> indices;
  std::vector<btScalar> vertices;
  std::unique_ptr<btTriangleIndexVertexArray> array;  // reads the two above: do not move them
};

// The caller checks the counts fit Bullet's ints (PhysicsWorld::addTexturedMesh).
std::unique_ptr<BulletTriangles> bulletTriangles(const mesh::TexturedMesh& mesh);

}  // namespace thx::phys
