#pragma once
// physics-client's command line (kHelp is the --help text). parseOptions() throws UsageError with
// a message naming the option, the value and what was expected.
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "clients/physics_client/physics_scene.hpp"

namespace thx::physclient {

extern const char* const kHelp;

using thx::UsageError;

enum class PenSource { Hapticd, ReplayLog, Csv, Script, None };

struct Options {
  bool help = false;
  std::string scene;               // a file, or a scene name looked up in scenes_dir
  std::optional<std::string> scenes_dir;  // --scenes-dir; scenesDir() gives the folder used
  bool allow_different_scene = false;
  std::optional<double> rate_hz, pose_hz, contact_hz, state_hz;  // default: from the scene
  std::optional<double> duration_s;
  PenSource pen_source = PenSource::Hapticd;
  std::string pen_file;  // --replay-log / --pen-csv
  std::optional<std::string> lcm_url;
  bool no_lcm = false;
  std::string client_id = "physics";
  // --device N: simulate only the pen of hapticd's device N (online and --replay-log); without it
  // one pen per device (the hello's device list, a log's hellos).
  std::optional<int> device;
  PenOptions pen;
  double impact_min_speed = 0.005;
  double connect_timeout_s = 10.0;
  std::string json;
  std::string poses_csv;  // --poses-csv FILE
  std::string record;     // --record FILE (offline runs)
  bool quiet = false;

  bool offline() const { return pen_source != PenSource::Hapticd; }
  // Where scene names are found (the --scene NAME, and the scenes hapticd switches to): --scenes-dir;
  // without it the folder of the --scene file when that is a path (its neighbours are the scenes
  // the server's folder holds too), else "scenes".
  std::string scenesDir() const;
};

Options parseOptions(const std::vector<std::string>& args);

}  // namespace thx::physclient
