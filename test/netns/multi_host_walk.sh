#!/usr/bin/env bash
# The walk on four hosts: one Linux network namespace per host, each with its own address on a
# bridge (veth pairs into a fifth namespace holding the bridge), ROS_IP and ROS_MASTER_URI per
# host, faults injected from outside the processes by nftables rules in the hosts' namespaces:
#   host 0 (10.43.0.1): master, sim_node, tvr_planner_node, the recorder (a bag), the checker
#   host 1 (10.43.0.2): transition_ocp_node and its reachability_node (check_footstep)
#   host 2 (10.43.0.3): reachability worker 0, with a random packet loss on its link
#                       (`numgen random mod 100 < LOSS drop`, in and out)
#   host 3 (10.43.0.4): reachability worker 1, partitioned (every packet from and to the other
#                       hosts dropped) once it has answered a ring of the first search, healed
#                       once transition_ocp_node has noticed (its warning)
# test/netns/hosts.launch says which node runs where. The checker (check_walk_nodes, as in
# workers_walk.test) compares the WALK line and every step report with the same walk run in
# process, byte for byte, and asserts that both workers checked candidates; this script also
# checks that the bag holds every step report, that transition_ocp_node noticed the partition
# (its warning, within worker_timeout of a call) and that worker 1 checked candidates again
# after the partition healed (its latched footholds_checked grew). tc netem (delay) would go
# beside the loss where the kernel has it; these kernels do not (CONFIG_NET_SCH_NETEM unset),
# so the faults that run are loss and partition. Prints
#   BENCH ros.multi_host hosts=4 loss=<%> partitions=1 same_walk=yes lost_msgs=0 rejoined=yes ...
# and writes one JUnit case (netns-multi_host.xml in RESULTS_DIR): skipped, with the reason,
# where namespaces cannot be made (not root, no nft, no netns support).
#   test/netns/multi_host_walk.sh RESULTS_DIR [LOSS_PERCENT = 5]
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../../scripts/env.sh"
results="${1:?usage: multi_host_walk.sh RESULTS_DIR [LOSS_PERCENT]}"
loss="${2:-5}"
mkdir -p "$results"
xml="$results/netns-multi_host.xml"
work=$(mktemp -d /tmp/multi_host.XXXXXX)
steps=6
t_start=$(date +%s)

junit() {  # junit passed|failed|skipped MESSAGE
  /usr/bin/python3 - "$xml" "$1" "$2" "$(($(date +%s) - t_start))" <<'PY'
import sys
from xml.sax.saxutils import quoteattr
path, status, msg, secs = sys.argv[1:]
body = {"failed": f"<failure message={quoteattr(msg)}/>",
        "skipped": f"<skipped message={quoteattr(msg)}/>"}.get(status, "")
open(path, "w").write(
    '<?xml version="1.0"?>\n<testsuite name="netns" tests="1" failures="%d" skipped="%d">\n'
    '  <testcase classname="netns" name="multi_host_walk" time="%s">%s</testcase>\n'
    "</testsuite>\n" % (status == "failed", status == "skipped", secs, body))
PY
}
skip() {
  echo "[multi_host] SKIPPED: $1"
  junit skipped "$1"
  exit 0
}

[ "$(id -u)" = 0 ] || skip "not root: network namespaces need CAP_NET_ADMIN"
command -v ip >/dev/null || skip "no ip (iproute2): scripts/bootstrap installs it"
command -v nft >/dev/null || skip "no nft (nftables): scripts/bootstrap installs it"

tag="rt$(($$ % 100000))"
sw="${tag}sw"
hosts=("${tag}h0" "${tag}h1" "${tag}h2" "${tag}h3")
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -INT "$p" 2>/dev/null; done
  sleep 2
  for p in "${pids[@]}"; do kill -KILL "$p" 2>/dev/null; done
  # Whatever still runs in a host's namespace (the watcher's rospy ignores SIGINT and outlived
  # its wrapper's kill, holding the caller's output open): killed with its namespace.
  for n in "${hosts[@]}"; do ip netns pids "$n" 2>/dev/null | xargs -r kill -KILL 2>/dev/null; done
  for n in "${hosts[@]}" "$sw"; do ip netns del "$n" 2>/dev/null; done
}
trap cleanup EXIT

