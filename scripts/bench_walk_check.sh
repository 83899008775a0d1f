#!/usr/bin/env bash
# The reachability check inside the walk: the proposed walk of the demo (20 steps in place, the
# base pushed 0.4 m/s backward at half swing of step 4, config/biped.yaml) run with 2 and with 1 OpenMP threads (the seeded sampler
# gives the same sets, verdicts and therefore the same walk for any thread count), the
# check's wall time of every step that ran it (kinematically infeasible footholds stop before
# it). Prints
#   BENCH reach.walk_check threads=2 mean_s=.. max_s=.. checks=.. ... ocp_mean_s=.. step_max_s=..
#     load_avg=..
#   BENCH reach.walk_check threads=1 ...  and  BENCH reach.walk_check_speedup ratio=..
# and the same walk with the sampler seeds 2-5 (2 threads): a check that the quick pass cannot
# end costs a retry or a hull or full pass, so one walk's max says little about the next one's:
#   BENCH reach.walk_check_seeds seeds=2-5 checks=.. mean_s=.. median_s=.. p90_s=.. max_s=..
#     beyond_quick=.. falls=.. ocp_mean_s=.. ocp_max_s=.. step_max_s=..
# ocp_*: the transition OCP's wall time of those steps; step_max_s: the largest check + OCP of
# one step (what the step's planning takes in all). Over every step of the demo walk (2 threads)
# that solved the OCP (the kinematically infeasible ones too: they solve it for the nearest
# feasible foothold), and of the demo's TALOS walk (config/talos.yaml, push 0.3 m/s):
#   BENCH ocp.walk robot=biped|talos mean_s=.. max_s=.. p95_s=.. steps=..
#   BENCH walk.plan_latency robot=biped|talos p50_s=.. p95_s=.. max_s=..   (check + OCP per step)
#   scripts/bench_walk_check.sh [steps = 20] [config = config/biped.yaml]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
cd "$REPO"
steps="${1:-20}"
config="${2:-config/biped.yaml}"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for t in 2 1; do
  OMP_NUM_THREADS=$t "$BIN/walk_experiment" --config "$config" --mode proposed --steps "$steps" \
    --midswing-push -0.4,0 > "$out/walk_$t.log"
done
# The demo's TALOS walk (scripts/demo: lateral push 0.3 m/s) for its OCP times.
OMP_NUM_THREADS=2 "$BIN/walk_experiment" --config config/talos.yaml --mode proposed \
  --steps "$steps" --push 0,0.3 > "$out/talos.log"
seeds="2 3 4 5"
for seed in $seeds; do
  OMP_NUM_THREADS=2 "$BIN/walk_experiment" --config "$config" --mode proposed --steps "$steps" \
    --midswing-push -0.4,0 --seed "$seed" > "$out/seed_$seed.log"
done
/usr/bin/python3 - "$out" $seeds <<'PY'
import re, sys, os
def stats(path, beyond=None, ocp=None):
    times, verdicts = [], []
    for line in open(path):
        if not line.startswith("step "):
            continue
        v = re.search(r" verdict=(\S+) certificate=(\S+)", line)
        t = re.search(r" check_s=([0-9.eE+-]+)", line)
        verdicts.append(v.group(1) + "/" + v.group(2))
        if v.group(1) != "kinematically_infeasible":
            times.append(float(t.group(1)))
            if ocp is not None:
                ocp.append(float(re.search(r" ocp_s=([0-9.eE+-]+)", line).group(1)))
            if beyond is not None and " passes=1 " not in line:
                beyond.append(line)
    return times, verdicts
load = os.getloadavg()[0]
res = {}
for t in (2, 1):
    ocp_t = []
    times, verdicts = stats(os.path.join(sys.argv[1], f"walk_{t}.log"), None, ocp_t)
    if not times:
        sys.exit("bench_walk_check: no step ran the check")
    res[t] = (sum(times) / len(times), times, verdicts)
    s = sorted(times)
    print(f"BENCH reach.walk_check threads={t} mean_s={res[t][0]:.3f} max_s={s[-1]:.3f} "
          f"median_s={s[len(s) // 2]:.3f} checks={len(times)} "
          f"reachable={sum(v.startswith('reachable') for v in verdicts)} "
          f"bridge={sum(v.endswith('/bridge') for v in verdicts)} "
          f"ocp_mean_s={sum(ocp_t) / len(ocp_t):.3f} "
          f"step_max_s={max(c + o for c, o in zip(times, ocp_t)):.3f} load_avg={load:.2f}")
def plan_times(path):
    """(ocp_s of every step that solved the OCP, check_s + ocp_s of every step that planned)."""
    ocp, plan = [], []
    for line in open(path):
        if not line.startswith("step "):
            continue
        c = float(re.search(r" check_s=([0-9.eE+-]+)", line).group(1))
        o = float(re.search(r" ocp_s=([0-9.eE+-]+)", line).group(1))
        if o > 0:
            ocp.append(o)
        if c + o > 0:
            plan.append(c + o)
    return ocp, plan
def rank(values, p):
    """Nearest-rank percentile."""
    s = sorted(values)
    return s[max(0, min(len(s) - 1, int(-(-p * len(s) // 100)) - 1))]
for robot, log in (("biped", "walk_2.log"), ("talos", "talos.log")):
    ocp, plan = plan_times(os.path.join(sys.argv[1], log))
    if not ocp:
        sys.exit(f"bench_walk_check: no step of the {robot} walk solved the OCP")
    print(f"BENCH ocp.walk robot={robot} mean_s={sum(ocp) / len(ocp):.3f} max_s={max(ocp):.3f} "
          f"p95_s={rank(ocp, 95):.3f} steps={len(ocp)} threads=2")
    print(f"BENCH walk.plan_latency robot={robot} p50_s={rank(plan, 50):.3f} "
          f"p95_s={rank(plan, 95):.3f} max_s={max(plan):.3f} steps={len(plan)} threads=2")
same = res[1][2] == res[2][2]
print(f"BENCH reach.walk_check_speedup threads=2 ratio={res[1][0] / res[2][0]:.2f} "
      f"same_walk={'yes' if same else 'no'}")
seeds = sys.argv[2:]
times, beyond, ocp, falls = [], [], [], 0
for seed in seeds:
    path = os.path.join(sys.argv[1], f"seed_{seed}.log")
    times += stats(path, beyond, ocp)[0]
    falls += sum(l.startswith("WALK") and " fell=yes" in l for l in open(path))
s = sorted(times)
step_max = max(c + o for c, o in zip(times, ocp))
print(f"BENCH reach.walk_check_seeds seeds={seeds[0]}-{seeds[-1]} threads=2 checks={len(s)} "
      f"mean_s={sum(s) / len(s):.3f} median_s={s[len(s) // 2]:.3f} "
      f"p90_s={s[int(0.9 * (len(s) - 1))]:.3f} max_s={s[-1]:.3f} beyond_quick={len(beyond)} "
      f"falls={falls} ocp_mean_s={sum(ocp) / len(ocp):.3f} ocp_max_s={max(ocp):.3f} "
      f"step_max_s={step_max:.3f}")
PY
