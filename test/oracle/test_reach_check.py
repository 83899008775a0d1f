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

DI_URDF = """<robot name="double_integrator">
  <link name="world"/>
  <link name="slider">
    <inertial><origin xyz="0 0 0"/><mass value="2.0"/>
      <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="x" type="prismatic">
    <parent link="world"/><child link="slider"/><axis xyz="1 0 0"/>
    <limit lower="-50" upper="50" effort="10" velocity="50"/>
  </joint>
</robot>"""
MASS, FORCE, DT = 2.0, 10.0, 1e-3
ACC = FORCE / MASS

DI_CONFIG = """reach:
  horizon: 0.05
  window_start: 0.0
  window_end: 0.05
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
                                              "config": {"initial_samples": 0}})
    run = run_tool("reach_check", di_files / "di.urdf", di_files / "di.yaml", bad)
    assert run.returncode == 2 and "initial_samples" in run.output, run.describe()
    (tmp_path / "junk.json").write_text("{not json")
    run = run_tool("reach_check", di_files / "di.urdf", di_files / "di.yaml",
                   tmp_path / "junk.json")
    assert run.returncode == 2 and "not valid JSON" in run.output, run.describe()


def bent_knees(names, x, y):
    q = [0.0] * len(names)
    q[0], q[1], q[2] = x, y, 1.1
    for s in ("l_", "r_"):
        q[names.index(s + "hip_pitch")] = -0.4
        q[names.index(s + "knee")] = 0.8
        q[names.index(s + "ankle_pitch")] = -0.4
    return q


NAMES = ["base_x", "base_y", "base_z", "base_yaw", "base_pitch", "base_roll",
         "l_hip_yaw", "l_hip_roll", "l_hip_pitch", "l_knee", "l_ankle_pitch", "l_ankle_roll",
         "r_hip_yaw", "r_hip_roll", "r_hip_pitch", "r_knee", "r_ankle_pitch", "r_ankle_roll"]


def test_biped_normal_footstep_witness_satisfies_the_dynamics_per_pinocchio(tmp_path):
    pin = pytest.importorskip("pinocchio")
    target = np.array([0.25, -0.12, 0.0])
    p0 = target + np.array([-0.03, 0.0, 0.02])
    horizon = 0.06
    req = write_json(tmp_path / "step.json", {
        "mode": "SS-L",
        "stance": {"position": [0.0, 0.1, 0.0], "yaw": 0.0},
        "target": {"position": target.tolist(), "yaw": 0.0},
        "swing": {"position": p0.tolist(), "velocity": (2 * (target - p0) / horizon).tolist(),
                  "q_init": bent_knees(NAMES, 0.5 * p0[0], 0.5 * (0.1 + p0[1]))},
        "config": {"horizon": horizon, "window_start": 0.02, "window_end": 0.04,
                   "initial_samples": 500, "children_per_parent": 4,
                   "backward_children_per_parent": 12, "max_boundary": 40,
                   "interior_samples": 12, "angular_bins": 8}})
    res = run_tool("reach_check", REPO / "urdf" / "biped.urdf", REPO / "config" / "biped.yaml",
                   req).json()
    assert res["joint_names"] == NAMES
    # The witness, certified or not, is a path without a jump (x_0 -> a, then the bridge):
    # every step is re-checked here; a certified one also ends on x_f at t_f.
    w = res["witness"]
    assert w["junction"] == -1 and w["bridge_start"] >= 0
    assert res["reachable"] == w["certified"], res["reason"]
    q, qd, u, lam = (np.array(w[k]) for k in ("q", "qd", "u", "lambda"))
    assert np.allclose(w["time"][0], 0.0)
    if w["certified"]:
        assert np.allclose(w["time"][-1], horizon)
        assert w["terminal_position_gap"] <= 1e-3 and w["terminal_velocity_gap"] <= 1e-2
    # Pinocchio model with our floating base (x, y, z, yaw, pitch, roll).
    root = pin.JointModelComposite()
    for j in (pin.JointModelPX(), pin.JointModelPY(), pin.JointModelPZ(),
              pin.JointModelRZ(), pin.JointModelRY(), pin.JointModelRX()):
        root.addJoint(j)
    model = pin.buildModelFromUrdf(str(REPO / "urdf" / "biped.urdf"), root)
    data = model.createData()
    # Our coordinate i -> Pinocchio index (by joint name; the root composite is first).
    idx = list(range(6)) + [model.joints[model.getJointId(n)].idx_q for n in NAMES[6:]]
    sole = model.getFrameId("l_sole")
    dt = res["dt"]
    cone_c = cone_matrix(0.7, 0.135, 0.08)
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
        assert (cone_c @ w_sole).min() >= -1e-6, f"step {k}: wrench outside the cone"
        assert np.all(np.abs(u[k]) <= np.array([150, 300, 300, 300, 200, 150] * 2) + 1e-6)
        assert np.linalg.norm(data.oMf[sole].translation - np.array([0.0, 0.1, 0.0])) <= 1e-4
    assert worst <= 1e-6, f"eq. (1) residual {worst} per Pinocchio"


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
