#include "benchmarks/table1_mesh_haptics.hpp"

namespace thx::bench::table1 {

// No mesh haptic renderer in the project yet (see the header): the cell stays pending.
std::optional<Timing> timeMeshHaptics(const visual::MeshData&, const std::vector<dev::DeviceState>&, int) {
  return std::nullopt;
}

}  // namespace thx::bench::table1
