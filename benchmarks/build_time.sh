#!/bin/bash
# Where `make test`'s time goes (docs/build.md): runs it from fresh build directories with ccache
# off, every compile and link logged with its CPU time through a compiler launcher (the commands
# themselves are the Makefile's), then sums the log per tree, per target and per file.
set -euo pipefail

usage() {
  cat <<'EOF'
Usage: benchmarks/build_time.sh [OUT_DIR]            run `make test` and summarise it
       benchmarks/build_time.sh --summary OUT_DIR    summarise a finished run again
OUT_DIR (default out/build_time) gets the two build trees (build, build-asan), steps.csv (one row
per compile or link: start, user_s, sys_s, wall_s, max_rss_kb, kind, dir, output), make_test.log
(each line stamped with its time), load.txt (the load average every 20 s) and summary.txt.
CPU seconds (user + sys) do not depend on what else runs on the machine; wall time does, so the
summary names the load. About 25 minutes on 2 idle cores; the tests must pass for a full summary.
EOF
}

ROOT=$(cd "$(dirname "$0")/.." && pwd)
case "${1:-}" in
  -h|--help) usage; exit 0 ;;
  --summary)
    [ $# -eq 2 ] || { usage >&2; exit 2; }
    exec python3 "$ROOT/benchmarks/build_time_summary.py" "$2" ;;
  -*) echo "build_time.sh: unknown option '$1' (expected --help or --summary OUT_DIR)" >&2; exit 2 ;;
esac
OUT=${1:-$ROOT/out/build_time}
mkdir -p "$OUT"; OUT=$(cd "$OUT" && pwd)
if [ -e "$OUT/build" ] || [ -e "$OUT/build-asan" ]; then
  echo "build_time.sh: $OUT already holds build trees; give a fresh OUT_DIR (the run must start from nothing)" >&2
  exit 2
fi

# The launcher: one line per call, appended (short lines: concurrent appends stay whole).
cat > "$OUT/launcher.sh" <<'EOF'
#!/bin/bash
out="?"; prev=""
for a in "$@"; do [ "$prev" = "-o" ] && out="$a"; prev="$a"; done
kind=link; case " $* " in *" -c "*) kind=compile;; esac
exec /usr/bin/time -a -o "$THX_STEPS" -f "$(date +%s.%N),%U,%S,%e,%M,$kind,$PWD,$out" "$@"
EOF
chmod +x "$OUT/launcher.sh"
echo "start,user_s,sys_s,wall_s,max_rss_kb,kind,dir,output" > "$OUT/steps.csv"

export CCACHE_DISABLE=1 THX_STEPS="$OUT/steps.csv"
# CMake (>= 3.21) takes the launchers from these variables when it configures a tree.
export CMAKE_CXX_COMPILER_LAUNCHER="$OUT/launcher.sh" CMAKE_C_COMPILER_LAUNCHER="$OUT/launcher.sh"
export CMAKE_CXX_LINKER_LAUNCHER="$OUT/launcher.sh" CMAKE_C_LINKER_LAUNCHER="$OUT/launcher.sh"

( while true; do echo "$(date +%s) $(cat /proc/loadavg)" >> "$OUT/load.txt"; sleep 20; done ) &
sampler=$!
trap 'kill $sampler 2>/dev/null || true' EXIT

date +%s > "$OUT/start"
set +e
( cd "$ROOT" && /usr/bin/time -o "$OUT/make_test.time" -f "%U %S %e" \
    make test BUILD="$OUT/build" BUILD_ASAN="$OUT/build-asan" ) 2>&1 |
  perl -MTime::HiRes -pe '$|=1; s/^/sprintf("%.1f ", Time::HiRes::time())/e' > "$OUT/make_test.log"
rc=${PIPESTATUS[0]}
set -e
date +%s > "$OUT/end"
echo "$rc" > "$OUT/make_test.rc"
python3 "$ROOT/benchmarks/build_time_summary.py" "$OUT"
exit "$rc"
