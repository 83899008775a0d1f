#!/usr/bin/env bash
# The verdict oracle (nodes/tools/verdict_grid.cpp): from bench/reach's case and the footsteps
# of the demo's pushed proposed walk (steps 1, 2 and 5, test/fixtures/pushed_walk_requests.jsonl,
# written by `walk_experiment --push 0,0.4 --plan-requests`), a grid of N x N footholds within
# +-0.15 m of each planned one, each checked by the planner (verdict, certificate re-checked
# independently) and by the strict OCP seeded without the witness. Prints `BENCH reach.verdict`.
# The shipped configuration plans each step with the quick pass first (reach.quick_pass); every
# foothold is also checked with config/reach_reference.yaml's (the full budget only):
# `BENCH reach.verdict_fast ref=reference agreement=..` from the same run, and the check on its
# own (its adaptive budget, which may give up after the quick budget) against the reference's:
# `BENCH reach.verdict_check ref=reference agreement=.. ref_only_reachable=..`.
# Last, TALOS legs: `BENCH reach.verdict_talos` (the same oracle on another robot).
#   scripts/bench_verdict.sh [grid N = 7 [verdict_grid options ...]]
# (the options, e.g. --max-states 1, go to both runs; TALOS's grid is min(N, 3)).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
cd "$REPO"
grid="${1:-7}"
shift || true
talos_grid=$((grid < 3 ? grid : 3))
"$BIN/verdict_grid" --bench-case --requests test/fixtures/pushed_walk_requests.jsonl \
  --grid "$grid" --half-width 0.15 --reference-config config/reach_reference.yaml "$@"
# TALOS legs (config/talos.yaml): 3 footsteps of its pushed proposed walk
# (test/fixtures/talos_walk_requests.jsonl, `walk_experiment --config config/talos.yaml
# --policy proposed --steps 3 --push 0,0.3 --plan-requests`), 3 x 3 footholds within +-0.1 m.
"$BIN/verdict_grid" --config config/talos.yaml --requests test/fixtures/talos_walk_requests.jsonl \
  --grid "$talos_grid" --half-width 0.1 "$@" | sed 's/^BENCH reach.verdict /BENCH reach.verdict_talos /'
