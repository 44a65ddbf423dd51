#include "clients/visual/options.hpp"

#include "base/cli_number.hpp"
#include "meshes/builtin_shapes.hpp"
#include "thx_msgs/protocol.hpp"

namespace thx::visual {

const char* const kHelp = R"(usage: visual-client --scene FILE (--screenshot FILE | --frames N --out DIR | --replay-log FILE --out DIR | --window) [options]
       visual-client --scene FILE --live (--out DIR | --window) [--rate HZ] [--frames N] [--duration S] [options]

Draws a scene headless (EGL, no display needed) or in a window: the textured plane from the scene's
own texture through the textures library (the map, plane mapping and sampling hapticd and the
physics client use), the scene's objects and the pens. Without --live (and without --replay-log) one
picture at rest: the objects at their poses in the file, each device's pen resting on the surface
where its hand script starts.

Live (--live): subscribes through the client kit to hapticd's device states (tip, proxy, contact)
at --rate and to the physics client's poses (THX_PHYSICS_POSES), and draws the bodies where they
are and every device's pen (see --device): its ball (device 0's red) and shaft at the tip; while
the proxy is held on the surface (the tip below it) the ball (device 0's yellow) and shaft on the
proxy, the tip a smaller ball of the first colour, a dark rod between. A loop step whose pens and
poses equal the last frame's draws nothing (a skipped frame). It follows the server's scene
switches (finds the new scene in --scenes-dir). The summary at exit counts steps, frames drawn
and skipped. Without hapticd within --connect-timeout it says so and draws the scene at rest (one
frame DIR/frame_0000, or the window at rest).
  --live                 with --out DIR (each drawn frame, numbered) or --window
  --rate HZ              live loop rate (default 30; in a window frames also wait for the display)
  --frames N             live headless: stop after N drawn frames
  --duration S           live: stop after S seconds (default 0: until --frames N or Ctrl-C)
  --lcm-url URL          (default )" THX_DEFAULT_LCM_URL R"()
  --connect-timeout S    wait this long for hapticd's hello (default 3)
  --device N             draw only the pen of hapticd's device N: its index in the hello's device
                         list (`hapticctl status` prints it); an index hapticd does not have is an
                         error naming its devices. Default: every device's pen, each in its own
                         colour (device 0 red, 1 blue, 2 green, 3 magenta, then again; the ball
                         on a held proxy lighter: yellow, cyan, lime, pink). With --replay-log,
                         device N's recorded pen (default: every device the log's hellos name)
  --scenes-dir DIR       where a switched-to scene NAME.yaml is found (default scenes)
  --allow-different-scene  run even when hapticd announces another scene or texture (a warning
                         instead of an error) and keep drawing --scene's look when hapticd
                         switches; the pen and the objects still move as hapticd and the physics
                         client say (the user study's candidate looks, docs/study.md §7)
  --verbose              live headless: the counts also while running (every --rate steps)

Output:
  --screenshot FILE      one frame, .png (libpng, compression level 1) or .ppm
  --frames N --out DIR   N numbered frames DIR/frame_0000.png ..., the camera orbiting the target
  --orbit DEG            azimuth step per frame with --frames (default 360 / N)
  --replay-log FILE      a recorded hapticd session (`hapticd --record FILE`) frame by frame into
                         --out DIR: one frame per 1/--rate s of recorded time, each recorded
                         device's pen (tip, proxy; --device N: one) where the recording put it,
                         the objects at the latest physics poses the log holds by then
                         (`physics-client --replay-log S --record OUT` writes them; at rest
                         before the first or without any); deterministic
                         (--frames N: at most N); refused when a recorded hello gives the scene
                         another texture fingerprint than --scene's
  --rate HZ              --replay-log frames per recorded second (default 30)
  --window               a window (needs an X display, e.g. xvfb-run -a); keys: N/R/M mode,
                         S shadows, X relief search, arrows camera, +/- distance, Esc/Q close
  --window-frames N      close the window after N drawn frames
  --window-screenshot F  with --window-frames: save the window's last frame (read from the window)
  --format png|ppm       frame files with --frames (default png)
  --size WxH             pixels (default 640x360)
  --png-level L          zlib level 0..9 (default 1: fast; 9 for pictures kept in git)

Surface:
  --mode M               normal | relief | mesh:N (default relief)
                           normal: normal mapping (the sampled normal at the plane's point)
                           relief: relief mapping, a linear then binary search along the per-pixel
                                   view ray in the tangent frame, self-shadowing, corrected depth
                           mesh:N: N x N quads displaced by the relief, per-vertex normals
  --linear-steps N       relief: linear search samples (default 16, 1..1024)
  --binary-steps N       relief: binary refinement halvings (default 6, 0..32)
  --shadow-steps N       relief: samples towards the light (default 8, 0..1024)
  --no-shadows           relief: no self-shadowing (same as --shadow-steps 0)
  --search S             relief: linear (default: the linear + binary search above) or maxmip
                           (walks the relief's max-mipmap, built at load: the exact hit, never
                           stepping over a thin wall; shadows by the same walk towards the light,
                           on unless --no-shadows; the step counts are not used)

Camera and light (angles in the plane's frame):
  --elevation DEG        camera above the plane (default 35, 1..90)
  --azimuth DEG          camera around the plane's normal (default -90: looking towards +y)
  --distance M           from the target (default 1.25 x the plane's larger side; a mesh scene:
                         1.3 x the mesh's largest side)
  --target X,Y           surface-local point looked at (default 0,0)
  --fov DEG              vertical field of view (default 40)
  --light-elevation DEG  (default 50)    --light-azimuth DEG (default -135)
  --ambient A            (default 0.15)  --specular S (default 0.15)

Textured meshes (issue 28; docs/visual.md "Textured meshes"):
  --surface-mesh SHAPE   draw a built-in textured mesh instead of the plane, with the scene's texture
                         in its tangent frames (--mode normal or relief, --search linear), headless
                         (--screenshot or --frames); no objects, no pen. SHAPE, of size s = 0.25 x
                         the plane's larger side (5 cm on a 20 cm plane), centred where the camera
                         looks (--target 0,0):
                           sphere    radius s, 128 x 64 segments
                           cylinder  an open tube, radius s, height 2 s, 128 x 32
                           torus     radii s and 0.4 s, 128 x 48
                           bowl      radius s, height 0.8 s, wall 0.08 s (turned, 128 segments)
                           vase      height 2.4 s, widest radius s, wall 0.06 s (turned, 128)
                           box       a cube of side 2 s, 8 x 8 cells a face; room: its inside
                           plate     2 s x 2 s, 0.05 s thick
  --surface-mesh-tile M  metres one texture tile spans on the mesh (default: the plane's width,
                         the texture at the scene's scale; rounded to whole tiles around the shape)

Objects:
  --pen X,Y              the (first) pen's tip at surface-local X,Y, on the surface (default:
                         where its hand script starts, else 0,0)
  --no-pen               no pen
  --no-objects           no scene objects

  --quiet                no progress lines
  -h, --help             this text

Environment: LP_NUM_THREADS sets llvmpipe's rendering threads (default one per CPU; beside a
running hapticd on a small machine, 1 keeps a core for the servo: docs/visual.md).
)";

namespace {

Eigen::Vector2d parsePair(const std::string& option, const std::string& text, const char* unit) {
  const std::size_t comma = text.find(',');
  if (comma == std::string::npos)
    throw UsageError(option + ": expected two numbers X,Y in " + unit + ", got '" + text + "'");
  return {cli::parseNumber(option, text.substr(0, comma)), cli::parseNumber(option, text.substr(comma + 1))};
}

void parseSize(const std::string& option, const std::string& text, Options& o) {
  const std::size_t x = text.find('x');
  if (x == std::string::npos) throw UsageError(option + ": expected WxH in pixels, e.g. 640x360, got '" + text + "'");
  o.width = int(cli::parseInteger(option + " width", text.substr(0, x), 16, 8192));
  o.height = int(cli::parseInteger(option + " height", text.substr(x + 1), 16, 8192));
}

}  // namespace

Options parseOptions(const std::vector<std::string>& args) {
  Options o;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) throw UsageError(a + ": missing value");
      return args[++i];
    };
    if (a == "-h" || a == "--help") o.help = true;
    else if (a == "--scene") o.scene = value();
    else if (a == "--screenshot") o.screenshot = value();
    else if (a == "--frames") o.frames = int(cli::parseInteger(a, value(), 1, 100000));
    else if (a == "--out") o.out_dir = value();
    else if (a == "--orbit") o.orbit_deg_per_frame = cli::parseNumber(a, value(), {-360, 360, false, "deg"}), o.orbit_given = true;
    else if (a == "--format") {
      o.frame_format = value();
      if (o.frame_format != "png" && o.frame_format != "ppm")
        throw UsageError(a + ": expected png or ppm, got '" + o.frame_format + "'");
    } else if (a == "--size") parseSize(a, value(), o);
    else if (a == "--png-level") o.png_level = int(cli::parseInteger(a, value(), 0, 9));
    else if (a == "--mode") parseMode(a, value(), o.render);
    else if (a == "--linear-steps") o.render.steps.linear = int(cli::parseInteger(a, value(), 1, 1024));
    else if (a == "--binary-steps") o.render.steps.binary = int(cli::parseInteger(a, value(), 0, 32));
    else if (a == "--shadow-steps") o.render.steps.shadow = int(cli::parseInteger(a, value(), 0, 1024));
    else if (a == "--no-shadows") o.render.steps.shadow = 0;
    else if (a == "--search") o.render.steps.search = parseSearch(a, value());
    else if (a == "--elevation") o.camera.elevation_deg = cli::parseNumber(a, value(), {1, 90, false, "deg"});
    else if (a == "--azimuth") o.camera.azimuth_deg = cli::parseNumber(a, value(), {-360, 360, false, "deg"});
    else if (a == "--distance") o.camera.distance_m = cli::parseNumber(a, value(), {0, 100, true, "m"}), o.distance_given = true;
    else if (a == "--target") o.camera.target_local = parsePair(a, value(), "m");
    else if (a == "--fov") o.camera.fov_y_deg = cli::parseNumber(a, value(), {1, 150, false, "deg"});
    else if (a == "--light-elevation") o.render.light.elevation_deg = cli::parseNumber(a, value(), {0, 90, true, "deg"});
    else if (a == "--light-azimuth") o.render.light.azimuth_deg = cli::parseNumber(a, value(), {-360, 360, false, "deg"});
    else if (a == "--ambient") o.render.light.ambient = cli::parseNumber(a, value(), {0, 1, false, ""});
    else if (a == "--specular") o.render.light.specular = cli::parseNumber(a, value(), {0, 10, false, ""});
    else if (a == "--pen") o.pen_xy = parsePair(a, value(), "m");
    else if (a == "--no-pen") o.no_pen = true;
    else if (a == "--no-objects") o.no_objects = true;
    else if (a == "--quiet") o.quiet = true;
    else if (a == "--window") o.window = true;
    else if (a == "--replay-log") o.replay_log = value();
    else if (a == "--rate") o.replay_rate_hz = cli::parseNumber(a, value(), {0, 1000, true, "Hz"});
    else if (a == "--live") o.live = true;
    else if (a == "--lcm-url") o.lcm_url = value();
    else if (a == "--connect-timeout") o.connect_timeout_s = cli::parseNumber(a, value(), {0, 3600, false, "s"});
    else if (a == "--device") o.device = int(cli::parseInteger(a, value(), 0, (long long)scene::kMaxSceneDevices - 1));
    else if (a == "--duration") o.duration_s = cli::parseNumber(a, value(), {0, 1e9, false, "s"});
    else if (a == "--scenes-dir") o.scenes_dir = value();
    else if (a == "--allow-different-scene") o.allow_different_scene = true;
    else if (a == "--verbose") o.verbose = true;
    else if (a == "--window-screenshot") o.window_screenshot = value(), o.window = true;
    else if (a == "--window-frames") o.window_frames = int(cli::parseInteger(a, value(), 1, 1000000)), o.window = true;
    else if (a == "--surface-mesh") {
      o.surface_mesh = value();
      if (!mesh::isBuiltInShape(o.surface_mesh))
        throw UsageError(a + ": expected " + mesh::kBuiltInShapes + ", got '" + o.surface_mesh + "'");
    } else if (a == "--surface-mesh-tile") o.surface_mesh_tile_m = cli::parseNumber(a, value(), {0, 100, true, "m"});
    else throw UsageError("unknown option '" + a + "'");
  }
  if (o.help) return o;
  if (o.scene.empty()) throw UsageError("--scene FILE is required");
  if (o.lcm_url.empty()) o.lcm_url = thx_msgs::kDefaultLcmUrl;
  const bool replay = !o.replay_log.empty();
  if (o.device && !o.live && !replay) throw UsageError("--device N picks a pen to draw: with --live or --replay-log");
  if (o.surface_mesh_tile_m > 0 && o.surface_mesh.empty()) throw UsageError("--surface-mesh-tile M needs --surface-mesh SHAPE");
  if (!o.surface_mesh.empty()) {
    if (o.window || replay || o.live) throw UsageError("--surface-mesh draws headless: with --screenshot FILE or --frames N --out DIR");
    if (o.render.mode == SurfaceMode::Mesh)
      throw UsageError("--surface-mesh: --mode normal or relief (mesh:N displaces the plane's grid)");
    if (o.render.steps.search == ReliefSearch::MaxMip)
      throw UsageError("--surface-mesh: --search linear (the max-mipmap walk is the plane's)");
    if (o.pen_xy) throw UsageError("--surface-mesh draws no pen: not with --pen");
  }
  if (o.live) {
    if (replay || !o.screenshot.empty()) throw UsageError("--live draws live frames: not with --replay-log or --screenshot");
    if (int(o.window) + int(!o.out_dir.empty()) != 1) throw UsageError("--live needs exactly one of --out DIR and --window");
    return o;
  }
  if (int(!o.screenshot.empty()) + int(o.frames > 0 && !replay) + int(replay) + int(o.window) != 1)
    throw UsageError("give exactly one of --screenshot FILE, --frames N --out DIR, --replay-log FILE --out DIR and --window");
  if (replay && o.out_dir.empty()) throw UsageError("--replay-log FILE needs --out DIR");
  if (!o.window_screenshot.empty() && o.window_frames == 0)
    throw UsageError("--window-screenshot FILE needs --window-frames N");
  if (o.frames > 0 && o.out_dir.empty()) throw UsageError("--frames N needs --out DIR");
  if (o.frames == 0 && !replay && !o.out_dir.empty()) throw UsageError("--out DIR needs --frames N or --replay-log FILE");
  if (o.pen_xy && o.no_pen) throw UsageError("--pen and --no-pen exclude each other");
  if (!o.orbit_given && o.frames > 0 && !replay) o.orbit_deg_per_frame = 360.0 / o.frames;
  return o;
}

CameraPlacement cameraPlacement(const Options& o, const scene::Scene& scene) {
  CameraPlacement placement = o.camera;
  if (!o.distance_given) placement.distance_m = 1.25 * scene.surface.size_m.maxCoeff();
  return placement;
}

double surfaceMeshSize(const scene::Scene& scene) { return 0.25 * scene.surface.size_m.maxCoeff(); }

double surfaceMeshTile(const Options& o, const scene::Scene& scene) {
  return o.surface_mesh_tile_m > 0 ? o.surface_mesh_tile_m : scene.surface.size_m.x();
}

}  // namespace thx::visual
