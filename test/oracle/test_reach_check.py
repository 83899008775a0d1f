"""Oracle tests of reach_check (the reachability check of eq. 13-21 as a CLI).

1. A one-joint double integrator (fixed base, |force| <= F, no contact): the exact reachable set
   of the discrete-time system after N steps is a zonotope, computed here with numpy from the
   recurrences; no forward or backward sample may lie outside it and the sampled position
   extent must reach 90% of it.
2. The biped, single support -> double support: a normal footstep is reachable, and the
   witness path satisfies eq. (1) according to Pinocchio (an independent dynamics code), the
   contact wrench cone, the torque limits and the stance contact.
3. Bad input gives exit status 2 and a clear message.
"""

import json
import math

import numpy as np
import pytest

from conftest import REPO, run_tool, write_json

DI_URDF = (REPO / "test" / "fixtures" / "double_integrator.urdf").read_text()
MASS, FORCE, DT = 2.0, 10.0, 1e-3
ACC = FORCE / MASS

# contact: is required in every config file (step/footstep_planner_setup.h); the double
# integrator has no contacts (mode "none"), so its values are never used.
DI_CONFIG = """contact:
  mu: 0.7
  half_length: 0.135
  half_width: 0.08
reach:
  horizon: 0.05
  window_start: 0.0
  window_end: 0.05
  budgets:
    full:
      initial_samples: 300
      children_per_parent: 6
      backward_children_per_parent: 6
      max_boundary: 24
      interior_samples: 8
  angular_bins: 8
  output_frame: slider
  output_axes: x
  backward_joint_accel: 5.0
  threads: 1
"""


def zonotope(x0, n, step):
    """Centre and generators of the set reached in n steps of step(x, a), |a| <= ACC."""
    def run(impulse):
        x = np.array(x0, float)
        for k in range(n):
            x = step(x, ACC if k == impulse else 0.0)
        return x
    c = run(-1)
    return c, [run(k) - c for k in range(n)]


def inside(z, c, gens, tol=1e-12):
    for g in gens:
        n = np.array([-g[1], g[0]])
        if np.linalg.norm(n) == 0:
            continue
        n /= np.linalg.norm(n)
        if abs(n @ (z - c)) > sum(abs(n @ h) for h in gens) + tol:
            return False
    return True


def fwd(x, a):
    v = x[1] + DT * a
    return np.array([x[0] + DT * v, v])


def bwd(x, a):
    return np.array([x[0] - DT * x[1], x[1] - DT * a])


@pytest.fixture(scope="module")
def di_files(tmp_path_factory):
    d = tmp_path_factory.mktemp("di")
    (d / "di.urdf").write_text(DI_URDF)
    (d / "di.yaml").write_text(DI_CONFIG)
    return d


def test_double_integrator_sets_match_the_exact_discrete_sets(di_files):
    x0, xf = (0.1, 0.3), (0.2, -0.2)
    req = write_json(di_files / "req.json", {"mode": "none", "x0": {"q": [x0[0]], "qd": [x0[1]]},
                                              "xf": {"q": [xf[0]], "qd": [xf[1]]}})
    res = run_tool("reach_check", di_files / "di.urdf", di_files / "di.yaml", req,
                   "--samples").json()
    for direction, root, step in (("forward", x0, fwd), ("backward", xf, bwd)):
        slices = res["slices"][direction]
        for n in (20, 50):
            s = slices[n]
            c, gens = zonotope(root, n, step)
            pos = np.array([o[0] for o in s["outputs"]])
            vel = np.array([v[0] for v in s["qd"]])
            assert s["count"] == len(pos) > 0
            out = [i for i in range(len(pos)) if not inside(np.array([pos[i], vel[i]]), c, gens)]
            assert not out, f"{direction} t={n} ms: {len(out)} samples outside the exact set"
            exact = sum(2 * abs(g[0]) for g in gens)
            assert pos.max() - pos.min() >= 0.9 * exact, (direction, n, pos.ptp(), exact)


