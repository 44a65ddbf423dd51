#include "clients/visual/render_settings.hpp"

#include <cmath>
#include <numbers>

#include "base/cli_number.hpp"
#include "base/error.hpp"

namespace thx::visual {

Eigen::Vector3d lightDirectionLocal(const Lighting& light) {
  const double el = light.elevation_deg * std::numbers::pi / 180, az = light.azimuth_deg * std::numbers::pi / 180;
  return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

void parseMode(const std::string& option, const std::string& text, RenderSettings& settings) {
  if (text == "normal") {
    settings.mode = SurfaceMode::Normal;
  } else if (text == "relief") {
    settings.mode = SurfaceMode::Relief;
  } else if (text.rfind("mesh:", 0) == 0) {
    settings.mode = SurfaceMode::Mesh;
    settings.mesh_n = int(cli::parseInteger(option + " mesh:N", text.substr(5), 1, 4096));
  } else {
    throw UsageError(option + ": expected normal, relief or mesh:N, got '" + text + "'");
  }
}

std::string modeName(const RenderSettings& settings) {
  switch (settings.mode) {
    case SurfaceMode::Normal: return "normal";
    case SurfaceMode::Relief: return "relief";
    case SurfaceMode::Mesh: return "mesh:" + std::to_string(settings.mesh_n);
  }
  return "?";
}

ReliefSearch parseSearch(const std::string& option, const std::string& text) {
  if (text == "linear") return ReliefSearch::Linear;
  if (text == "maxmip") return ReliefSearch::MaxMip;
  throw UsageError(option + ": expected linear or maxmip, got '" + text + "'");
}

}  // namespace thx::visual
