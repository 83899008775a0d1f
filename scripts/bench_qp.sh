#!/usr/bin/env bash
# Builds bench/qp (the bundled QP against eiquadprog's C++ from the venv wheel, in its own CMake
# project so the product never links eiquadprog) and prints its BENCH lines.
#   scripts/bench_qp.sh [scale]   scale multiplies the number of problems (default 1)
# Build directory: $REACH_WS/bench_qp (REACH_WS defaults to .build_ws, as in scripts/env.sh).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/bench_lib.sh"
prefix="$VENV/lib/python3.11/site-packages/cmeel.prefix"
bench_need -d "$prefix/lib/cmake/eiquadprog" "(the eiquadprog wheel) run scripts/bootstrap"
build="$WS/bench_qp"
cmake -S "$REPO/bench/qp" -B "$build" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_USE_CMAKE_SYSTEM_PATH=OFF >/dev/null
cmake --build "$build" -j2 >/dev/null
"$build/bench_qp" "${1:-1}"
