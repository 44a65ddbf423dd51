// The list of generators, request validation and dispatch (generators.hpp).
#include <cmath>
#include <cstdio>

#include "textures/generators/common.hpp"

namespace thx::tex {

namespace gen {

std::string formatNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

void failParams(const std::string& kind, const std::string& problem, const std::string& value,
                const std::string& expected) {
  throw TextureError("generator " + kind, problem, value, expected);
}

}  // namespace gen

namespace {

// Every generator takes the physical side of the square texture.
GeneratorParam extentParam() {
  return {"extent", 0.2, "m", "physical side of the square texture", 1e-3, 100.0};
}

const std::vector<gen::GeneratorEntry>& entries() {
  static const std::vector<gen::GeneratorEntry> list = [] {
    std::vector<gen::GeneratorEntry> v{gen::bricksGenerator(), gen::vvalleyGenerator(), gen::groovesGenerator(),
                                       gen::pebblesGenerator(), gen::woodGenerator(),    gen::sineGenerator(),
                                       gen::dimplesGenerator(), gen::tiltedGenerator(),   gen::zigzagGenerator(),
                                       gen::porcelainGenerator(), gen::metalGenerator(), gen::stoneGenerator(),
                                       gen::ceramicTileGenerator()};
    for (gen::GeneratorEntry& e : v) e.spec.params.push_back(extentParam());
    return v;
  }();
  return list;
}

template <class Items, class Name>
std::string joinNames(const Items& items, Name&& name) {
  std::string s;
  for (const auto& item : items) s += (s.empty() ? "" : ", ") + name(item);
  return s;
}

std::string rangeText(const GeneratorParam& p) {
  return "a finite value in [" + gen::formatNumber(p.min_value) + ", " + gen::formatNumber(p.max_value) + "]" +
         (p.unit.empty() || p.unit == "1" ? "" : " " + p.unit);
}

// Defaults filled in, every value checked against its range.
gen::Params resolveParams(const GeneratorSpec& spec, const std::map<std::string, double>& given) {
  const std::string source = "generator " + spec.kind;
  for (const auto& [name, value] : given) {
    const bool known = std::any_of(spec.params.begin(), spec.params.end(),
                                   // init-capture: clang 14 (the fuzz tree) cannot capture a binding
                                   [&n = name](const GeneratorParam& p) { return p.name == n; });
    if (!known) {
      throw TextureError(source, "unknown parameter '" + name + "'", name + "=" + gen::formatNumber(value),
                         "one of: " + joinNames(spec.params, [](const GeneratorParam& p) { return p.name; }));
    }
  }
  gen::Params params;
  for (const GeneratorParam& p : spec.params) {
    const auto it = given.find(p.name);
    const double value = it == given.end() ? p.default_value : it->second;
    if (!std::isfinite(value) || value < p.min_value || value > p.max_value) {
      throw TextureError(source, "parameter '" + p.name + "' out of range", p.name + "=" + gen::formatNumber(value),
                         rangeText(p));
    }
    params[p.name] = value;
  }
  return params;
}

std::string paramsText(const GeneratorSpec& spec, const gen::Params& params, std::uint64_t seed) {
  std::string s;
  for (const GeneratorParam& p : spec.params) {
    s += p.name + "=" + gen::formatNumber(params.at(p.name)) + " ";
  }
  return s + "seed=" + std::to_string(seed);
}

}  // namespace

const std::vector<GeneratorSpec>& generatorSpecs() {
  static const std::vector<GeneratorSpec> specs = [] {
    std::vector<GeneratorSpec> v;
    for (const gen::GeneratorEntry& e : entries()) v.push_back(e.spec);
    return v;
  }();
  return specs;
}

const GeneratorSpec* findGenerator(const std::string& kind) {
  for (const GeneratorSpec& s : generatorSpecs()) {
    if (s.kind == kind) return &s;
  }
  return nullptr;
}

TextureMap generate(const GenerateRequest& request) {
  const auto& list = entries();
  const auto entry = std::find_if(list.begin(), list.end(),
                                  [&](const gen::GeneratorEntry& e) { return e.spec.kind == request.kind; });
  if (entry == list.end()) {
    throw TextureError("generator " + request.kind, "unknown generator kind", "'" + request.kind + "'",
                       "one of: " + joinNames(list, [](const gen::GeneratorEntry& e) { return e.spec.kind; }));
  }
  if (request.size < kMinTextureSide || request.size > kMaxTextureSide) {
    throw TextureError("generator " + request.kind, "size out of range", "size=" + std::to_string(request.size),
                       "texels per side in [" + std::to_string(kMinTextureSide) + ", " +
                           std::to_string(kMaxTextureSide) + "]");
  }
  const gen::Params params = resolveParams(entry->spec, request.params);
  TextureMap map = entry->make(params, request.size, request.seed);

  // A generator may leave derived quantities (e.g. the V-valley depth) in meta.params.
  TextureMeta& meta = map.meta();
  const std::string derived = meta.params;
  meta.kind = request.kind;
  meta.extent_x_m = meta.extent_y_m = params.at("extent");
  meta.params = paramsText(entry->spec, params, request.seed) + (derived.empty() ? "" : " " + derived);
  return map;
}

}  // namespace thx::tex
