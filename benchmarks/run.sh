#!/usr/bin/env bash
# Runs the benchmarks and regenerates their results: docs/results/bench_*.{json,csv,png} and the
# tables in docs/benchmarks.md (between the <!-- BEGIN bench_X --> / <!-- END bench_X --> markers).
#
# Usage: benchmarks/run.sh [BUILD_DIR] [PART...]
#   BUILD_DIR  a configured and built tree (default: build); build it first with
#              cmake -S . -B BUILD_DIR -DCMAKE_BUILD_TYPE=RelWithDebInfo && cmake --build BUILD_DIR -j2 --target benchmarks
#   PART       any of: render force_error memory latency clients physics (default: all six, in that order)
#
# The clients part can also sweep the number of clients (issue 17): set THX_CLIENTS_SWEEP to the
# counts (e.g. 1,2,4,8,16,32,64), optionally THX_CLIENTS_WORKLOADS (default "mixed half": 1/4 resp.
# 1/2 of the clients batched CONTACT at 1 kHz, the rest DEVICE_STATE at 60 Hz),
# THX_CLIENTS_SWEEP_SECONDS (10 per point) and THX_CLIENTS_HAPTICD_ARGS (extra hapticd options,
# e.g. "--data-port-base 7900"). Writes docs/results/bench_clients_scale_WORKLOAD.{json,csv} and
# splices the bench_clients_scale_WORKLOAD table if docs/benchmarks.md has its markers.
#
# Needs: the built benchmarks and hapticd; cyclictest (Debian rt-tests, in setup.sh) for latency;
# root or CAP_SYS_NICE + CAP_IPC_LOCK for SCHED_FIFO and mlockall (without them the latency and
# memory tables say so). Takes about 6 minutes (clients: 2 minutes, physics: 1.5). Timing on a shared machine is noisy: compare
# ratios within one run.
set -uo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-build}
[ $# -gt 0 ] && shift
case "$BUILD" in /*) ;; *) BUILD="$ROOT/$BUILD" ;; esac
PARTS=("$@")
[ ${#PARTS[@]} -eq 0 ] && PARTS=(render force_error memory latency clients physics)

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

# Replaces the lines between <!-- BEGIN name --> and <!-- END name --> in docs/benchmarks.md.
splice() {
  local name=$1 fragment=$2
  if ! grep -q "^<!-- BEGIN $name -->$" "$DOC"; then
    say "warning: no '<!-- BEGIN $name -->' marker in $DOC; table not updated"
    return 0
  fi
  awk -v name="$name" -v frag="$fragment" '
    $0 == "<!-- BEGIN " name " -->" { print; while ((getline line < frag) > 0) print line; skip = 1; next }
    $0 == "<!-- END " name " -->" { skip = 0 }
    !skip { print }
  ' "$DOC" > "$DOC.tmp" && mv "$DOC.tmp" "$DOC"
  say "updated the $name table in docs/benchmarks.md"
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
  say "part 2: force error against the exact height-field contact (about 60 s)"
  "$BIN/bench_force_error" --json "$RESULTS/bench_force_error.json" --csv "$RESULTS/bench_force_error.csv" \
    --png "$RESULTS/bench_force_error.png" --md "$WORK/bench_force_error.md" || return 1
  splice bench_force_error "$WORK/bench_force_error.md"
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

run_clients() {
  need "$BIN/bench_clients" && need "$HAPTICD" && need "$BUILD/clients/probe/probe-client" || return 1
  say "part 5: 16 clients against hapticd (60 s), and hapticd alone before and after (30 s each)"
  "$BIN/bench_clients" --hapticd "$HAPTICD" --probe "$BUILD/clients/probe/probe-client" \
    --scene "$ROOT/scenes/default.yaml" --seconds 60 --baseline-seconds 30 --workdir "$WORK" \
    --json "$RESULTS/bench_clients.json" --csv "$RESULTS/bench_clients.csv" --md "$WORK/bench_clients.md"
  local rc=$?
  [ -s "$WORK/bench_clients.md" ] && splice bench_clients "$WORK/bench_clients.md"
  if [ -n "${THX_CLIENTS_SWEEP:-}" ]; then
    local w extra=()
    read -r -a hargs <<< "${THX_CLIENTS_HAPTICD_ARGS:-}"
    for a in "${hargs[@]}"; do extra+=(--hapticd-arg "$a"); done
    for w in ${THX_CLIENTS_WORKLOADS:-mixed half}; do
      say "part 5b: client sweep $THX_CLIENTS_SWEEP, workload $w (${THX_CLIENTS_SWEEP_SECONDS:-10} s per point)"
      "$BIN/bench_clients" --hapticd "$HAPTICD" --probe "$BUILD/clients/probe/probe-client" \
        --scene "$ROOT/scenes/default.yaml" --seconds "${THX_CLIENTS_SWEEP_SECONDS:-10}" --baseline-seconds 10 \
        --workdir "$WORK" --clients-list "$THX_CLIENTS_SWEEP" --workload "$w" "${extra[@]}" \
        --json "$RESULTS/bench_clients_scale_$w.json" --csv "$RESULTS/bench_clients_scale_$w.csv" \
        --md "$WORK/bench_clients_scale_$w.md" >/dev/null || rc=1
      [ -s "$WORK/bench_clients_scale_$w.md" ] && splice "bench_clients_scale_$w" "$WORK/bench_clients_scale_$w.md"
    done
  fi
  return $rc
}

run_physics() {
  need "$BIN/bench_physics" || return 1
  say "part 6: physics, time per step / memory / outcome error of five ground representations (about 1.5 min)"
  "$BIN/bench_physics" --json "$RESULTS/bench_physics.json" --csv "$RESULTS/bench_physics.csv" \
    --png "$RESULTS/bench_physics.png" --md "$WORK/bench_physics.md" || return 1
  splice bench_physics "$WORK/bench_physics.md"
}

for part in "${PARTS[@]}"; do
  case "$part" in
    render | force_error | memory | latency | clients | physics)
      if ! "run_$part"; then
        say "part '$part' FAILED (logs in $WORK)"
        failed+=("$part")
      fi
      ;;
    *)
      say "unknown part '$part' (expected: render force_error memory latency clients physics)"
      exit 2
      ;;
  esac
done

if [ ${#failed[@]} -gt 0 ]; then
  say "done with failures: ${failed[*]}"
  exit 1
fi
say "done: results in docs/results/, tables in docs/benchmarks.md"
