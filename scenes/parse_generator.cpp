// surface.texture with `generator:`, checked against the textures library's generator registry
// so that a typo in a kind or parameter is reported with its line at load time, not later by
// generate().
#include <algorithm>
#include <cmath>
#include <map>

#include "scenes/scene_sections.hpp"

namespace thx::scene::detail {

namespace {

// Every generator accepts `extent` whether or not its spec lists it (textures/generators.hpp).
constexpr const char* kExtent = "extent";
// Above this a generated map costs hundreds of MiB and seconds to build.
constexpr int kLargeTextureSide = 4096;

const tex::GeneratorSpec& parseKind(const Field& field) {
  const std::string kind = field.text();
  if (const tex::GeneratorSpec* spec = tex::findGenerator(kind)) return *spec;
  std::vector<std::string> kinds;
  for (const tex::GeneratorSpec& spec : tex::generatorSpecs()) kinds.push_back(spec.kind);
  const std::string guess = closestMatch(kind, kinds);
  field.fail(guess.empty() ? "unknown generator" : "unknown generator (did you mean '" + guess + "'?)",
             "one of: " + joinNames(kinds));
}

NumberRange rangeOf(const tex::GeneratorParam& p) {
  NumberRange range;
  if (p.max_value > p.min_value) {
    range.min = p.min_value;
    range.max = p.max_value;
  }
  range.unit = p.unit == "1" ? std::string() : p.unit;
  return range;
}

std::map<std::string, double> parseParams(const Field& field, const tex::GeneratorSpec& spec) {
  std::vector<std::string> names;
  for (const tex::GeneratorParam& p : spec.params) names.push_back(p.name);
  if (std::find(names.begin(), names.end(), kExtent) == names.end()) names.push_back(kExtent);
  field.expectKeys(names);
  std::map<std::string, double> params;
  for (const auto& [name, value] : field.entries()) {
    const auto p = std::find_if(spec.params.begin(), spec.params.end(),
                                // init-capture: clang 14 (the fuzz tree) cannot capture a binding
                                [&n = name](const tex::GeneratorParam& gp) { return gp.name == n; });
    params[name] = p != spec.params.end() ? value.number(rangeOf(*p)) : value.number(positiveUpTo(10.0, "m"));
  }
  return params;
}

}  // namespace

tex::GenerateRequest parseGenerator(const Field& texture, const Surface& surface, const std::string& size_name) {
  const Field kind_field = *texture.find("generator");
  const tex::GeneratorSpec& spec = parseKind(kind_field);
  tex::GenerateRequest request;
  request.kind = spec.kind;
  if (auto size = texture.find("size")) {
    request.size = static_cast<int>(size->integer(tex::kMinTextureSide, tex::kMaxTextureSide, "texels per side"));
    if (request.size > kLargeTextureSide)
      size->warn("a " + std::to_string(request.size) + "^2 texture takes long to generate and much memory");
  }
  if (auto seed = texture.find("seed")) request.seed = seed->unsignedInteger();
  if (auto params = texture.find("params")) request.params = parseParams(*params, spec);

  // The texture spans the surface once, so its physical side should be the surface's.
  const double side = surface.size_m.x();
  if (surface.size_m.x() != surface.size_m.y())
    kind_field.warn("generated textures are square; on a " + formatNumber(surface.size_m.x()) + " x " +
                    formatNumber(surface.size_m.y()) + " m surface their features are stretched along y");
  const auto extent = request.params.find(kExtent);
  if (extent == request.params.end()) {
    request.params[kExtent] = side;
  } else if (std::fabs(extent->second - side) > 1e-9 * side) {
    texture.find("params")->find(kExtent)->warn(
        "extent " + formatNumber(extent->second) + " m differs from " + size_name + " " + formatNumber(side) +
        " m: features appear scaled by " + formatNumber(side / extent->second) + " and normals no longer match depth");
  }
  return request;
}

}  // namespace thx::scene::detail