ip netns add "$sw" 2>"$work/netns.err" || skip "cannot create a network namespace: $(cat "$work/netns.err")"
ip -n "$sw" link add br0 type bridge && ip -n "$sw" link set br0 up ||
  skip "cannot create a bridge in a namespace"
for i in 0 1 2 3; do
  h="${hosts[$i]}"
  ip netns add "$h" || skip "cannot create namespace $h"
  ip link add "${tag}a$i" type veth peer name "${tag}b$i" || skip "no veth pairs"
  ip link set "${tag}a$i" netns "$h" name eth0
  ip link set "${tag}b$i" netns "$sw"
  ip -n "$sw" link set "${tag}b$i" master br0 up
  ip -n "$h" addr add "10.43.0.$((i + 1))/24" dev eth0
  ip -n "$h" link set eth0 up
  ip -n "$h" link set lo up
done

master="http://10.43.0.1:11311"
# on_host I CMD...: CMD in host I's namespace with its ROS_IP, the master of host 0 and a
# ROS_HOME of its own (the logs), in the background; its pid is kept for the cleanup.
on_host() {
  local i="$1"
  shift
  mkdir -p "$work/h$i"
  ip netns exec "${hosts[$i]}" env ROS_IP="10.43.0.$((i + 1))" ROS_MASTER_URI="$master" \
    ROS_HOME="$work/h$i" "$@" >"$work/h$i/out.log" 2>&1 &
  pids+=($!)
}
in_host() {  # in_host I CMD...: CMD in host I's namespace, in the foreground
  local i="$1"
  shift
  ip netns exec "${hosts[$i]}" env ROS_IP="10.43.0.$((i + 1))" ROS_MASTER_URI="$master" \
    ROS_HOME="$work/h$i" "$@"
}
launch="$REPO/test/netns/hosts.launch"
on_host 0 roslaunch "$launch" host:=0 steps:=$steps bag:="$work/multi_host.bag"
for _ in $(seq 1 60); do
  in_host 1 rosparam get /robot_description >/dev/null 2>&1 && break
  sleep 1
done
for i in 1 2 3; do
  in_host "$i" rosparam get /robot_description >/dev/null 2>&1 ||
    { echo "[multi_host] FAILED: host $i does not reach the master on host 0"
      junit failed "host $i does not reach the master on host 0"; exit 1; }
done
for i in 1 2 3; do on_host "$i" roslaunch --wait "$launch" host:="$i"; done

# Loss on worker 0's link, both ways, from now on.
in_host 2 nft -f - <<EOF
table inet faults {
  chain in { type filter hook input priority 0; iifname "eth0" numgen random mod 100 < $loss drop; }
  chain out { type filter hook output priority 0; oifname "eth0" numgen random mod 100 < $loss drop; }
}
EOF

# A watcher on host 0 (running through the walk): every footholds_checked count of worker 1
# with the wall time it arrived, one line each. It is connected to worker 1 and listens to
# com_state before sim_node starts (com_subscribers counts it), so it sees the first count.
in_host 0 /usr/bin/python3 - "$work/worker1_counts" <<'PY' &
import sys, time, rospy
from std_msgs.msg import UInt64
out = open(sys.argv[1], "w")
rospy.init_node("multi_host_watch", anonymous=True, disable_signals=True)
def on_count(m):
    out.write("%.3f %d\n" % (time.time(), m.data))
    out.flush()
sub = rospy.Subscriber("/reachability_worker_1/footholds_checked", UInt64, on_count)
while sub.get_num_connections() < 1:
    time.sleep(0.05)  # wall time: /use_sim_time is set and no clock runs before the walk
com = rospy.Subscriber("/com_state", rospy.AnyMsg, lambda m: None)
rospy.spin()
PY
pids+=($!)
notice_pattern="reachability worker '/reachability_worker_1/check_footholds'"

# The checker last: sim_node starts walking once it listens to com_state.
mkdir -p "$work/h0"
ip netns exec "${hosts[0]}" env ROS_IP=10.43.0.1 ROS_MASTER_URI="$master" ROS_HOME="$work/h0" \
  "$BIN/check_walk_nodes" __name:=check_walk_nodes _config:="$REPO/config/biped.yaml" \
  _sim_config:="$REPO/config/sim.yaml" _policy:=kinematic _steps:=$steps _seed:=1 \
  _push_vx:=-0.2 _push_vy:=-0.6 _timeout:=400 _workers:=2 \
  --gtest_output="xml:$results/netns-check_walk_nodes.xml" >"$work/checker.log" 2>&1 &
