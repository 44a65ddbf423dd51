#!/usr/bin/env bash
# Runs the benchmarks and regenerates their results: docs/results/bench_*.{json,csv,png} and the
# tables in docs/benchmarks.md (between the <!-- BEGIN bench_X --> / <!-- END bench_X --> markers).
#
# Usage: benchmarks/run.sh [BUILD_DIR] [PART...]
#   BUILD_DIR  a configured and built tree (default: build); build it first with
#              cmake -S . -B BUILD_DIR -DCMAKE_BUILD_TYPE=RelWithDebInfo && cmake --build BUILD_DIR -j2 --target benchmarks
#   PART       any of: render force_error memory latency clients physics visual (default: all seven, in that order),
#              or audio (FEM modal analysis and modal synthesis speed/error, about 3.5 min; its
#              tables go to docs/audio.md),
#              or audio-live (the live audio client beside hapticd with its simulated device: the
#              servo's wake latency with and without it; THX_AUDIO_LIVE_SECONDS per phase (20),
#              THX_AUDIO_LIVE_ROUNDS (2); about 3 min; its table goes to docs/audio.md),
#              or load (hapticd's full-force share beside stress-ng and cyclictest, old and new
#              missed-tick policy; THX_LOAD_SECONDS per run (25), THX_LOAD_LOADS (none,cpu2,cpu2+vm),
#              THX_LOAD_ROUNDS (1); about 3 min a round; needs stress-ng, Debian stress-ng, in setup.sh)
#              or rates (issue 30: the same at servo rates of 1, 2 and 4 kHz, ride-through only,
#              cyclictest at the servo's period, loads none and cpu2, hapticd sleeping to each tick and
#              spinning its last 150 us; THX_RATES_SECONDS per run (15), THX_RATES (1000,2000,4000),
#              THX_RATES_LOADS (none,cpu2), THX_RATES_SPINS (0,150); about 3.5 min; then the
#              texture's force error against the servo rate (bench_rate_texture, seconds); both
#              tables go to docs/hapticd.md)
#              or capsule (issue 30: the pen with extent's cost against its contacts on the default
#              scene's bricks and a steep V-valley, upright, at 45 degrees and lying flat, beside the
#              point pen; about 20 s; its table goes to docs/hapticd.md)
#              or devices (issue 30: 1, 2 and 4 simulated devices under one servo clock beside
#              cyclictest, the group's compute against one device's, and each device's force in the
#              group against alone in lock-step; THX_DEVICES_SECONDS per count (15), THX_DEVICES
#              (1,2,4); about 1 min; its table goes to docs/hapticd.md)
#              or visual_servo (hapticd's wake latency alone and beside visual-client --live, servo
#              SCHED_FIFO and normal, LP_NUM_THREADS 2 and 1; THX_VISUAL_SERVO_SECONDS per run (20);
#              about 2.5 min; needs xvfb-run and setpriv; its table goes to docs/visual.md)
#              or table1 (the paper's Table 1 on one surface: normal map, relief map, meshes 256² and
#              512², beside the paper's figures; writes docs/results/table1.{md,csv} and the table in
#              docs/table1.md; THX_TABLE1_MESH_SIZES the Tet4 slabs measured for the meshes' memory
#              fit (24,32,48,64,96,128,256,512: both mesh cells measured, the 512² one needs about
#              8 GB and 7 min; leave 512 out to extrapolate it); about 10 min)
#              or clients_lan (issue 31: hapticd and 32 probe-clients on a virtual LAN of network
#              namespaces, on one host and on two others, and host 2's cable pulled for 2 s;
#              THX_CLIENTS_LAN_SECONDS per run (20); about 1.5 min; needs root)
#              or mesh_force (issue 28: the textured mesh renderer's force error against exact displaced
#              spheres and cylinders by triangle count and frame, force turns across edges, render
#              cost up to 500,000 triangles; about 2 min; its tables go to docs/meshes.md)
#              or physics_mesh (issue 29: a ball swinging in and rolling off tessellated spheres
#              against the smooth sphere's answers, smooth contacts and Bullet's flat ones, by
#              tessellation, the relief by step, and 100 releases shared over the cores; about
#              18 min on 2 cores; its table goes to docs/physics.md)
#              or lifted_swing (issue 29: the lifted ball, the default, swinging in a bowl of sine bumps
#              at the UV sphere's pole and on its equator against a rigid ball rolling on the relief
#              as its sphere meets it with the rolling-impact law where its touch jumps, and where it
#              leaves the top of that sphere; about 1 min; its table goes to docs/physics.md)
#              or block_by_pole (issue 29: a block set down around the squeezed pole of the bowl of
#              bricks as a normal map, read at one point, as its integrated relief and as the
#              relief map, then the map leaning (at one point, and as its relief with its normals
#              leaning); about 20 s; its table goes to docs/physics.md)
#              or textured_pair (issue 29: a grooved block on a grooved plane, the force that starts
#              it sliding along and across the grooves (raised slowly; across also at once) in both
#              orders of the pair and beside a plain block, along and across on a slab mesh and on
#              a grooved box (fixed, and across on a moving one), and the cost of a step, at 64,
#              128 and 256 texels; about 5 min; its table goes to
#              docs/physics.md)
#              or capsule_run (issue 29: a capsule lying on a textured box's face, the search along
#              its run for the ball whose lifted gap is least against brute force, its error and
#              cost at spacings of 0.5 to 4 texels; about 30 s; its table goes to docs/physics.md)
#              or pen_on_objects (issue 29: a whole world's physics step with the pen's capsule
#              pressing a block and a ball, a marble in a ball's dimple and a ball on a ball, each
#              object plain and textured; about 5 s; its table goes to docs/physics.md)
#              or textured_ball (issue 29: a ball with a bump map on relief planes of 128, 256 and
#              512 texels: rolling on its recessed radius, at rest on a flat and a bumpy relief, the
#              cost of a step beside a plain ball; on UV spheres of 64, 128 and 256 segments, a
#              recessed ball's swing in a bowl and where it leaves a sphere's top; about a minute;
#              its tables go to docs/physics.md)
#              or ball_own_texels (issue 29: the dimpled ball let down in a smooth bowl and in a
#              smooth relief dish from 24 starts each, at rest, rocking or swinging; on a plain plane
#              at 256 to 1024 texels a face, how deep it rests and what a step costs rolling; about
#              two and a half minutes; its table goes to docs/physics.md)
#              or rolling_ridges (issue 29: a ball rolling across sine ridges on the relief plane and on
#              a relief mesh, lifted and steered, against the rolling-impact law, with the cost of a
#              step; about half a minute; its table goes to docs/physics.md)
#              or rod_in_groove (issue 29: a capsule, a cylinder and a ball lying in a V-groove on the relief
#              plane, a flat relief mesh and a grooved pipe, where it rests and the force that rolls
#              it out against the analytic answers, with the cost of a step; about 15 s; its table
#              goes to docs/physics.md)
#              or rocking_on_curve (issue 29: a block rocking on an untextured cylinder mesh and a
#              capsule and a cylinder rolling in a pipe, met on the smooth chart and on Bullet's
#              triangles, their period against the exact rolling answer by tessellation and grid,
#              with the cost of a step; seconds; its table goes to docs/physics.md)
#              or object_by_crease (issue 29: a plain and a grooved block by a slab mesh's edge,
#              grooved or untextured, where it rests and how it tips over the edge, with the cost
#              of a step; seconds; its table goes to docs/physics.md)
#              or ball_on_small_mesh (issue 29: a plain and a recessed 1 cm ball pressed on sphere
#              meshes of 20 to 0.25 mm and a 1 mm rod mesh, where it rests against its touch, with
#              the cost of a step; about 25 s; its table goes to docs/physics.md)
#              or report (no measuring: docs/report.md and docs/report/*.png, every modality's speed
#              against error, from the results already in docs/results/; seconds. To measure
#              everything first: benchmarks/run.sh BUILD, then BUILD audio, then BUILD report)
#
# The clients part also sweeps the number of clients (issue 17): 1, 2, 4, 8, 16, 32, 64 clients
# (THX_CLIENTS_SWEEP), for the workloads "mixed" (1/4 of the clients batched CONTACT at 1 kHz, the
# rest DEVICE_STATE at 60 Hz: 16 + 48 at 64) and "half" (1/2 and 1/2: 16 + 16 at 32)
# (THX_CLIENTS_WORKLOADS), THX_CLIENTS_SWEEP_SECONDS (20) per point, with hapticd's per-client data
# ports and control port (the default); and "mixed" once more with everything on the one shared
# port (--data-ports off --control-port off) for comparison (THX_CLIENTS_COMPARE_SHARED=0 skips it).
# Writes docs/results/bench_clients_scale_{WORKLOAD,mixed_shared}.{json,csv}, the plot
# docs/results/bench_clients_scale.png, and splices the bench_clients_scale_* tables.
# THX_CLIENTS_SWEEP=none runs only the 16-client benchmark.
#
# Needs: the built benchmarks and hapticd; cyclictest (Debian rt-tests, in setup.sh) for latency;
# root or CAP_SYS_NICE + CAP_IPC_LOCK for SCHED_FIFO and mlockall (without them the latency and
# memory tables say so). Takes about 17 minutes (clients: 13 minutes with its sweeps, physics: 1.5). Timing on a shared machine is noisy: compare
# ratios within one run.
set -uo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-build}
[ $# -gt 0 ] && shift
case "$BUILD" in /*) ;; *) BUILD="$ROOT/$BUILD" ;; esac
PARTS=("$@")
[ ${#PARTS[@]} -eq 0 ] && PARTS=(render force_error memory latency clients physics visual)

RESULTS="$ROOT/docs/results"
DOC="$ROOT/docs/benchmarks.md"
WORK="$BUILD/benchmarks/run"  # logs, scratch files and the table fragments
BIN="$BUILD/benchmarks"
HAPTICD="$BUILD/server/hapticd"
mkdir -p "$RESULTS" "$WORK"

say() { printf '[run.sh %s] %s\n' "$(date +%H:%M:%S)" "$*"; }
failed=()

need() {
  if [ ! -x "$1" ]; then
    say "missing $1: build it first (cmake --build $BUILD -j2 --target benchmarks)"
    return 1
  fi
}

# Replaces the lines between <!-- BEGIN name --> and <!-- END name --> in docs/benchmarks.md
# (or in the document given as a third argument).
splice() {
  local name=$1 fragment=$2 DOC=${3:-$DOC}
  if ! grep -q "^<!-- BEGIN $name -->$" "$DOC"; then
    say "warning: no '<!-- BEGIN $name -->' marker in $DOC; table not updated"
    return 0
  fi
  awk -v name="$name" -v frag="$fragment" '
    $0 == "<!-- BEGIN " name " -->" { print; while ((getline line < frag) > 0) print line; skip = 1; next }
    $0 == "<!-- END " name " -->" { skip = 0 }
    !skip { print }
  ' "$DOC" > "$DOC.tmp" && mv "$DOC.tmp" "$DOC"
  say "updated the $name table in ${DOC#"$ROOT"/}"
}

# bench_with_table NAME DOC [--png]: a benchmark that writes its results into RESULTS (NAME.json,
# .csv, and with --png its plot NAME.png) and one table, spliced into DOC between NAME's markers.
bench_with_table() {
  local name=$1 doc=$2 png=()
  [ "${3:-}" = --png ] && png=(--png "$RESULTS/$name.png")
  "$BIN/$name" --json "$RESULTS/$name.json" --csv "$RESULTS/$name.csv" "${png[@]}" \
    --md "$WORK/$name.md" > /dev/null || return 1
  splice "$name" "$WORK/$name.md" "$doc"
}

run_render() {
  if [ ! -x "$BIN/bench_render" ]; then
    say "bench_render was not built (Google Benchmark missing? Debian: libbenchmark-dev); skipping part 1"
    return 1
  fi
  say "part 1: per-tick cost (Google Benchmark, about 60 s)"
  "$BIN/bench_render" --benchmark_out="$RESULTS/bench_render.json" --benchmark_out_format=json \
    --benchmark_counters_tabular=true --benchmark_enable_random_interleaving=true --csv "$RESULTS/bench_render.csv" --md "$WORK/bench_render.md" || return 1
  splice bench_render "$WORK/bench_render.md"
}

run_force_error() {
  need "$BIN/bench_force_error" || return 1
  say "part 2: force error against the exact height-field contact (about 80 s)"
  "$BIN/bench_force_error" --json "$RESULTS/bench_force_error.json" --csv "$RESULTS/bench_force_error.csv" \
    --png "$RESULTS/bench_force_error.png" --md "$WORK/bench_force_error.md" || return 1
  splice bench_force_error "$WORK/bench_force_error.md"
  # The paper's mitigation (docs/stability.md): its loop on the raw and the smoothed map, at the
  # stability map's smoothing (2 texels) and the device's full stiffness, beside crease handling.
  say "part 2b: force error of the paper's loop and its smoothing (about 10 s)"
  "$BIN/bench_force_error" --sizes 512,1024 --smooth 2 --stiffness 1000 --variants paper,paper+smoothed,bilinear+crease \
    --json "$RESULTS/bench_force_error_paper.json" --csv "$RESULTS/bench_force_error_paper.csv" \
    --md "$WORK/bench_force_error_paper.md" --md-compact 1 || return 1
  splice bench_force_error_paper "$WORK/bench_force_error_paper.md" "$ROOT/docs/stability.md"
  # Issue 16: the relief as 256² and 512² meshes under the god object, beside the texture renderers,
  # on the same probes; then the haptic time per tick on the default scene's meshes (Table 1).
  need "$BIN/bench_mesh_haptic" || return 1
  say "part 2c: the meshes' god object: force error and time per tick (about 40 s)"
  "$BIN/bench_force_error" --sizes 256,512 --variants normal-map+crease,bilinear+crease,mesh \
    --json "$RESULTS/bench_force_error_mesh.json" --csv "$RESULTS/bench_force_error_mesh.csv" \
    --md "$WORK/bench_force_error_mesh.md" --md-compact 1 || return 1
  splice bench_force_error_mesh "$WORK/bench_force_error_mesh.md"
  "$BIN/bench_mesh_haptic" --csv "$RESULTS/bench_mesh_haptic.csv" --json "$RESULTS/bench_mesh_haptic.json" \
    --md "$WORK/bench_mesh_haptic.md" || return 1
  splice bench_mesh_haptic "$WORK/bench_mesh_haptic.md"
}

run_memory() {
  need "$BIN/bench_memory" && need "$HAPTICD" || return 1
  say "part 3: hapticd memory with a 1024² relief map (about 15 s)"
  "$BIN/bench_memory" --hapticd "$HAPTICD" --scene "$ROOT/benchmarks/scenes/relief1024.yaml" \
    --baseline-scene "$ROOT/scenes/default.yaml" --workdir "$WORK" \
    --json "$RESULTS/bench_memory.json" --csv "$RESULTS/bench_memory.csv" --md "$WORK/bench_memory.md" || return 1
  splice bench_memory "$WORK/bench_memory.md"
}

run_latency() {
  need "$BIN/bench_latency" && need "$HAPTICD" || return 1
  local ct
  ct=$(command -v cyclictest || true)
  if [ -z "$ct" ]; then
    say "cyclictest not found: install rt-tests (./setup.sh); skipping part 4"
    return 1
  fi
  say "part 4: wake-up latency, hapticd beside cyclictest (5 runs of 10 s)"
  # The latency tool writes its fragment even when a run fails (the table then says why).
  "$BIN/bench_latency" --hapticd "$HAPTICD" --scene "$ROOT/scenes/default.yaml" --seconds 10 --cyclictest "$ct" \
    --workdir "$WORK" --json "$RESULTS/bench_latency.json" --csv "$RESULTS/bench_latency.csv" \
    --md "$WORK/bench_latency.md"
  local rc=$?
  [ -s "$WORK/bench_latency.md" ] && splice bench_latency "$WORK/bench_latency.md"
  return $rc
}

# Sets ct and sn (the caller's locals) to cyclictest and stress-ng, or says what to install and
# fails, naming part $1.
load_tools() {
  ct=$(command -v cyclictest || true)
  sn=$(command -v stress-ng || true)
  if [ -z "$ct" ] || [ -z "$sn" ]; then
    say "cyclictest or stress-ng not found: install rt-tests and stress-ng (./setup.sh); skipping part $1"
    return 1
  fi
}

run_load() {
  need "$BIN/bench_load" && need "$HAPTICD" || return 1
  local ct sn
  load_tools load || return 1
  say "part load: hapticd's full-force share beside stress-ng and cyclictest, old and new missed-tick policy"
  "$BIN/bench_load" --hapticd "$HAPTICD" --scene "$ROOT/benchmarks/scenes/load_press.yaml" \
    --seconds "${THX_LOAD_SECONDS:-25}" --loads "${THX_LOAD_LOADS:-none,cpu2,cpu2+vm}" --rounds "${THX_LOAD_ROUNDS:-1}" --cyclictest "$ct" \
    --stress-ng "$sn" --workdir "$WORK" --json "$RESULTS/bench_load.json" --csv "$RESULTS/bench_load.csv" \
    --md "$WORK/bench_load.md"
  local rc=$?
  [ -s "$WORK/bench_load.md" ] && splice bench_load "$WORK/bench_load.md"
  return $rc
}

run_rates() {
  need "$BIN/bench_load" && need "$BIN/bench_rate_texture" && need "$HAPTICD" || return 1
  local ct sn
  load_tools rates || return 1
  say "part rates: hapticd at 1, 2 and 4 kHz beside cyclictest at the same period, idle and loaded"
  "$BIN/bench_load" --hapticd "$HAPTICD" --scene "$ROOT/benchmarks/scenes/load_press.yaml" \
    --seconds "${THX_RATES_SECONDS:-15}" --rates "${THX_RATES:-1000,2000,4000}" --policies ride-through \
    --spins "${THX_RATES_SPINS:-0,150}" \
    --loads "${THX_RATES_LOADS:-none,cpu2}" --cyclictest "$ct" --stress-ng "$sn" --workdir "$WORK" \
    --json "$RESULTS/bench_rates.json" --csv "$RESULTS/bench_rates.csv" --md "$WORK/bench_rates.md"
  local rc=$?
  [ -s "$WORK/bench_rates.md" ] && splice bench_rates "$WORK/bench_rates.md" "$ROOT/docs/hapticd.md"
  say "part rates: the texture's force error against the servo rate"
  bench_with_table bench_rate_texture "$ROOT/docs/hapticd.md" --png || rc=1
  return $rc
}

run_devices() {
  need "$BIN/bench_devices" || return 1
  local ct
  ct=$(command -v cyclictest || echo none)
  [ "$ct" = none ] && say "cyclictest not found (Debian rt-tests, ./setup.sh): part devices runs without it"
  say "part devices: ${THX_DEVICES:-1,2,4} simulated devices under one servo clock beside cyclictest"
  "$BIN/bench_devices" --counts "${THX_DEVICES:-1,2,4}" --seconds "${THX_DEVICES_SECONDS:-15}" --cyclictest "$ct" \
    --workdir "$WORK" --json "$RESULTS/bench_devices.json" --md "$WORK/bench_devices.md" > /dev/null
  local rc=$?
  [ -s "$WORK/bench_devices.md" ] && splice bench_devices "$WORK/bench_devices.md" "$ROOT/docs/hapticd.md"
  return $rc
}

run_capsule() {
  need "$BIN/bench_capsule_tool" || return 1
  say "part capsule: the pen with extent's cost against its contacts (about 20 s)"
  bench_with_table bench_capsule_tool "$ROOT/docs/hapticd.md"
}

run_clients() {
  need "$BIN/bench_clients" && need "$HAPTICD" && need "$BUILD/clients/probe/probe-client" || return 1
  say "part 5: 16 clients against hapticd (60 s), and hapticd alone before and after (30 s each)"
  "$BIN/bench_clients" --hapticd "$HAPTICD" --probe "$BUILD/clients/probe/probe-client" \
    --scene "$ROOT/scenes/default.yaml" --seconds 60 --baseline-seconds 30 --workdir "$WORK" \
    --json "$RESULTS/bench_clients.json" --csv "$RESULTS/bench_clients.csv" --md "$WORK/bench_clients.md"
  local rc=$?
  [ -s "$WORK/bench_clients.md" ] && splice bench_clients "$WORK/bench_clients.md"
  local sweep=${THX_CLIENTS_SWEEP:-1,2,4,8,16,32,64} secs=${THX_CLIENTS_SWEEP_SECONDS:-20}
  [ "$sweep" = none ] && return $rc
  need "$BIN/bench_clients_plot" || return 1
  # One sweep: its name, workload, and extra hapticd options; bus ports 7950 (+ 66 for control and
  # data ports) apart from part 5's 7841.
  sweep_one() {
    local name=$1 w=$2 extra=()
    shift 2
    for a in "$@"; do extra+=(--hapticd-arg "$a"); done
    say "part 5b: client sweep $sweep, $name ($secs s per point; about $((7 * (secs + 5) / 60 + 1)) minutes)"
    "$BIN/bench_clients" --hapticd "$HAPTICD" --probe "$BUILD/clients/probe/probe-client" \
      --scene "$ROOT/scenes/default.yaml" --seconds "$secs" --baseline-seconds 10 --port 7950 \
      --workdir "$WORK" --clients-list "$sweep" --workload "$w" "${extra[@]}" \
      --json "$RESULTS/bench_clients_scale_$name.json" --csv "$RESULTS/bench_clients_scale_$name.csv" \
      --md "$WORK/bench_clients_scale_$name.md" >/dev/null || rc=1
    [ -s "$WORK/bench_clients_scale_$name.md" ] && splice "bench_clients_scale_$name" "$WORK/bench_clients_scale_$name.md"
  }
  local w plots=()
  for w in ${THX_CLIENTS_WORKLOADS:-mixed half}; do
    sweep_one "$w" "$w"
    plots+=("$w=$RESULTS/bench_clients_scale_$w.csv")
  done
  if [ "${THX_CLIENTS_COMPARE_SHARED:-1}" != 0 ]; then
    sweep_one mixed_shared mixed --data-ports off --control-port off
    plots+=("mixed shared port=$RESULTS/bench_clients_scale_mixed_shared.csv")
  fi
  "$BIN/bench_clients_plot" --png "$RESULTS/bench_clients_scale.png" "${plots[@]}" || rc=1
  return $rc
}

run_clients_lan() {
  need "$BIN/bench_clients_lan" && need "$HAPTICD" && need "$BUILD/clients/probe/probe-client" || return 1
  say "part 5c: 32 clients on one host and on two others of a virtual LAN, and a pulled cable (about 1.5 min)"
  "$BIN/bench_clients_lan" --hapticd "$HAPTICD" --probe "$BUILD/clients/probe/probe-client" \
    --scene "$ROOT/scenes/default.yaml" --seconds "${THX_CLIENTS_LAN_SECONDS:-20}" --workdir "$WORK" \
    --json "$RESULTS/bench_clients_lan.json" --md "$WORK/bench_clients_lan.md" || return 1
  splice bench_clients_lan "$WORK/bench_clients_lan.md"
}

run_physics() {
  need "$BIN/bench_physics" || return 1
  say "part 6: physics, time per step / memory / outcome error of five ground representations (about 1.5 min)"
  "$BIN/bench_physics" --json "$RESULTS/bench_physics.json" --csv "$RESULTS/bench_physics.csv" \
    --png "$RESULTS/bench_physics.png" --md "$WORK/bench_physics.md" || return 1
  splice bench_physics "$WORK/bench_physics.md"
}

run_audio() {
  need "$BIN/bench_audio_fem" || return 1
  say "part 7: audio, FEM modal analysis error / DOF / time / peak memory, Tet4 and Tet10 (about 2 min)"
  "$BIN/bench_audio_fem" --json "$RESULTS/bench_audio_fem.json" --csv "$RESULTS/bench_audio_fem.csv" \
    --md "$WORK/bench_audio_fem.md" || return 1
  splice bench_audio_fem "$WORK/bench_audio_fem.md" "$ROOT/docs/audio.md"
  need "$BIN/bench_audio_synth" || return 1
  say "part 7b: audio, synthesis speed per instruction set, float against double, compression against spectral error (about 1.5 min)"
  "$BIN/bench_audio_synth" --prefix "$RESULTS/bench_audio_synth" --md "$WORK/bench_audio_synth.md" > /dev/null || return 1
  splice bench_audio_synth "$WORK/bench_audio_synth.md" "$ROOT/docs/audio.md"
}

run_audio_live() {
  need "$BIN/bench_audio_live" && need "$HAPTICD" && need "$BUILD/clients/audio/audio-client" || return 1
  say "part 7c: live audio beside hapticd, alone / with audio-client / with --playout-ms 0 (about 3 min)"
  "$BIN/bench_audio_live" --hapticd "$HAPTICD" --audio-client "$BUILD/clients/audio/audio-client" \
    --scene "$ROOT/benchmarks/scenes/audio_scrape.yaml" --seconds "${THX_AUDIO_LIVE_SECONDS:-20}" \
    --rounds "${THX_AUDIO_LIVE_ROUNDS:-2}" --workdir "$WORK" --json "$RESULTS/bench_audio_live.json" \
    --csv "$RESULTS/bench_audio_live.csv" --md "$WORK/bench_audio_live.md" || return 1
  splice bench_audio_live "$WORK/bench_audio_live.md" "$ROOT/docs/audio.md"
}

run_visual() {
  need "$BIN/bench_visual" || return 1
  say "part 8: visual client, frame time against image error (normal / relief / mesh, about 3 min)"
  (cd "$ROOT" && "$BIN/bench_visual" --json "$RESULTS/bench_visual.json" --csv "$RESULTS/bench_visual.csv" \
    --md "$WORK/bench_visual.md") || return 1
  splice bench_visual "$WORK/bench_visual.md" "$ROOT/docs/visual.md"
}

run_visual_servo() {
  need "$BIN/bench_visual_servo" && need "$HAPTICD" && need "$BUILD/clients/visual/visual-client" || return 1
  say "part visual_servo: hapticd's wake latency alone and beside visual-client --live (6 runs of ${THX_VISUAL_SERVO_SECONDS:-20} s)"
  "$BIN/bench_visual_servo" --hapticd "$HAPTICD" --visual-client "$BUILD/clients/visual/visual-client" \
    --seconds "${THX_VISUAL_SERVO_SECONDS:-20}" --workdir "$WORK" --json "$RESULTS/bench_visual_servo.json" \
    --csv "$RESULTS/bench_visual_servo.csv" --md "$WORK/bench_visual_servo.md" || return 1
  splice bench_visual_servo "$WORK/bench_visual_servo.md" "$ROOT/docs/visual.md"
}

run_mesh_force() {
  need "$BIN/bench_mesh_force" || return 1
  say "part mesh_force: textured meshes, force error and render cost against triangles (about 2 min)"
  bench_with_table bench_mesh_force "$ROOT/docs/meshes.md" --png
}

run_physics_mesh() {
  need "$BIN/bench_physics_mesh" || return 1
  say "part physics_mesh: balls on tessellated spheres against the smooth sphere's answers (about 18 min on 2 cores)"
  bench_with_table bench_physics_mesh "$ROOT/docs/physics.md" --png
}

run_textured_pair() {
  need "$BIN/bench_textured_pair" || return 1
  say "part textured_pair: a grooved block on a grooved plane, slab mesh and box, the force to slide it each way (about 5 min)"
  bench_with_table bench_textured_pair "$ROOT/docs/physics.md"
}

run_pen_on_objects() {
  need "$BIN/bench_pen_on_objects" || return 1
  say "part pen_on_objects: a physics step with the pen or a ball on a plain and a textured object (about 5 s)"
  bench_with_table bench_pen_on_objects "$ROOT/docs/physics.md"
}

run_capsule_run() {
  need "$BIN/bench_capsule_run" || return 1
  say "part capsule_run: the search along a capsule's run over a textured box's face, its error by spacing (about 30 s)"
  bench_with_table bench_capsule_run "$ROOT/docs/physics.md"
}

run_textured_ball() {
  need "$BIN/bench_textured_ball" || return 1
  say "part textured_ball: a ball with a bump map rolling and at rest on relief planes and on meshes (about a minute)"
  bench_with_table bench_textured_ball "$ROOT/docs/physics.md"
}

run_ball_own_texels() {
  need "$BIN/bench_ball_own_texels" || return 1
  say "part ball_own_texels: a ball with a bump map on featureless or smooth ground, on its own texels (about two and a half minutes)"
  bench_with_table bench_ball_own_texels "$ROOT/docs/physics.md"
}

run_rolling_ridges() {
  need "$BIN/bench_rolling_ridges" || return 1
  say "part rolling_ridges: a ball across sine ridges, plane and mesh against the rolling-impact law (about half a minute)"
  bench_with_table bench_rolling_ridges "$ROOT/docs/physics.md"
}

run_rocking_on_curve() {
  need "$BIN/bench_rocking_on_curve" || return 1
  say "part rocking_on_curve: boxes and rods rocking on untextured curved meshes (seconds)"
  bench_with_table bench_rocking_on_curve "$ROOT/docs/physics.md" --png
}

run_object_by_crease() {
  need "$BIN/bench_object_by_crease" || return 1
  say "part object_by_crease: a block by a slab mesh's edge (seconds)"
  bench_with_table bench_object_by_crease "$ROOT/docs/physics.md"
}

run_ball_on_small_mesh() {
  need "$BIN/bench_ball_on_small_mesh" || return 1
  say "part ball_on_small_mesh: a ball pressed on meshes smaller than itself (about 25 s)"
  bench_with_table bench_ball_on_small_mesh "$ROOT/docs/physics.md"
}

run_block_by_pole() {
  need "$BIN/bench_block_by_pole" || return 1
  say "part block_by_pole: a block around the squeezed pole of a normal-mapped bowl, read five ways (about 20 s)"
  bench_with_table bench_block_by_pole "$ROOT/docs/physics.md"
}

run_lifted_swing() {
  need "$BIN/bench_lifted_swing" || return 1
  say "part lifted_swing: the lifted ball in a textured bowl against a rigid ball's rolling, and off a textured sphere (about 1 min)"
  bench_with_table bench_lifted_swing "$ROOT/docs/physics.md"
}

run_rod_in_groove() {
  need "$BIN/bench_rod_in_groove" || return 1
  say "part rod_in_groove: a rod in a V-groove on the relief plane and on relief meshes (about 15 s)"
  bench_with_table bench_rod_in_groove "$ROOT/docs/physics.md"
}

run_table1() {
  need "$BIN/bench_table1" || return 1
  say "part table1: the paper's Table 1 on one surface, normal / relief / mesh 256² / mesh 512² (about 10 min, 8 GB)"
  "$BIN/bench_table1" --scene "$ROOT/scenes/default.yaml" --workdir "$WORK" \
    --fem-mesh-sizes "${THX_TABLE1_MESH_SIZES:-24,32,48,64,96,128,256,512}" \
    --md "$RESULTS/table1.md" --csv "$RESULTS/table1.csv" > /dev/null || return 1
  splice table1 "$RESULTS/table1.md" "$ROOT/docs/table1.md"
}

run_report() {
  need "$BUILD/tools/report/bench_report" || return 1
  say "part report: docs/report.md from docs/results/ (tools/report/bench_report; measures nothing)"
  # From the root, so the report names its sources as docs/results/..., not this checkout's path.
  (cd "$ROOT" && "$BUILD/tools/report/bench_report" --results docs/results --out docs/report.md --pictures docs/report)
}

for part in "${PARTS[@]}"; do
  case "$part" in
    render | force_error | memory | latency | clients | clients_lan | physics | visual | visual_servo | audio | audio-live | load | rates | devices | capsule | table1 | mesh_force | physics_mesh | lifted_swing | block_by_pole | textured_pair | capsule_run | pen_on_objects | textured_ball | ball_own_texels | rolling_ridges | rod_in_groove | rocking_on_curve | object_by_crease | ball_on_small_mesh | report)
      if ! "run_${part//-/_}"; then
        say "part '$part' FAILED (logs in $WORK)"
        failed+=("$part")
      fi
      ;;
    *)
      say "unknown part '$part' (expected: render force_error memory latency clients clients_lan physics visual visual_servo audio audio-live load rates devices capsule table1 mesh_force physics_mesh lifted_swing block_by_pole textured_pair capsule_run pen_on_objects textured_ball ball_own_texels rolling_ridges rod_in_groove rocking_on_curve object_by_crease ball_on_small_mesh report)"
      exit 2
      ;;
  esac
done

if [ ${#failed[@]} -gt 0 ]; then
  say "done with failures: ${failed[*]}"
  exit 1
fi
say "done: results in docs/results/, tables in docs/benchmarks.md"
