#pragma once
// A rendered frame of a textured mesh against its CPU reference (mesh_reference.hpp), with the
// plane's measures (image_error.hpp): pixels whose hit lands on another texel, intensity error in
// 8-bit LSB, pixels next to the background skipped.
#include "clients/visual/image_error.hpp"
#include "clients/visual/mesh_reference.hpp"

namespace thx::visual {

ReferenceImage meshReferenceImage(const MeshReference& reference, const Camera& camera, int width, int height,
                                  bool relief, const ReferenceLight& light);

PixelStats compareWithMeshReference(const MeshReference& reference, const ReferenceImage& image,
                                    const Rgba8Image& colour, const FloatImage& hits);

}  // namespace thx::visual
