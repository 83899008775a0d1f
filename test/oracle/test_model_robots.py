"""Every robot of example-robot-data through `model_info`, checked against Pinocchio.

Each URDF shipped by the example-robot-data wheel (read from the venv at test time, none is
committed) is loaded as we load it: floating base unless its root link is "world" (then fixed
base, as Pinocchio without a root joint). At seeded random states within the joint limits, M, b,
the CoM and its Jacobian, and the pose, Jacobian and Jdot*qd of every link frame agree with
Pinocchio to 1e-8 (relative). Legged robots, humanoids and flying bases are tested floating;
fixed-base arms whose root is not "world" are tested floating too (a free-floating arm is a valid
model for both). A URDF with a joint type we do not model (planar, floating) must fail to load
with an error naming that joint; it is counted, not compared. A URDF our validation rejects
(model/urdf_validation.h: e.g. pr2's inertias that break the triangle inequality) must fail
with a clean error naming the link or joint; no legged robot or humanoid may be rejected.
"""

import xml.etree.ElementTree as ET

import pytest

from conftest import EXAMPLE_ROBOTS, SUMMARY_LINES, run_tool
from model_oracle import ModelCheck, urdf_root_link

UNSUPPORTED = ("planar", "floating")
# Legged robots and humanoids (description folders): every one of them must load and agree.
LEGGED = ("a1_", "alex_", "alexander_", "anymal_", "b1_", "bolt_", "cassie_", "centauro_",
          "g1_", "go1_", "go2_", "human_", "hyq_", "icub_", "laikago_", "quadruped_", "romeo_",
          "simple_humanoid_", "solo_", "talos_")
# Legged robots whose URDF is physically invalid, rejected by name (checked, not skipped).
KNOWN_INVALID = {
    # LHipPitch_link's inertia has a principal moment of -0.0027 kg m^2 (not PSD).
    "romeo_laas_small": "'LHipPitch_link'",
}


def robot_urdfs():
    return sorted(EXAMPLE_ROBOTS.rglob("*.urdf"))


def joint_types(text):
    return {j.get("name"): j.get("type") for j in ET.fromstring(text).iter("joint")}


def test_every_example_robot_agrees_with_pinocchio(tmp_path):
    urdfs = robot_urdfs()
    assert len(urdfs) >= 40, f"expected the example-robot-data URDFs under {EXAMPLE_ROBOTS}"
    failures, checked, floating, unsupported, rejected = [], [], 0, [], []
    for path in urdfs:
        text = path.read_text()
        key = path.stem
        bad = [n for n, t in joint_types(text).items() if t in UNSUPPORTED]
        if bad:
            run = run_tool("model_info", path, "--json")
            assert run.returncode != 0 and bad[0] in run.output or any(
                b in run.output for b in bad), f"{path}: joint {bad} should be rejected by name"
            unsupported.append(key)
            continue
        if not ET.fromstring(text).findall("joint"):
            continue  # a single rigid body without joints: nothing to compare
        summary = run_tool("model_info", path, "--json")
        if summary.returncode != 0:
            legged = path.parent.parent.name.startswith(LEGGED)
            named = "link '" in summary.output or "joint '" in summary.output
            expected = KNOWN_INVALID.get(key)
            if expected and expected not in summary.output:
                named = False
            if (legged and not expected) or summary.returncode < 0 or not named:
                failures.append(f"{path}: rejected (exit {summary.returncode}): "
                                f"{summary.output.strip()[:300]}")
            rejected.append(key)
            continue
        is_floating = urdf_root_link(text) != "world"
        floating += is_floating
        check = ModelCheck(path, tmp_path, f"{path.parent.parent.name}-{key}", is_floating,
                           n_states=6)
        checked.append(f"{key}({len(check.frames)} frames)")
        failures += check.failures
    SUMMARY_LINES.append(
        f"model oracle: {len(checked)} example-robot-data robots checked against Pinocchio "
        f"({floating} floating-base), every link frame; unsupported joints rejected: "
        f"{unsupported}; rejected by the URDF validation: {rejected}")
    missing = sorted(set(KNOWN_INVALID) - set(rejected))
    assert not missing, f"expected to be rejected as invalid: {missing}"
    assert not failures, "\n".join(failures[:60])
    assert floating >= 30, f"only {floating} floating-base robots checked"
