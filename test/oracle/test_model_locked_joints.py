"""Locked joints (robot.locked_joints, model/joint_locking.h) against Pinocchio's
buildReducedModel: TALOS legs as config/talos.yaml builds them (every non-leg joint of
talos_reduced.urdf at half_sitting), and seeded random trees with a random subset of their
moving joints locked at random positions within their limits. M, b, the CoM and its Jacobian
and every frame's pose, Jacobian and Jdot*qd agree to 1e-8 (relative) at random states; a
locked joint that does not exist, is fixed, or is held outside its limits is an error naming it.
"""

import xml.etree.ElementTree as ET

import numpy as np

from conftest import EXAMPLE_ROBOTS, REPO, SUMMARY_LINES, run_tool
from model_oracle import ModelCheck, random_urdf

TALOS = EXAMPLE_ROBOTS / "talos_data" / "robots" / "talos_reduced.urdf"


def write_robot_config(path, locked):
    """A config file holding only a robot section with these locked joints."""
    lines = ["robot:", "  locked_joints:"] + [f"    {k}: {v!r}" for k, v in locked.items()]
    path.write_text("\n".join(lines) + "\n")
    return path


def shipped_locked_joints(config):
    """robot.locked_joints of a shipped config file (a flat block of `name: value` lines)."""
    locked, inside = {}, False
    for line in config.read_text().splitlines():
        if line.strip().startswith("locked_joints:"):
            inside = True
            continue
        if inside:
            body = line.split("#")[0].strip()
            if not line.startswith("    ") or ":" not in body:
                break
            name, value = body.split(":")
            locked[name.strip()] = float(value)
    return locked


def test_talos_legs_agree_with_pinocchio_reduced_model(tmp_path):
    locked = shipped_locked_joints(REPO / "config" / "talos.yaml")
    assert len(locked) == 20, "TALOS: everything but the 12 leg joints is locked"
    config = write_robot_config(tmp_path / "talos_locked.yaml", locked)
    check = ModelCheck(TALOS, tmp_path, "talos_legs", True, n_states=6, config=config,
                       locked=locked)
    assert not check.failures, "\n".join(check.failures)
    assert len(check.names) == 18, check.names  # 6 + 12 leg joints
    SUMMARY_LINES.append(f"locked joints: TALOS legs (n_v 18, {len(check.frames)} frames, "
                         f"mass {check.mass:.3f} kg) agree with buildReducedModel")


def movable_joints(text):
    """(name, type, lower, upper) of every revolute, continuous or prismatic joint."""
    out = []
    for j in ET.fromstring(text).iter("joint"):
        kind = j.get("type")
        if kind not in ("revolute", "continuous", "prismatic"):
            continue
        limit = j.find("limit")
        lo = float(limit.get("lower", 0)) if limit is not None and kind != "continuous" else -3.0
        hi = float(limit.get("upper", 0)) if limit is not None and kind != "continuous" else 3.0
        out.append((j.get("name"), kind, lo, hi))
    return out


def test_random_trees_with_locked_joints_agree_with_pinocchio(tmp_path):
    rng = np.random.default_rng(20261202)
    failures, checked = [], 0
    for i in range(12):
        text = random_urdf(rng, f"locked{i}", max_links=8)
        joints = movable_joints(text)
        if len(joints) < 2:
            continue
        n_lock = int(rng.integers(1, len(joints)))  # keep at least one moving joint
        picked = rng.choice(len(joints), size=n_lock, replace=False)
        locked = {joints[k][0]: float(rng.uniform(joints[k][2], joints[k][3])) for k in picked}
        urdf = tmp_path / f"locked{i}.urdf"
        urdf.write_text(text)
        config = write_robot_config(tmp_path / f"locked{i}.yaml", locked)
        floating = bool(rng.random() < 0.5)
        check = ModelCheck(urdf, tmp_path, f"locked{i}", floating, n_states=4, config=config,
                           locked=locked)
        failures += check.failures
        checked += 1
    assert checked >= 8
    assert not failures, "\n".join(failures)
    SUMMARY_LINES.append(f"locked joints: {checked} random trees with random locked joints "
                         "agree with buildReducedModel")


def test_bad_locked_joints_are_errors_naming_the_joint(tmp_path):
    cases = {
        "no_such_joint": ({"leg_left_9_joint": 0.0}, "leg_left_9_joint"),
        "fixed_joint": ({"leg_left_sole_fix_joint": 0.0}, "leg_left_sole_fix_joint"),
        "outside_limits": ({"arm_left_4_joint": 5.0}, "arm_left_4_joint"),
    }
    for key, (locked, name) in cases.items():
        config = write_robot_config(tmp_path / f"{key}.yaml", locked)
        run = run_tool("model_info", TALOS, "--config", config)
        assert run.returncode != 0 and run.returncode > 0, f"{key}: {run.output}"
        assert name in run.output, f"{key}: the error must name {name}: {run.output}"
    # A NaN position is an error naming the key, not a silent NaN model.
    (tmp_path / "nan.yaml").write_text("robot:\n  locked_joints:\n    arm_left_1_joint: .nan\n")
    run = run_tool("model_info", TALOS, "--config", tmp_path / "nan.yaml")
    assert run.returncode > 0 and "arm_left_1_joint" in run.output, run.output
