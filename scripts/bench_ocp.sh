#!/usr/bin/env bash
# Builds bench/ocp against the catkin-built core library and prints its BENCH lines:
#   BENCH ocp.<case> ours_s=... iters=... (three footsteps of the biped; see bench_ocp.cpp).
#   scripts/bench_ocp.sh [repeats]
# Build directory: $REACH_WS/bench_ocp (REACH_WS defaults to .build_ws, as in scripts/env.sh).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
core="$WS/devel/lib/libreach_trajopt_core.so"
if [ ! -f "$core" ]; then
  echo "[bench_ocp] $core not found: run scripts/build first" >&2
  exit 1
fi
build="$WS/bench_ocp"
cmake -S "$REPO/bench/ocp" -B "$build" -DCMAKE_BUILD_TYPE=Release \
  -DREACH_CORE_LIBRARY="$core" >/dev/null
cmake --build "$build" -j2 >/dev/null
"$build/bench_ocp" "${1:-3}"