def test_bad_requests_fail_cleanly(di_files, tmp_path):
    bad = write_json(tmp_path / "bad.json", {"mode": "none", "x0": {"q": [0.0], "qd": [99.0]},
                                             "xf": {"q": [0.0], "qd": [0.0]}})
    run = run_tool("reach_check", di_files / "di.urdf", di_files / "di.yaml", bad)
    assert run.returncode == 2 and "velocity limit" in run.output, run.describe()
    bad = write_json(tmp_path / "bad2.json", {"mode": "none", "x0": {"q": [0.0], "qd": [0.0]},
                                              "xf": {"q": [0.0], "qd": [0.0]},
                                              "config": {"budgets": {"full": {"initial_samples": 0}}}})
    run = run_tool("reach_check", di_files / "di.urdf", di_files / "di.yaml", bad)
    assert run.returncode == 2 and "initial_samples" in run.output, run.describe()
    (tmp_path / "junk.json").write_text("{not json")
    run = run_tool("reach_check", di_files / "di.urdf", di_files / "di.yaml",
                   tmp_path / "junk.json")
    assert run.returncode == 2 and "not valid JSON" in run.output, run.describe()


def bent_knees(names, x, y, z=1.1, legs=(("l_hip_pitch", "l_knee", "l_ankle_pitch"),
                                         ("r_hip_pitch", "r_knee", "r_ankle_pitch"))):
    """A configuration with the base at (x, y, z) and both knees bent by 0.8 rad."""
    q = [0.0] * len(names)
    q[0], q[1], q[2] = x, y, z
    for hip, knee, ankle in legs:
        q[names.index(hip)] = -0.4
        q[names.index(knee)] = 0.8
        q[names.index(ankle)] = -0.4
    return q


NAMES = ["base_x", "base_y", "base_z", "base_yaw", "base_pitch", "base_roll",
         "l_hip_yaw", "l_hip_roll", "l_hip_pitch", "l_knee", "l_ankle_pitch", "l_ankle_roll",
         "r_hip_yaw", "r_hip_roll", "r_hip_pitch", "r_knee", "r_ankle_pitch", "r_ankle_roll"]


def normal_footstep_request(path, names, stance_y, target, legs=None, base_z=1.1):
    """Single support on the left sole at (0, stance_y), the right sole 3 cm behind and 2 cm
    above `target`, moving onto it within the horizon; a small sample budget."""
    target = np.array(target, float)
    p0 = target + np.array([-0.03, 0.0, 0.02])
    horizon = 0.06
    q_init = bent_knees(names, 0.5 * p0[0], 0.5 * (stance_y + p0[1]), base_z,
                        *([legs] if legs else []))
    return write_json(path, {
        "mode": "SS-L",
        "stance": {"position": [0.0, stance_y, 0.0], "yaw": 0.0},
        "target": {"position": target.tolist(), "yaw": 0.0},
        "swing": {"position": p0.tolist(), "velocity": (2 * (target - p0) / horizon).tolist(),
                  "q_init": q_init},
        "config": {"horizon": horizon, "window_start": 0.02, "window_end": 0.04,
                   "budgets": {"full": {"initial_samples": 500, "children_per_parent": 4,
                                        "backward_children_per_parent": 12,
                                        "max_boundary": 40, "interior_samples": 12}},
                   "angular_bins": 8}}), horizon


def check_witness_with_pinocchio(res, model, sole_name, stance, cone, horizon):
    """Re-checks every step of reach_check's witness with Pinocchio: eq. (1) (RNEA residual),
    the stance sole's wrench cone, |u| <= the URDF effort limits and the held stance sole.
    `model`: Pinocchio's model with our floating base (x, y, z, yaw, pitch, roll) first."""
    pin = pytest.importorskip("pinocchio")
    names = res["joint_names"]
    w = res["witness"]
    assert w["junction"] == -1 and w["bridge_start"] >= 0
    assert res["reachable"] == w["certified"], res["reason"]
    q, qd, u, lam = (np.array(w[k]) for k in ("q", "qd", "u", "lambda"))
    assert np.allclose(w["time"][0], 0.0)
    if w["certified"]:
        assert np.allclose(w["time"][-1], horizon)
        assert w["terminal_position_gap"] <= 1e-3 and w["terminal_velocity_gap"] <= 1e-2
    data = model.createData()
    # Our coordinate i -> Pinocchio index (by joint name; the root composite is first).
    idx = list(range(6)) + [model.joints[model.getJointId(n)].idx_q for n in names[6:]]
    effort = model.effortLimit[idx[6:]]
    sole = model.getFrameId(sole_name)
    dt = res["dt"]
    worst = 0.0
    for k in range(len(q) - 1):
        qp, vp, ap = (np.zeros(model.nq) for _ in range(3))
        qp[idx], vp[idx] = q[k], qd[k]
        ap[idx] = (qd[k + 1] - qd[k]) / dt
        tau = pin.rnea(model, data, qp, vp, ap)
        pin.computeJointJacobians(model, data, qp)
        pin.updateFramePlacements(model, data)
        J = pin.getFrameJacobian(model, data, sole, pin.LOCAL_WORLD_ALIGNED)
        gen = np.zeros(model.nv)
        gen[idx[6:]] = u[k]
        resid = tau - gen - J.T @ lam[k]
        worst = max(worst, np.abs(resid).max())
        R = data.oMf[sole].rotation
        w_sole = np.concatenate([R.T @ lam[k][:3], R.T @ lam[k][3:]])
        assert (cone @ w_sole).min() >= -1e-6, f"step {k}: wrench outside the cone"
        assert np.all(np.abs(u[k]) <= effort + 1e-6), f"step {k}: torque above the limits"
        assert np.linalg.norm(data.oMf[sole].translation - np.array(stance)) <= 1e-4
    assert worst <= 1e-6, f"eq. (1) residual {worst} per Pinocchio"
    return w


