#include "clients/visual/mesh_image_error.hpp"

namespace thx::visual {

ReferenceImage meshReferenceImage(const MeshReference& reference, const Camera& camera, int width, int height,
                                  bool relief, const ReferenceLight& light) {
  ReferenceImage image{width, height, std::vector<std::optional<ReferenceHit>>(std::size_t(width) * height)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      image.hits[std::size_t(y) * width + x] = reference.hit(camera.pixelRay(x, y), relief, light);
  return image;
}

PixelStats compareWithMeshReference(const MeshReference& reference, const ReferenceImage& image,
                                    const Rgba8Image& colour, const FloatImage& hits) {
  // The plane's comparison reads only the map and its address mode from the surface.
  return compareWithReference(reference.tangentPlane(), image, colour, hits);
}

}  // namespace thx::visual
