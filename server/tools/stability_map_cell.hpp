#pragma once
// One cell of the stability map: the simulated hand holds the PHANToM's pen a few millimetres
// above the floor of one V-valley, lowers it, presses with a fixed force and holds; the servo
// pipeline renders the valley; the final window is measured on the simulator's true state.
//
// Timeline (lock-step, 1 kHz servo, 10 kHz device integration): hover at hover_m above the floor
// for settle_s (the safety stage engages and ramps in while nothing touches), descend over 0.2 s,
// ramp the push in over 0.1 s, hold to duration_s. The window is the last window_s.
//
// The hand's frame is put at the valley floor (relief) or on the plane (normal map, whose surface
// is the plane itself), so "press" means press into the floor: a hand frame on the plane would
// hang the pen in the air above the floor of a deep relief valley, and nothing would be measured.
// A capsule's hand frame is where its point (the tip ball's centre) rests on the relief instead.
// The hand aims aim_offset_m beside the floor line: a hand never aims exactly at a crease, and a
// tip exactly on it would sample the two walls' average (a flat normal) and never feel either.
#include <functional>
#include <string>

#include "device/sim_phantom.hpp"
#include "server/capsule_tool.hpp"
#include "server/proxy_renderer.hpp"
#include "server/tick_record.hpp"
#include "server/tools/stability_map_metrics.hpp"
#include "server/tools/stability_map_valley.hpp"

namespace thx::srv::stab {

struct Mitigations {
  bool crease = false;     // RendererConfig::crease_handling
  bool passivity = false;  // PassivityConfig::enabled (the observer always runs)
  bool smoothing = false;  // smoothTexture, ValleyGeometry::smoothing_sigma_texels
  // The source paper's loop (server/paper_loop.hpp): one plane per frame, held between frames,
  // no recovery rule; the baseline. Only with smoothing (the paper's own mitigation), never with
  // crease or passivity.
  bool paper_loop = false;

  // "none", "crease", "passivity", "smoothing", "crease+passivity", ..., "all"; "paper",
  // "paper+smoothing"
  std::string name() const;
  int index() const { return (crease ? 1 : 0) | (passivity ? 2 : 0) | (smoothing ? 4 : 0) | (paper_loop ? 8 : 0); }
  static Mitigations fromIndex(int index);
};

// The hand holding the pen: SimPhantomConfig's hand and mechanism-friction fields.
struct HandParams {
  std::string name;
  double mass_kg = 0.2;
  double stiffness_n_per_m = 300.0;
  double damping_ns_per_m = 3.0;
  double friction_n = 0.06;  // the mechanism's Coulomb friction
};
HandParams defaultHand();    // scenes/default.yaml (= SimPhantomConfig defaults)
HandParams lightGripHand();  // docs/stability.md: fingertips only, holding the pen loosely
// "default" or "light"; throws thx::Error (Config) otherwise.
HandParams handByName(const std::string& name);

// What the pen is (issue 30): the point (the plane-proxy renderer), or a capsule
// (server/capsule_tool.hpp) held upright, its tip's ball in the valley, or lying across the
// ridges (its shaft along -x from the tip, the hand holding it level). The simulated Desktop shows
// force only, so a capsule's torque steers the tool and is not displayed.
enum class PenTool { Point, Capsule, CapsuleAcross };
const char* penToolName(PenTool tool);  // "point", "capsule", "capsule-across"

struct CellSetup {
  ValleyGeometry geometry;
  HandParams hand = defaultHand();
  double virtual_damping_ns_per_m = 1.0;  // B, as both shipped scenes (default.yaml, vvalley.yaml)
  int recovery_ticks = RendererConfig{}.recovery_ticks;  // the renderer's recovery rule (0: off)
  double plane_rate_hz = 100.0;           // the paper's loop: planes per second (--plane-rate)
  bool sided_ridges = RendererConfig{}.sided_ridges;  // --ridges sided|blend (issue 12)
  double aim_offset_m = 1e-4;             // half a texel, four encoder counts
  double hover_m = 0.005;
  double settle_s = 0.5;
  double duration_s = 3.0;
  double window_s = 1.0;
  Thresholds thresholds;
  PenTool tool = PenTool::Point;
  double capsule_length_m = 0.10;  // scenes' device.tool defaults
  double capsule_radius_m = 0.002;
};

struct CellParams {
  double angle_deg = 60.0;          // opening angle between the walls
  double stiffness_fraction = 1.0;  // of the device maximum (Desktop: 1000 N/m)
  double push_force_n = 1.0;
  bool relief = true;               // false: the same map read as a normal map
  Mitigations mitigations;
};

struct CellResult {
  CellParams params;
  double stiffness_n_per_m = 0.0;
  double floor_height_m = 0.0;  // plane-local z of the rendered floor under the aim (0 for a normal map)
  CellMetrics metrics;
};

// Called after every tick with the servo's record and the simulator's truth (--trace, tests).
using TraceFn = std::function<void(const TickRecord&, const dev::SimTruth&)>;

// The simulator configuration of a cell (also what the tests start from).
dev::SimPhantomConfig simConfigFor(const HandParams& hand);

// `valley` must be the map for params.angle_deg with params.mitigations.smoothing. Deterministic.
// A capsule takes no crease handling and no paper loop (they are the point renderer's): thx::Error.
CellResult simulateCell(const CellParams& params, const ValleyMap& valley, const CellSetup& setup,
                        const TraceFn& trace = {});

}  // namespace thx::srv::stab
