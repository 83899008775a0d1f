# Sourced by the scripts: Debian's Python and ROS tools first on PATH (a pyenv python3 may
# shadow them), the catkin workspace's paths, and where things are.
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
WS="${REACH_WS:-$REPO/.build_ws}"  # REACH_WS: another workspace, e.g. for a parallel build
VENV="$REPO/.venv"
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:$PATH"
export ROS_HOME="${ROS_HOME:-$WS/ros_home}"
if [ -f "$WS/devel/setup.bash" ]; then
  # shellcheck disable=SC1091
  set +u; source "$WS/devel/setup.bash"; set -u
fi
BIN="$WS/devel/lib/reach_trajopt"
# OpenMP threads sleep when idle instead of spinning (the reachability check's threads share
# the machine with other work: bench/README.md, reach.walk_check); a value set outside wins.
export OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-passive}"
# Robots of example-robot-data (test/bench venv), for configs such as config/talos.yaml
# (robot.urdf: ${EXAMPLE_ROBOT_DATA}/talos_data/...); a value set outside wins.
export EXAMPLE_ROBOT_DATA="${EXAMPLE_ROBOT_DATA:-$VENV/lib/python3.11/site-packages/cmeel.prefix/share/example-robot-data/robots}"
