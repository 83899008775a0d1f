# Sourced by the scripts/bench_*.sh benchmarks instead of env.sh: env.sh, the name the
# benchmark's messages start with, and its checks that what it needs is there.
# shellcheck shell=bash
# shellcheck disable=SC1091
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
BENCH_NAME="$(basename "${BASH_SOURCE[1]}" .sh)"
# The catkin-built core library the benchmark projects link.
CORE_LIBRARY="$WS/devel/lib/libreach_trajopt_core.so"

# bench_need TEST PATH HINT: stops with "[bench_x] PATH not found: HINT" unless `test TEST PATH`
# holds (-e exists, -f a file, -d a folder, -x an executable).
bench_need() {
  if ! test "$1" "$2"; then
    echo "[$BENCH_NAME] $2 not found: $3" >&2
    exit 1
  fi
}

# bench_need_core: the core library, built first by scripts/build (same REACH_WS).
bench_need_core() {
  bench_need -f "$CORE_LIBRARY" "build first (REACH_WS=$WS bash scripts/build)"
}
