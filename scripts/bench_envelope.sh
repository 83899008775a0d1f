#!/usr/bin/env bash
# The push-recovery envelope of the four walking policies beside the standing robot
# (nodes/tools/push_envelope.cpp), in both protocols: `standing` (an initial CoM velocity, feet
# still) and `midswing` (a base velocity change at half swing of the 4th step, walking in place),
# 8 directions x 0.2, 0.4, 0.6 m/s x seed 1, 20 steps each, two walks side by side on the 2
# cores. Prints one `BENCH walk.envelope` line per preset and protocol (preset=standing: the
# reference) and writes the polar figures and every walk to report/
# (push_envelope_<protocol>.svg, push_envelope_<protocol>.csv).
# Then the proposed preset in both protocols paying for its plans' time (plan_latency=measured).
# Then TALOS (config/talos.yaml) in the standing protocol: the baseline, kinematic and proposed
# presets and the standing robot at 0.2 and 0.4 m/s, its lines marked robot=talos
# (report/push_envelope_talos_standing.*).
#   scripts/bench_envelope.sh [--fine]      (--fine: magnitudes 0.1 to 1.0 m/s by 0.1, 2 seeds)
#   scripts/bench_envelope.sh --smoke DIR   (make test: the baseline, one push, 5 steps)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
cd "$REPO"
out=report
grid=(--magnitudes 0.2,0.4,0.6 --seeds 1)
case "${1:-}" in
  --fine) grid=(--fine --seeds 1,2) ;;
  --smoke) out="${2:?usage: scripts/bench_envelope.sh --smoke DIR}"
    grid=(--policies baseline --directions 1 --magnitudes 0.2 --seeds 1 --steps 5) ;;
esac
mkdir -p "$out"
for protocol in standing midswing; do
  "$BIN/push_envelope" --jobs 2 --standing --protocol "$protocol" "${grid[@]}" \
    --svg "$out/push_envelope_$protocol.svg" --csv "$out/push_envelope_$protocol.csv" \
    | grep '^BENCH'
  echo "figure: $(cd "$out" && pwd)/push_envelope_$protocol.svg"
done
# The proposed preset paying for its plans' wall time (walk.plan_latency measured: the simulation
# goes on while it plans), one walk at a time so that no other walk lengthens its plans; its
# lines end with plan_latency=measured (about 70 s per protocol).
if [ "${1:-}" != "--smoke" ]; then
  for protocol in standing midswing; do
    "$BIN/push_envelope" --jobs 1 --plan-latency measured --protocol "$protocol" \
      --policies proposed "${grid[@]}" --csv "$out/push_envelope_${protocol}_measured.csv" \
      | grep '^BENCH'
  done
  # TALOS (config/talos.yaml), standing protocol, the baseline, kinematic and proposed presets
  # beside the standing robot at 0.2 and 0.4 m/s (about 3 minutes); its lines carry robot=talos.
  "$BIN/push_envelope" --config config/talos.yaml --jobs 2 --standing --protocol standing \
    --policies baseline,kinematic,proposed --magnitudes 0.2,0.4 --seeds 1 \
    --svg "$out/push_envelope_talos_standing.svg" --csv "$out/push_envelope_talos_standing.csv" \
    | grep '^BENCH' | sed 's/^BENCH walk.envelope /BENCH walk.envelope robot=talos /'
  echo "figure: $(cd "$out" && pwd)/push_envelope_talos_standing.svg"
fi
