"""The derivatives of inverse dynamics (model/rnea_derivatives.h) against Pinocchio's
computeRNEADerivatives, through `model_info --state FILE --rnea-derivatives`.

For each robot, seeded random states (q within the joint limits, a random base pose, moderate
velocities) and random accelerations qdd in [-5, 5] are written to one state file; the tool's
tau = M qdd + b, d tau / d q and d tau / d qd are compared with Pinocchio 4's rnea and
computeRNEADerivatives at the same state (gravity -9.81 z). Our floating base is built for
Pinocchio here as six separate one-dof joints base_x, base_y, base_z (prismatic), base_yaw,
base_pitch, base_roll (revolute z, y, x) with massless links in front of the URDF's root link:
the same coordinates as the composite root joint of the other model oracles, but
computeRNEADerivatives is not exact for a composite joint (its motion subspace depends on its own
q, which the algorithm's derivative of S does not see: measured here, errors of 100 % in the base
rows), while for one-dof joints its tangent-space derivative is the plain partial derivative in
q. Columns and rows are mapped by joint name. Pass: |ours - ref| <= 1e-8 * max(1, |ref|) (Frobenius norm) at
every state, the tolerance of the other model oracles.
"""

from pathlib import Path

import math
import re

import numpy as np
import pinocchio as pin
import pytest

from conftest import EXAMPLE_ROBOTS, REPO, run_tool, write_json
from model_oracle import TOL, Reference, rel_err, urdf_root_link

ROBOTS = [
    ("biped", REPO / "urdf" / "biped.urdf", True),
    ("biped_fixed", REPO / "urdf" / "biped.urdf", False),
    ("g1", EXAMPLE_ROBOTS / "g1_description" / "urdf" / "g1_29dof_rev_1_0.urdf", True),
    ("romeo", EXAMPLE_ROBOTS / "romeo_description" / "urdf" / "romeo_small.urdf", True),
    ("talos", EXAMPLE_ROBOTS / "talos_data" / "robots" / "talos_reduced.urdf", True),
]
N_STATES = 20
BASE = [("base_x", "prismatic", "1 0 0"), ("base_y", "prismatic", "0 1 0"),
        ("base_z", "prismatic", "0 0 1"), ("base_yaw", "revolute", "0 0 1"),
        ("base_pitch", "revolute", "0 1 0"), ("base_roll", "revolute", "1 0 0")]


def chain_base_model(urdf):
    """Pinocchio model of the URDF with our floating base as six one-dof joints (see above)."""
    text = Path(urdf).read_text()
    root = urdf_root_link(text)
    links, parent = ['<link name="reach_world"/>'], "reach_world"
    for k, (name, kind, axis) in enumerate(BASE):
        child = root if k == len(BASE) - 1 else f"reach_{name}_link"
        if child != root:
            links.append(f'<link name="{child}"/>')
        links.append(f'<joint name="{name}" type="{kind}"><parent link="{parent}"/>'
                     f'<child link="{child}"/><axis xyz="{axis}"/>'
                     f'<limit lower="-100" upper="100" effort="0" velocity="100"/></joint>')
        parent = child
    text = re.sub(r"(<robot[^>]*>)", lambda m: m.group(1) + "".join(links), text, count=1)
    return pin.buildModelFromXML(text)


def configuration(model, positions):
    """Pinocchio q from one angle or offset per joint (a continuous joint: cos, sin)."""
    q = np.zeros(model.nq)
    for j in range(1, model.njoints):
        jm = model.joints[j]
        x = positions[model.names[j]]
        if jm.nq == 1:
            q[jm.idx_q] = x
        else:
            q[jm.idx_q:jm.idx_q + 2] = [math.cos(x), math.sin(x)]
    return q


@pytest.mark.parametrize("key,urdf,floating", ROBOTS, ids=[r[0] for r in ROBOTS])
def test_rnea_derivatives_match_pinocchio(key, urdf, floating, tmp_path):
    if not Path(urdf).is_file():
        pytest.fail(f"URDF {urdf} not found")
    ref = Reference(urdf, floating)  # its sampler; the floating model below for the derivatives
    m = chain_base_model(urdf) if floating else ref.model
    d = m.createData()
    v_names = [m.names[j] for j in range(1, m.njoints)]
    base = [urdf] + ([] if floating else ["--fixed-base"])
    names = run_tool("model_info", *base, "--json").json()["joint_names"]
    assert sorted(names) == sorted(ref.v_names), f"{key}: joints differ from Pinocchio's"
    sample_perm = np.array([ref.v_names.index(n) for n in names])  # ours i -> sampler index
    perm = np.array([v_names.index(n) for n in names])  # ours i -> Pinocchio v index

    rng = np.random.default_rng(20181206)
    samples = []
    for _ in range(N_STATES):
        qv, v = ref.sample(rng)
        samples.append((qv[sample_perm], v[sample_perm], rng.uniform(-5.0, 5.0, m.nv)))
    states = [{"q": qv.tolist(), "qd": v.tolist(), "qdd": a.tolist()} for qv, v, a in samples]
    state_file = write_json(tmp_path / f"{key}_states.json", {"states": states})
    out = run_tool("model_info", *base, "--state", state_file, "--rnea-derivatives").json()
    results = out["results"]
    assert len(results) == N_STATES

    failures = []
    for k, ((qv, v, a), r) in enumerate(zip(samples, results)):
        # Our coordinates (qv, v, a) into Pinocchio's order.
        q = configuration(m, dict(zip(names, qv)))
        vp, ap = np.zeros(m.nv), np.zeros(m.nv)
        vp[perm], ap[perm] = v, a
        tau_ref = pin.rnea(m, d, q, vp, ap).copy()
        dq_ref, dv_ref, _ = pin.computeRNEADerivatives(m, d, q, vp, ap)
        P = np.ix_(perm, perm)
        ours = r["rnea_derivatives"]
        for label, mine, theirs in (("tau", np.array(ours["tau"]), tau_ref[perm]),
                                    ("dtau_dq", np.array(ours["dtau_dq"]), np.array(dq_ref)[P]),
                                    ("dtau_dqd", np.array(ours["dtau_dqd"]),
                                     np.array(dv_ref)[P])):
            assert mine.shape == theirs.shape, f"{key} state {k} {label}: shape {mine.shape}"
            err = rel_err(mine, theirs)
            if not err <= TOL:
                where = np.unravel_index(np.argmax(np.abs(mine - theirs)), mine.shape)
                cols = f" column {names[where[1]]}" if mine.ndim == 2 else ""
                failures.append(f"{key} state {k} {label}: relative error {err:.3e}, largest at "
                                f"row {names[where[0]]}{cols}: ours {mine[where]:.9g}, "
                                f"Pinocchio {theirs[where]:.9g}")
    assert not failures, "\n".join(failures[:20])
