// texturetool: make, inspect, convert and smooth texture files (see `texturetool --help`).
#include <cstdio>
#include <string>
#include <vector>

#include "base/program_main.hpp"
#include "textures/tools/cli.hpp"

namespace thx::tex::cli {

namespace {

const char* kGenerateHelp = R"(usage: texturetool generate KIND --out FILE [--size N] [--param NAME=VALUE ...]
                            [--seed S] [--bits 8|16] [--green opengl|directx]
       texturetool generate --list

Writes a procedural relief map (RGBA PNG: RGB = normal, alpha = depth) whose normals are the
exact gradients of the generator's continuous height field.

  KIND                 bricks, vvalley, grooves, pebbles, wood, sine, dimples, tilted, zigzag,
                       porcelain, metal, stone, ceramic_tile
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

It also says which green convention the normals most likely use: a normal map of a height
field has slopes whose cross derivatives agree (zero curl); read with the wrong convention they
have opposite signs. The score (their magnitude-weighted sign agreement) is +1 for a map
consistent with how it was read and -1 for a flipped one; noise and creases pull it towards 0.
Below |0.2| it says "cannot tell": the relief has no mixed slopes (straight grooves or valleys,
a uniform tilt, a flat map), and no method could tell from the normals.

FILE may also be a JPEG, TGA, BMP, TIFF or WebP image (see `texturetool help import`); it is
then read as `import` would with --alpha none, and the import warnings are printed.

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

const char* kImportHelp = R"(usage: texturetool import IN OUT [--green opengl|directx] [--alpha none|height|depth]
                        [--alpha-scale M] [--extent M] [--bits 8|16] [--max-pixels N]

Converts a normal map made elsewhere into this project's PNG (RGB = normal, OpenGL green; RGBA
adds alpha = depth into the surface, with its maximum depth in metres recorded in the file).

Reads PNG (8 or 16 bit), JPEG, BMP, TIFF and WebP (OpenCV's codecs) and TGA (stb_image; the
name must end in .tga, since TGA has no signature). The format is told from the file's bytes,
not its name. RGB holds the normal as (n + 1)/2 per channel; every normal is renormalised.

  --green opengl|directx  how IN stores green: opengl (+Y up, default) or directx (+Y down; the
                          green channel is flipped). `texturetool info IN` says which one the
                          normals most likely use. OUT is always written opengl.
  --alpha none|height|depth
                          what IN's alpha holds: none (default: alpha is dropped, OUT is a normal
                          map), height (white = high: depth = (1 - a/max) x scale) or depth
                          (white = deep: depth = a/max x scale). OUT is then a relief map.
  --alpha-scale M         metres from alpha 0 to full alpha = OUT's maximum depth, in (0, 1];
                          required with --alpha height|depth
  --extent M              physical width of the image in metres (recorded in OUT; optional)
  --bits 8|16             bits per channel of OUT (default 16)
  --max-pixels N          refuse IN if it has more than N pixels (width x height; default and
                          at most 268435456 = 16384 x 16384, at least 4). Read from the file's
                          header before decoding where the header says (every format here), so a
                          small file that declares a huge image costs no memory.

Warnings (on stderr; the file is still written):
  - the alpha is constant although --alpha height|depth was given (an RGBA normal map whose
    alpha is 255 everywhere would become a flat relief: import it with --alpha none);
  - the alpha varies although it is dropped (--alpha none);
  - the normals are far from unit length (more than 5 % of texels off by more than 10 %: not a
    normal map, or another encoding);
  - bad texels (degenerate, or pointing into the surface) were repaired, with their count;
  - the normals look like the other green convention.

Errors name the file: unknown format, truncated or corrupt file, grayscale input (use
from-height), --alpha height|depth on an image without alpha or without --alpha-scale, size
outside [2, 16384] per side or above --max-pixels, samples other than 8 or 16 bits.
)";

const char* kMainHelp = R"(usage: texturetool COMMAND [ARGS...]

Commands:
  generate     write a procedural relief map (bricks, vvalley, pebbles, ...)
  info         print a texture's size, metadata and statistics
  from-height  convert a grayscale height image to a relief or normal map
  smooth       Gaussian-smooth a texture in the gradient domain
  preview      write a shaded picture of a texture
  import       convert a JPEG, TGA, BMP, TIFF, WebP or PNG normal map into this project's PNG
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
      {"import", "other image formats to our PNG", kImportHelp, runImport,
       {{"--green"}, {"--alpha"}, {"--alpha-scale"}, {"--extent"}, {"--bits"}, {"--max-pixels"}}},
  };
  return list;
}

}  // namespace thx::tex::cli

// The shape of thx::runProgram (base/program_main.hpp) with a help per command: no command is a
// usage error with the command list; `help CMD`, or -h/--help anywhere after CMD, prints CMD's help;
// a command's errors are "texturetool CMD: message" with exit status 2 (usage) or 1.
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
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (help || thx::helpRequested(rest)) {
    std::fputs(command->help, stdout);
    return 0;
  }
  return thx::reportErrors(std::string("texturetool ") + command->name,
                           [&] { return command->run(parseArgs(rest, command->options)); });
}
