#!/usr/bin/env bash
# Builds bench/reach against the core library of the catkin workspace (run scripts/build first)
# and prints its BENCH lines: the paper's reachability case with the shipped configuration
# (config/biped.yaml's reach budget; initial_samples 10000 gives the paper's first step).
# With `reference` as the first argument: the same with config/reach_reference.yaml (the slow
# settings before the fast check), for the before / after comparison of bench/README.md.
#   scripts/bench_reach.sh [reference] [repeats] [initial_samples]
# Build directory: $REACH_WS/bench_reach (REACH_WS defaults to .build_ws, as in scripts/env.sh).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/bench_lib.sh"
bench_need_core
build="$WS/bench_reach"
cmake -S "$REPO/bench/reach" -B "$build" -DCMAKE_BUILD_TYPE=Release -DREACH_WS="$WS" >/dev/null
cmake --build "$build" -j2 >/dev/null
if [ "${1:-}" = reference ]; then
  shift
  "$build/bench_reach" "${1:-3}" "${2:-0}" "$REPO/config/reach_reference.yaml"
else
  "$build/bench_reach" "${1:-3}" "${2:-0}"
fi
