#include "clients/physics_client/options.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "base/cli_number.hpp"
#include "thx_client/devices.hpp"
#include "thx_client/scene_check.hpp"
#include "thx_msgs/protocol.hpp"

namespace thx::physclient {

const char* const kHelp = R"(usage: physics-client --scene FILE|NAME [options]

Simulates the scene's objects with Bullet on its textured plane (normal or relief, as the scene
says) or its textured mesh (surface.mesh: the smooth surface, its contacts turned by the texture's
normals), with a pen per hapticd device, each a kinematic body following its device. Each pen's
contacts become a force sent back to its own device (client_force_t); object poses and contact
events are published for the audio and visual clients (docs/physics.md, docs/messages.md).

Online it follows hapticd's scene: when a client switches hapticd to scene NAME (server_command_t
ACTION_LOAD_SCENE), it releases its pens' forces, loads NAME.yaml from the scenes folder, checks
its texture fingerprint against hapticd's (a mismatch stops it, as at the start), and goes on in the
new scene at that scene's rates (unless set below). A scene it cannot find or load there stops it
too: hapticd found the file in its own folder, so the two folders differ.

  --scene FILE|NAME      scene file (docs/scenes.md), e.g. scenes/marble_bricks.yaml, or a scene name
                         (marble_bricks) found in --scenes-dir
  --scenes-dir DIR       where scene names are looked up: --scene NAME, and online the scenes hapticd
                         switches to (default: the folder of --scene FILE, or scenes for a NAME)
  --allow-different-scene  online: run even when hapticd announces another scene or texture
                         (a warning instead of an error), and keep this scene when hapticd switches
  --rate HZ              physics steps per second (default: the scene's rates.physics_hz)
  --duration S           stop after S seconds of simulated time (default: online until SIGINT;
                         offline the pen path's length plus 1 s)
  --pose-rate HZ         physics_poses_t rate (default: the scene's rates.visual_hz)
  --contact-rate HZ      physics_contacts_t rate (default: the scene's rates.audio_feed_hz, at most --rate)
  --state-rate HZ        DEVICE_STATE subscription rate (default: --rate)

Pen (the device's tip; default: hapticd over LCM, a pen for each of its devices):
  --replay-log FILE      deterministic, no network: the pens of a recorded hapticd session
                         (`hapticd --record FILE`; one per device its hellos name), stepped in
                         lock-step with its ticks
  --device N             simulate only the pen of hapticd's device N (online, or a --replay-log's):
                         its index in the hello's device list (`hapticctl status` prints it); the
                         other devices' states are ignored, its force goes to device N. An index
                         hapticd or the log does not have is an error naming its devices. Without
                         it: every device's pen
  --pen-csv FILE         deterministic, no network: tip positions, rows `t_s, x_m, y_m, z_m` (world)
  --pen-script           deterministic, no network: the scene's hand script (its first device's),
                         followed kinematically on the surface
  --no-pen               deterministic, no network, no pen (objects only); needs --duration
  --pen-shape S          capsule (default; stands on the tip along the plane's normal) | sphere | none.
                         A scene device with `tool: capsule` gets that capsule instead, along its
                         device's axis (device_state_t.q_world; kinematic pens only); --pen-shape,
                         --pen-radius or --pen-length make every pen the one they describe
  --pen-radius M         default 0.004
  --pen-length M         capsule, between cap centres (default 0.04)
  --force-scale F        client force = F x contact force on the pen (default 1)
  --max-force N          clamp of |client force| (default 2; hapticd refuses above its peak force)
  --no-friction-force    send only the normal part of the pen's contact force
  --pen-coupling K       N/m: grasping pens (docs/physics.md, "Grasping"): each pen a dynamic body
                         on a spring of K (critically damped) to its device's tip, touching the
                         objects only; the device feels the coupling, so two pens pushed against a
                         box's sides squeeze it and can lift it. 0 (default): kinematic pens that
                         follow the tips exactly (they push, but cannot grip). 300 suits a Desktop
  --pen-mass KG          a grasping pen's mass (default 0.02)
  --pen-friction MU      the pen's friction coefficient (default 0.5; Bullet multiplies a pair's)
  --impact-speed M/S     slowest first touch reported as an impact (default 0.005)

LCM:
  --lcm-url URL          default )" THX_DEFAULT_LCM_URL R"(; offline runs publish only when given
  --no-lcm               offline only: publish nothing
  --client-id ID         1-32 of [A-Za-z0-9_-] (default physics)
  --connect-timeout S    wait this long for the first device state (default 10)

  --json FILE            write a run summary (steps, forces, impacts over the whole run, and with
                         several pens each pen's contact steps, forces and impacts; the current
                         scene's name and the scene switches followed; per object of the current
                         scene: displacement, end position in the world and on the surface,
                         speeds, objects it touched)
  --poses-csv FILE       write every moving object's pose at the pose rate: `t_s, object, x_m, y_m,
                         z_m, x_local_m, y_local_m, h_local_m, speed_m_per_s, spin_rad_per_s`
                         (world, then the surface's frame: along the plane and height above it;
                         after a followed scene switch t_s starts again at 0 with the new objects)
  --record FILE          offline: write the poses, impacts and contacts to an LCM log on the pen
                         session's clock; with --replay-log the log is that session plus the
                         physics streams, interleaved by time (the same bytes on every run)
  --quiet                no progress lines (and no line per scene switch)
  -h, --help             this text
)";


std::string Options::scenesDir() const {
  if (scenes_dir) return *scenes_dir;
  if (!client::isScenePath(scene)) return "scenes";
  const std::string parent = std::filesystem::path(scene).parent_path().string();
  return parent.empty() ? "." : parent;
}

Options parseOptions(const std::vector<std::string>& args) {
  Options o;
  int sources = 0;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) throw UsageError(a + ": missing value");
      return args[++i];
    };
    if (a == "-h" || a == "--help") {
      o.help = true;
    } else if (a == "--scene") {
      o.scene = value();
    } else if (a == "--scenes-dir") {
      o.scenes_dir = value();
    } else if (a == "--allow-different-scene") {
      o.allow_different_scene = true;
    } else if (a == "--rate") {
      o.rate_hz = cli::parseNumber(a, value(), {10, 10000, false, "Hz"});
    } else if (a == "--duration") {
      o.duration_s = cli::parseNumber(a, value(), {0, 1e6, true, "s"});
    } else if (a == "--pose-rate") {
      o.pose_hz = cli::parseNumber(a, value(), {0, 10000, true, "Hz"});
    } else if (a == "--contact-rate") {
      o.contact_hz = cli::parseNumber(a, value(), {0, 10000, true, "Hz"});
    } else if (a == "--state-rate") {
      o.state_hz = cli::parseNumber(a, value(), {0, 10000, true, "Hz"});
    } else if (a == "--replay-log") {
      o.pen_source = PenSource::ReplayLog, o.pen_file = value(), ++sources;
    } else if (a == "--pen-csv") {
      o.pen_source = PenSource::Csv, o.pen_file = value(), ++sources;
    } else if (a == "--pen-script") {
      o.pen_source = PenSource::Script, ++sources;
    } else if (a == "--no-pen") {
      o.pen_source = PenSource::None, ++sources;
    } else if (a == "--pen-shape") {
      const std::string v = value();
      o.pen.scene_tool = false;
      if (v == "capsule") o.pen.shape = PenShape::Capsule;
      else if (v == "sphere") o.pen.shape = PenShape::Sphere;
      else if (v == "none") o.pen.shape = PenShape::None;
      else throw UsageError(a + ": expected capsule, sphere or none, got '" + v + "'");
    } else if (a == "--pen-radius") {
      o.pen.radius_m = cli::parseNumber(a, value(), {0, 0.1, true, "m"});
      o.pen.scene_tool = false;
    } else if (a == "--pen-length") {
      o.pen.length_m = cli::parseNumber(a, value(), {0, 1, true, "m"});
      o.pen.scene_tool = false;
    } else if (a == "--force-scale") {
      o.pen.force_scale = cli::parseNumber(a, value(), {0, 100, false, ""});
    } else if (a == "--max-force") {
      o.pen.max_force_n = cli::parseNumber(a, value(), {0, 100, false, "N"});
    } else if (a == "--no-friction-force") {
      o.pen.friction = false;
    } else if (a == "--pen-coupling") {
      o.pen.coupling_n_per_m = cli::parseNumber(a, value(), {0, 1e5, false, "N/m"});
    } else if (a == "--pen-mass") {
      o.pen.coupling_mass_kg = cli::parseNumber(a, value(), {0, 10, true, "kg"});
    } else if (a == "--pen-friction") {
      o.pen.material_friction = cli::parseNumber(a, value(), {0, 10, false, ""});
    } else if (a == "--impact-speed") {
      o.impact_min_speed = cli::parseNumber(a, value(), {0, 100, false, "m/s"});
    } else if (a == "--lcm-url") {
      o.lcm_url = value();
    } else if (a == "--no-lcm") {
      o.no_lcm = true;
    } else if (a == "--client-id") {
      o.client_id = value();
      if (!thx_msgs::is_valid_client_id(o.client_id))
        throw UsageError(a + ": expected 1 to 32 characters of [A-Za-z0-9_-], got '" + o.client_id + "'");
    } else if (a == "--connect-timeout") {
      o.connect_timeout_s = cli::parseNumber(a, value(), {0, 3600, true, "s"});
    } else if (a == "--device") {
      o.device = int(cli::parseInteger(a, value(), 0, client::kMaxDevices - 1));
    } else if (a == "--json") {
      o.json = value();
    } else if (a == "--poses-csv") {
      o.poses_csv = value();
    } else if (a == "--record") {
      o.record = value();
    } else if (a == "--quiet") {
      o.quiet = true;
    } else {
      throw UsageError("unknown option '" + a + "'");
    }
  }
  if (o.help) return o;
  if (o.scene.empty()) throw UsageError("--scene FILE|NAME is required");
  if (sources > 1) throw UsageError("--replay-log, --pen-csv, --pen-script and --no-pen exclude each other");
  if (o.no_lcm && !o.offline())
    throw UsageError("--no-lcm needs an offline pen (--replay-log, --pen-csv, --pen-script or --no-pen)");
  if (o.no_lcm && o.lcm_url) throw UsageError("--no-lcm and --lcm-url exclude each other");
  if (o.pen_source == PenSource::None && !o.duration_s) throw UsageError("--no-pen needs --duration S");
  if (o.device.value_or(0) != 0 && o.offline() && o.pen_source != PenSource::ReplayLog)
    throw UsageError("--device N picks hapticd's pen or a --replay-log's: not with --pen-csv, --pen-script or --no-pen");
  if (!o.record.empty() && !o.offline())
    throw UsageError("--record needs an offline pen (--replay-log, --pen-csv, --pen-script or --no-pen): online "
                     "runs step in real time and would not replay the same");
  return o;
}

}  // namespace thx::physclient
