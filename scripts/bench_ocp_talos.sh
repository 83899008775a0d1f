#!/usr/bin/env bash
# Our transition OCP beside Crocoddyl on one TALOS step (issue 18 part 3), both re-checked at 1 ms
# by our full-model checker (check_transition: eq. 1, stance contact, cones, torque and joint
# limits, x(t_0) = x_0, x(t_f) = x_f). The step: bench/crocoddyl/talos_step_request.json (see
# bench/crocoddyl/README.md). Ours: plan_transition --config config/talos.yaml. References:
# bench/crocoddyl/talos_step.py in the bench-only venv .venv-croc/ (scripts/bootstrap --bench):
# Crocoddyl 3.2.1 FDDP and mim-solvers CSQP from the same x_0 and x_f. Prints
#   BENCH ocp.talos_step ours_s=.. violation=.. ref=crocoddyl_fddp ref_s=.. ref_violation=.. ratio=..
#   BENCH ocp.talos_step ours_s=.. violation=.. ref=mim_solvers_csqp ref_s=.. ref_violation=.. ratio=..
# (ratio = ours_s / ref_s; violation = the checker's largest family; times are medians over
# `repeats` solves, ours = plan_transition's solve_time, the references' solver.solve()), then the
# same two lines for Crocoddyl on 1 ms knots (ocp.talos_step_knots_1ms, one solve each).
#   scripts/bench_ocp_talos.sh [repeats]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/bench_lib.sh"
repeats="${1:-3}"
req="$REPO/bench/crocoddyl/talos_step_request.json"
cfg="$REPO/config/talos.yaml"
py="$REPO/.venv-croc/bin/python"
bench_need -x "$py" "run scripts/bootstrap --bench"
for tool in plan_transition check_transition; do
  bench_need -x "$BIN/$tool" "run scripts/build"
done
out="$WS/bench_ocp_talos"
mkdir -p "$out"
cd "$REPO"

field() {  # field FILE KEY.PATH: a number of a JSON file
  /usr/bin/python3 -c 'import json, sys
d = json.load(open(sys.argv[1]))
for k in sys.argv[2].split("."): d = d[k]
print(d)' "$1" "$2"
}

times=()
for ((i = 0; i < repeats; i++)); do
  "$BIN/plan_transition" "$req" --config "$cfg" >"$out/ours.json" || {
    echo "[bench_ocp_talos] plan_transition failed: $(head -c 400 "$out/ours.json")" >&2; exit 1; }
  times+=("$(field "$out/ours.json" solve_time)")
done
ours_s=$(printf '%s\n' "${times[@]}" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
"$BIN/check_transition" "$req" "$out/ours.json" --config "$cfg" >"$out/ours_check.json"
ours_v=$(field "$out/ours_check.json" violation.max)
echo "[bench_ocp_talos] ours: status=$(field "$out/ours.json" status)" \
  "iterations=$(field "$out/ours.json" iterations) solves=$(field "$out/ours.json" solves)"

run_refs() {  # run_refs NAME KNOT_DT REPEATS
  local name="$1" knot_dt="$2" n="$3" dir="$out/knots_$2"
  "$py" bench/crocoddyl/talos_step.py --request "$req" --config "$cfg" --out-dir "$dir" \
    --repeats "$n" --knot-dt "$knot_dt" | tee "$dir.log"
  while read -r _ solver ref_s _; do
    solver="${solver#solver=}"
    ref_s="${ref_s#ref_s=}"
    "$BIN/check_transition" "$req" "$dir/$solver.json" --config "$cfg" >"$dir/${solver}_check.json"
    ref_v=$(field "$dir/${solver}_check.json" violation.max)
    ratio=$(/usr/bin/python3 -c "print(f'{$ours_s / $ref_s:.3f}')")
    printf 'BENCH %s ours_s=%.4f violation=%.3g ref=%s ref_s=%.4f ref_violation=%.3g ratio=%s\n' \
      "$name" "$ours_s" "$ours_v" "$solver" "$ref_s" "$ref_v" "$ratio"
  done < <(grep '^REF ' "$dir.log")
}
mkdir -p "$out/knots_0.01" "$out/knots_0.001"
run_refs ocp.talos_step 0.01 "$repeats"
run_refs ocp.talos_step_knots_1ms 0.001 1
