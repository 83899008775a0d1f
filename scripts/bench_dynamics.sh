#!/usr/bin/env bash
# Dynamics benchmark: our RobotModel vs Pinocchio C++ (bench/dynamics/) on urdf/biped.urdf and
# on TALOS (example-robot-data's talos_reduced.urdf from the venv, every joint free, mimic joints
# independent as in our model).
# Needs the package built (scripts/build, same REACH_WS) and the venv (scripts/bootstrap).
# Configures and builds bench/dynamics in $WS/bench_dynamics (one TU including Pinocchio: about
# 80 s the first time), saves Pinocchio's model of the URDF (parsed by Pinocchio in Python, root
# joint PX PY PZ RZ RY RX = our floating base) and runs the benchmark, which prints
#   BENCH dynamics.{full,mass_matrix,bias} robot=... ours_us=... ref=pinocchio ref_us=... ratio=...
# Extra arguments go to bench_dynamics (--rounds N --batch K).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/bench_lib.sh"
bench_need_core
bench_need -x "$VENV/bin/python" "run scripts/bootstrap"
core="$CORE_LIBRARY"
site="$("$VENV/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"
prefix="$site/cmeel.prefix"
build="$WS/bench_dynamics"
mkdir -p "$build"

# catkin's setup.bash exports CMAKE_PREFIX_PATH and LD_LIBRARY_PATH: keep Pinocchio's
# dependencies (Eigen, Boost, coal) from the wheels only, and let the rpaths pick libraries.
env -u CMAKE_PREFIX_PATH cmake -S "$REPO/bench/dynamics" -B "$build" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_USE_CMAKE_SYSTEM_PATH=OFF \
  -DREACH_CORE_LIBRARY="$core" >"$build/configure.log" 2>&1 || {
  cat "$build/configure.log" >&2; echo "[bench_dynamics] cmake configure failed" >&2; exit 1; }
echo "[bench_dynamics] building (one Pinocchio translation unit, about 80 s when it changed)"
cmake --build "$build" -j1 >"$build/build.log" 2>&1 || {
  tail -n 40 "$build/build.log" >&2; echo "[bench_dynamics] build failed" >&2; exit 1; }

# bench_one NAME URDF FRAMES [extra args]
bench_one() {
  local name="$1" urdf="$2" frames="$3"
  shift 3
  local model="$build/${name}_pinocchio.txt"            # composite root PX PY PZ RZ RY RX (= ours)
  local model_ff="$build/${name}_pinocchio_freeflyer.txt"  # Pinocchio's FreeFlyer root (info only)
  "$VENV/bin/python" - "$urdf" "$model" "$model_ff" <<'PY'
import sys
import pinocchio as pin
root = pin.JointModelComposite()
for j in (pin.JointModelPX(), pin.JointModelPY(), pin.JointModelPZ(),
          pin.JointModelRZ(), pin.JointModelRY(), pin.JointModelRX()):
    root.addJoint(j)
pin.buildModelFromUrdf(sys.argv[1], root).saveToText(sys.argv[2])
pin.buildModelFromUrdf(sys.argv[1], pin.JointModelFreeFlyer()).saveToText(sys.argv[3])
PY
  env -u LD_LIBRARY_PATH "$build/bench_dynamics" "$urdf" "$model" --freeflyer-model "$model_ff" \
    --frames "$frames" --robot "$name" "$@"
}

bench_one biped "$REPO/urdf/biped.urdf" l_sole,r_sole "$@"
bench_one talos_reduced "$site/cmeel.prefix/share/example-robot-data/robots/talos_data/robots/talos_reduced.urdf" \
  left_sole_link,right_sole_link "$@"
