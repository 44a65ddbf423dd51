#pragma once
// The hook for Table 1's one cell the project cannot fill yet: haptic time on the meshes. A
// god-object (proxy) renderer on the triangle mesh with a bounding-volume hierarchy is being built
// beside this benchmark (issue 16); once it lands, implement timeMeshHaptics with it: build it on
// `mesh` (the visual client's displaced grid of the same surface, so every sense sees the same
// triangles), replay `path` (the tip path the relief renderer was timed on) calling its per-tick
// render, and return the per-tick median / p99 as timeHaptics does for the textures. Until then it
// returns nothing and the table says "pending (god-object renderer)".
#include <optional>
#include <vector>

#include "benchmarks/table1_senses.hpp"
#include "clients/visual/mesh_builders.hpp"
#include "device/haptic_device.hpp"

namespace thx::bench::table1 {

inline constexpr const char* kMeshHapticsPending = "pending (god-object renderer)";

std::optional<Timing> timeMeshHaptics(const visual::MeshData& mesh, const std::vector<dev::DeviceState>& path,
                                      int passes);

}  // namespace thx::bench::table1
