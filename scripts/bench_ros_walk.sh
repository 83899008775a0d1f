#!/usr/bin/env bash
# The cost of running the stepping loop through the nodes: the same proposed walk (6 steps after
# the demo's 0.4 m/s lateral push, seed 1) by walk.launch with in_process:=false (every checked
# footstep planned by transition_ocp_node's plan_footstep) and in_process:=true (planned in
# sim_node), alternately, `repeats` times each, on a private roscore. Prints every WALK line
# (their fields beyond wall_s must be equal: same_walk) and
#   BENCH ros.walk_overhead ratio=<node-wired wall_s / in-process wall_s> ...
# (target <= 1.1) from the fastest run of each (the machine is shared: the slower runs measure
# the neighbours). wall_s is the walking loop's own wall time, not the nodes' start-up.
#   scripts/bench_ros_walk.sh [steps [repeats]]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
steps="${1:-6}"
repeats="${2:-2}"
export ROS_MASTER_URI="http://localhost:$((11400 + RANDOM % 500))"
roscore -p "${ROS_MASTER_URI##*:}" > /dev/null 2>&1 &
master=$!
trap 'kill $master 2>/dev/null || true' EXIT
sleep 3
walk() {  # $1: in_process
  roslaunch reach_trajopt walk.launch policy:=proposed steps:="$steps" seed:=1 push_vy:=0.4 \
    in_process:="$1" 2>&1 | sed 's/\x1b\[[0-9;]*m//g' | grep -o 'WALK .*' | head -n 1
}
lines=()
for ((i = 0; i < repeats; ++i)); do
  lines+=("nodes $(walk false)")
  lines+=("in_process $(walk true)")
done
printf '%s\n' "${lines[@]}"
printf '%s\n' "${lines[@]}" | /usr/bin/python3 -c '
import sys
runs = []
for line in sys.stdin.read().splitlines():
    how, _, walk = line.split(" ", 2)
    kv = dict(t.split("=", 1) for t in walk.split()[1:] if "=" in t)
    runs.append((how, kv))
key = lambda kv: {k: v for k, v in kv.items() if k != "wall_s"}
same = all(key(kv) == key(runs[0][1]) for _, kv in runs)
best = {how: min(float(kv["wall_s"]) for h, kv in runs if h == how) for how in ("nodes", "in_process")}
steps = runs[0][1]["steps"]
print("BENCH ros.walk_overhead ratio=%.3f nodes_wall_s=%.3f in_process_wall_s=%.3f steps=%s "
      "runs=%d same_walk=%s target=1.1" % (best["nodes"] / best["in_process"], best["nodes"],
      best["in_process"], steps, len(runs), "yes" if same else "no"))
sys.exit(0 if same else 1)
'