def test_biped_normal_footstep_witness_satisfies_the_dynamics_per_pinocchio(tmp_path):
    pin = pytest.importorskip("pinocchio")
    req, horizon = normal_footstep_request(tmp_path / "step.json", NAMES, 0.1, [0.25, -0.12, 0.0])
    res = run_tool("reach_check", REPO / "urdf" / "biped.urdf", REPO / "config" / "biped.yaml",
                   req).json()
    assert res["joint_names"] == NAMES
    from model_oracle import floating_root_joint
    model = pin.buildModelFromUrdf(str(REPO / "urdf" / "biped.urdf"), floating_root_joint())
    check_witness_with_pinocchio(res, model, "l_sole", [0.0, 0.1, 0.0],
                                 cone_matrix(0.7, 0.135, 0.08), horizon)


def test_talos_legs_normal_footstep_witness_satisfies_the_dynamics_per_pinocchio(tmp_path):
    """The same on TALOS legs (config/talos.yaml: the robot section's URDF, its 20 locked
    joints), re-checked on Pinocchio's buildReducedModel of talos_reduced.urdf."""
    pin = pytest.importorskip("pinocchio")
    from model_oracle import floating_root_joint, reduced_model
    from test_model_locked_joints import TALOS, shipped_locked_joints
    config = REPO / "config" / "talos.yaml"
    names = ["base_x", "base_y", "base_z", "base_yaw", "base_pitch", "base_roll"] + [
        f"leg_{side}_{i}_joint" for side in ("left", "right") for i in range(1, 7)]
    legs = tuple((f"leg_{s}_3_joint", f"leg_{s}_4_joint", f"leg_{s}_5_joint")
                 for s in ("left", "right"))
    req, horizon = normal_footstep_request(tmp_path / "talos_step.json", names, 0.085,
                                           [0.15, -0.1, 0.0], legs, base_z=1.0)
    run = run_tool("reach_check", "--config", config, req)
    assert run.returncode == 0, run.describe()
    res = run.json()
    assert res["joint_names"] == names
    model = reduced_model(pin.buildModelFromUrdf(str(TALOS), floating_root_joint()),
                          shipped_locked_joints(config))
    w = check_witness_with_pinocchio(res, model, "left_sole_link", [0.0, 0.085, 0.0],
                                     cone_matrix(0.7, 0.1, 0.05), horizon)
    assert len(w["q"]) > 10


def cone_matrix(mu, X, Y):
    """The 16 x 6 contact wrench cone of docs/method.md Sec. 2 (Caron, Pham, Nakamura 2015)."""
    rows = [[1, 0, mu, 0, 0, 0], [-1, 0, mu, 0, 0, 0], [0, 1, mu, 0, 0, 0], [0, -1, mu, 0, 0, 0],
            [0, 0, Y, 1, 0, 0], [0, 0, Y, -1, 0, 0], [0, 0, X, 0, 1, 0], [0, 0, X, 0, -1, 0]]
    for s1 in (1, -1):
        for s2 in (1, -1):
            rows.append([s1 * Y, s2 * X, mu * (X + Y), -s1 * mu, -s2 * mu, 1])
    for s1 in (1, -1):
        for s2 in (1, -1):
            rows.append([-s1 * Y, -s2 * X, mu * (X + Y), -s1 * mu, -s2 * mu, -1])
    return np.array(rows, float)
