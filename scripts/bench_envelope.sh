#!/usr/bin/env bash
# The push-recovery envelope of the four walking policies (nodes/tools/push_envelope.cpp):
# pushes (initial CoM velocities) in 8 directions x 0.2, 0.4, 0.6 m/s x seeds 1 and 2, 20 steps
# each, two walks side by side on the 2 cores. Prints one `BENCH walk.envelope` line per preset
# and writes the polar figure and every walk to report/ (push_envelope.svg, push_envelope.csv).
#   scripts/bench_envelope.sh [--fine]   (--fine: magnitudes 0.1 to 0.8 m/s by 0.1)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
cd "$REPO"
mkdir -p report
"$BIN/push_envelope" --jobs 2 --svg report/push_envelope.svg --csv report/push_envelope.csv "$@" \
  | grep '^BENCH'
echo "figure: $REPO/report/push_envelope.svg"
