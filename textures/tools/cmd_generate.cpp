// texturetool generate: procedural relief maps (generators.hpp).
#include <cstdio>

#include "textures/generators.hpp"
#include "textures/texture_io.hpp"
#include "textures/tools/cli.hpp"

namespace thx::tex::cli {

namespace {

void printList() {
  for (const GeneratorSpec& spec : generatorSpecs()) {
    std::printf("%s: %s\n", spec.kind.c_str(), spec.description.c_str());
    for (const GeneratorParam& p : spec.params) {
      const std::string unit = p.unit == "1" ? "" : " " + p.unit;
      char range[96];
      std::snprintf(range, sizeof range, "[%g, %g]%s", p.min_value, p.max_value, unit.c_str());
      char def[64];
      std::snprintf(def, sizeof def, "%g%s", p.default_value, unit.c_str());
      std::printf("  %-16s default %-12s range %-22s %s\n", p.name.c_str(), def, range, p.description.c_str());
    }
    std::printf("\n");
  }
}

}  // namespace

int runGenerate(const Args& args) {
  if (args.has("--list")) {
    if (!args.positional.empty() || args.options.size() > 1) throw UsageError("--list takes no other arguments");
    printList();
    return 0;
  }
  requirePositional(args, {"KIND"});
  GenerateRequest request;
  request.kind = args.positional[0];  // generate() names the known kinds if this is not one
  const std::string out = args.require("--out");
  if (const auto size = args.get("--size")) request.size = parseInt("--size", *size);
  if (const auto seed = args.get("--seed")) request.seed = parseSeed(*seed);
  if (args.has("--param")) {
    for (const std::string& kv : args.options.at("--param")) {
      const std::size_t eq = kv.find('=');
      if (eq == std::string::npos || eq == 0) throw UsageError("--param: '" + kv + "'; expected NAME=VALUE");
      const std::string name = kv.substr(0, eq);
      if (request.params.count(name)) throw UsageError("--param: '" + name + "' given more than once");
      request.params[name] = parseNumber("--param " + name, kv.substr(eq + 1));
    }
  }
  SaveOptions save;
  save.bit_depth = parseBits(args.get("--bits"), 16);
  save.green = parseGreen(args.get("--green"));

  const TextureMap map = generate(request);  // validates kind, size and every parameter
  saveTexture(out, map, save);
  std::printf("wrote %s: %s %dx%d, %d-bit, max depth %.6g m, extent %.6g m\n  %s\n", out.c_str(),
              request.kind.c_str(), map.width(), map.height(), save.bit_depth, map.maxDepth(), map.meta().extent_x_m,
              map.meta().params.c_str());
  return 0;
}

}  // namespace thx::tex::cli