checker=$!
pids+=($checker)

# Partition worker 1 mid-walk, as soon as it has answered its first chunk of a search ring:
# every packet from and to the other hosts dropped, in its namespace, outside its processes.
for _ in $(seq 1 3000); do [ -s "$work/worker1_counts" ] && break; sleep 0.02; done
[ -s "$work/worker1_counts" ] || { junit failed "worker 1 checked no candidate"; exit 1; }
in_host 3 nft -f - <<'EOF'
table inet partition {
  chain in { type filter hook input priority 0; iifname "eth0" drop; }
  chain out { type filter hook output priority 0; oifname "eth0" drop; }
}
EOF
t_partition=$(date +%s.%N)
echo "[multi_host] worker 1 partitioned after it answered a chunk"
# Healed once transition_ocp_node has noticed it (its warning; within worker_timeout of a call).
for _ in $(seq 1 1200); do
  grep -q "$notice_pattern" "$work/h1/out.log" && break
  sleep 0.05
done
in_host 3 nft delete table inet partition
t_heal=$(date +%s.%N)
noticed_after=$(/usr/bin/python3 -c "print(f'{$t_heal - $t_partition:.1f}')")
echo "[multi_host] partition healed after transition_ocp_node noticed it"
wait "$checker"
checker_rc=$?
# Rejoined: worker 1 answered after the heal: two counts at least (one may be an answer that
# was in flight when the partition began, delivered late).
after_heal=$(awk -v t="$t_heal" '$1 > t' "$work/worker1_counts" | wc -l)

# The bag: close it (the recorder stops with host 0's roslaunch), then count the step reports.
kill -INT "${pids[0]}" 2>/dev/null
for _ in $(seq 1 30); do [ -f "$work/multi_host.bag" ] && break; sleep 1; done
sleep 2
in_bag=$(/usr/bin/python3 -c '
import sys, rosbag
b = rosbag.Bag(sys.argv[1])
t = [t.to_sec() for _, _, t in b.read_messages(topics=["/step_report"], raw=True)]
print(len(t), "ok" if t == sorted(t) else "unordered")
' "$work/multi_host.bag" 2>"$work/bag.err")
read -r bag_reports bag_order <<<"${in_bag:-0 unreadable}"
walk_steps=$(grep -o 'WALK .*' "$work/h0/out.log" | head -n 1 | grep -o ' steps=[0-9]*' | cut -d= -f2)
lost=$((${walk_steps:-$steps} - ${bag_reports:-0}))

# Noticed: transition_ocp_node's warning about worker 1 (left out after a failed call).
notice=$(grep -c "$notice_pattern" "$work/h1/out.log")
rejoined=no
[ "$after_heal" -ge 2 ] && rejoined=yes
same_walk=no
[ $checker_rc -eq 0 ] && same_walk=yes
echo "BENCH ros.multi_host hosts=4 loss=${loss}% partitions=1 same_walk=$same_walk" \
  "lost_msgs=$lost rejoined=$rejoined steps=${walk_steps:-?} bag_reports=$bag_reports" \
  "partition_noticed=$notice noticed_after_s=$noticed_after worker_timeout_s=2 worker1_answers_after_heal=$after_heal worker1_checked_end=$(tail -n 1 "$work/worker1_counts" | cut -d' ' -f2)" \
  "faults=loss,partition netem=absent"
problems=()
[ "$same_walk" = yes ] || problems+=("the walk differs from the in-process one (checker exit $checker_rc): $(grep -E 'Failure|Expected|FAILED' "$work/checker.log" | head -n 5 | tr '\n' ' ')")
[ "$lost" = 0 ] && [ "$bag_order" = ok ] || problems+=("bag: $bag_reports step reports ($bag_order) for ${walk_steps:-?} steps")
[ "$notice" -gt 0 ] || problems+=("the partition of worker 1 was not noticed")
[ "$rejoined" = yes ] || problems+=("worker 1 checked no candidate after the partition healed")
if [ ${#problems[@]} -gt 0 ]; then
  printf '[multi_host] FAILED: %s\n' "${problems[@]}"
  tail -n 20 "$work/checker.log" | sed 's/^/[multi_host checker] /'
  junit failed "${problems[*]}"
  exit 1
fi
junit passed ""
rm -rf "$work"
