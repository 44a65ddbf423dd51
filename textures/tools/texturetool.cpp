// texturetool: make, inspect, convert and smooth texture files (see `texturetool --help`).
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "textures/texture_error.hpp"
#include "textures/tools/cli.hpp"

namespace thx::tex::cli {

namespace {

const char* kGenerateHelp = R"(usage: texturetool generate KIND --out FILE [--size N] [--param NAME=VALUE ...]
                            [--seed S] [--bits 8|16] [--green opengl|directx]
       texturetool generate --list

Writes a procedural relief map (RGBA PNG: RGB = normal, alpha = depth) whose normals are the
exact gradients of the generator's continuous height field.

  KIND                 bricks, vvalley, grooves, pebbles, wood, sine, dimples, tilted
  --out FILE           output PNG
  --size N             texels per side (default 512)
  --param NAME=VALUE   a generator parameter in SI units (metres, degrees for *_deg);
                       repeat for several. `--list` shows each kind's parameters.
  --seed S             seed of the seeded generators, unsigned integer (default 1)
  --bits 8|16          bits per channel (default 16)
  --green opengl|directx  green-channel convention of the file (default opengl)
  --list               print every kind with its parameters, defaults, units and ranges
)";

const char* kInfoHelp = R"(usage: texturetool info FILE [--green opengl|directx] [--max-depth M]

Prints a texture's size, representation, bit depth, metadata, depth range, normal statistics
and how many texels steeper than 60 deg it has. Bad texels (degenerate or pointing into the
surface) are repaired for the statistics and reported, not refused.

  --green opengl|directx  green-channel convention to read the file with (default opengl)
  --max-depth M           maximum depth in metres of a relief map (overrides the file's)
)";

const char* kFromHeightHelp = R"(usage: texturetool from-height IN OUT --extent M [--height-range M]
                            [--representation relief|normal] [--bits 8|16]
                            [--address clamp|wrap] [--green opengl|directx]

Converts a grayscale (1-channel, 8- or 16-bit) PNG height image, white = high, into a relief
map (depth = highest - height) or a normal map. Normals are central differences of the heights.

  --extent M              physical width of the image in metres (texels are square)
  --height-range M        metres between black and white (default 0.001)
  --representation R      relief (default) or normal
  --bits 8|16             bits per channel of OUT (default 16)
  --address clamp|wrap    border rule of the differences: clamp (default, one-sided at the
                          border) or wrap (the image tiles)
  --green opengl|directx  green-channel convention of OUT (default opengl)
)";

const char* kSmoothHelp = R"(usage: texturetool smooth IN OUT --sigma S [--address wrap|clamp] [--bits 8|16]
                        [--green opengl|directx]

Gaussian smoothing in the gradient domain: slopes and depth are blurred with the same kernel and
the normals rebuilt from the slopes, so a relief map's normals stay consistent with its depth.

  --sigma S               standard deviation in texels, in [0, 256] (0 copies the map)
  --address wrap|clamp    border rule: wrap (default, the map tiles) or clamp
  --bits 8|16             bits per channel of OUT (default: that of IN)
  --green opengl|directx  convention of IN and OUT (default opengl)
)";

const char* kPreviewHelp = R"(usage: texturetool preview IN OUT [--azimuth DEG] [--elevation DEG] [--green opengl|directx]

Writes a grayscale 8-bit PNG that shows the texture lit from one direction (Lambert shading of
its normals; relief maps are also darkened with depth). Bad texels are repaired, not refused.

  --azimuth DEG           light direction in the plane, from +x towards +y (default 135: upper left)
  --elevation DEG         light height above the plane, in (0, 90] (default 45)
  --green opengl|directx  convention to read IN with (default opengl)
)";

const char* kMainHelp = R"(usage: texturetool COMMAND [ARGS...]

Commands:
  generate     write a procedural relief map (bricks, vvalley, pebbles, ...)
  info         print a texture's size, metadata and statistics
  from-height  convert a grayscale height image to a relief or normal map
  smooth       Gaussian-smooth a texture in the gradient domain
  preview      write a shaded picture of a texture
  help [CMD]   this text, or a command's own help (also: texturetool CMD --help)

Exit status: 0 success, 1 bad input or failed I/O, 2 bad command line.
)";

}  // namespace

const std::vector<Command>& commands() {
  static const std::vector<Command> list = {
      {"generate", "write a procedural relief map", kGenerateHelp, runGenerate,
       {{"--out"}, {"--size"}, {"--param", true, true}, {"--seed"}, {"--bits"}, {"--green"}, {"--list", false}}},
      {"info", "print statistics", kInfoHelp, runInfo, {{"--green"}, {"--max-depth"}}},
      {"from-height", "height image to relief map", kFromHeightHelp, runFromHeight,
       {{"--extent"}, {"--height-range"}, {"--representation"}, {"--bits"}, {"--address"}, {"--green"}}},
      {"smooth", "Gaussian smoothing", kSmoothHelp, runSmooth, {{"--sigma"}, {"--address"}, {"--bits"}, {"--green"}}},
      {"preview", "shaded picture", kPreviewHelp, runPreview, {{"--azimuth"}, {"--elevation"}, {"--green"}}},
  };
  return list;
}

}  // namespace thx::tex::cli

int main(int argc, char** argv) {
  using namespace thx::tex::cli;
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "-h" || args[0] == "--help" || (args[0] == "help" && args.size() == 1)) {
    std::fputs(kMainHelp, args.empty() ? stderr : stdout);
    return args.empty() ? 2 : 0;
  }
  const bool help = args[0] == "help";
  const std::string name = help ? args[1] : args[0];
  const Command* command = nullptr;
  for (const Command& c : commands()) {
    if (name == c.name) command = &c;
  }
  if (!command) {
    std::fprintf(stderr, "texturetool: unknown command '%s'\n\n%s", name.c_str(), kMainHelp);
    return 2;
  }
  if (help) {
    std::fputs(command->help, stdout);
    return 0;
  }
  try {
    const Args parsed = parseArgs(std::vector<std::string>(args.begin() + 1, args.end()), command->options);
    if (parsed.has("--help")) {
      std::fputs(command->help, stdout);
      return 0;
    }
    return command->run(parsed);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "texturetool %s: %s\n(see: texturetool help %s)\n", command->name, e.what(), command->name);
    return 2;
  } catch (const thx::tex::TextureError& e) {
    std::fprintf(stderr, "texturetool %s: error: %s\n", command->name, e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "texturetool %s: error: %s\n", command->name, e.what());
    return 1;
  }
}
