#!/usr/bin/env bash
# Builds bench/ocp against the catkin-built core library and IPOPT (benchmark-only: Debian's
# coinor-libipopt-dev, installed by `scripts/bootstrap --bench`, i.e. by `make bench`) and prints
# one BENCH line per footstep (three footsteps of the biped; see bench_ocp.cpp):
#   BENCH ocp.<case> ours_s=... iters=... ... status=... ref=ipopt ref_s=... ref_iters=...
#         ref_status=... ... ratio=<ours_s / ref_s> cost=... ref_cost=... ref_solver_s=...
#   scripts/bench_ocp.sh [repeats]
# Build directory: $REACH_WS/bench_ocp (REACH_WS defaults to .build_ws, as in scripts/env.sh).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/bench_lib.sh"
bench_need_core
core="$CORE_LIBRARY"
if ! pkg-config --exists ipopt; then
  echo "[bench_ocp] IPOPT (ipopt.pc) not found: run scripts/bootstrap --bench" >&2
  exit 1
fi
build="$WS/bench_ocp"
mkdir -p "$build"
cmake -S "$REPO/bench/ocp" -B "$build" -DCMAKE_BUILD_TYPE=Release \
  -DREACH_CORE_LIBRARY="$core" >"$build/configure.log" 2>&1 || {
  cat "$build/configure.log" >&2; echo "[bench_ocp] cmake configure failed" >&2; exit 1; }
cmake --build "$build" -j2 >"$build/build.log" 2>&1 || {
  tail -n 40 "$build/build.log" >&2; echo "[bench_ocp] build failed" >&2; exit 1; }
"$build/bench_ocp" "${1:-3}"
