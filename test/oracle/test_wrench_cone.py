"""Contact wrench cone of eq. (7)-(8) (docs/method.md Sec. 2) against an independent LP.

A wrench w = [f; tau] at the sole centre (sole frame) is in the cone iff it is the sum of four
corner forces f_k at (+-X, +-Y, 0), each in the friction pyramid |fx_k|, |fy_k| <= mu fz_k.
The LP maximises the smallest pyramid slack t over all corner force distributions that
produce w; w is inside iff t* >= 0. The cone matrix comes from the built tool `wrench_cone`
(nothing of the cone is reimplemented here), and its sign verdict min(C w) >= 0 must agree.
"""
import json
import os
import subprocess

import numpy as np
import pytest
from scipy.optimize import linprog

BIN = os.environ.get("REACH_BIN", "")
TOOL = os.path.join(BIN, "wrench_cone")

# (mu, X, Y): the biped's sole, a slippery narrow one, a grippy square one.
CASES = [(0.7, 0.135, 0.08), (0.3, 0.05, 0.02), (1.2, 0.1, 0.1)]


def cone_from_tool(mu, X, Y, rpy=(0.0, 0.0, 0.0)):
    out = subprocess.run([TOOL, "--mu", repr(mu), "--half-length", repr(X), "--half-width",
                          repr(Y), "--rpy", *map(repr, rpy)], check=True, capture_output=True,
                         text=True)
    data = json.loads(out.stdout)
    return np.array(data["sole"]), np.array(data["world"]), np.array(data["R"])


def corners(X, Y):
    return np.array([[sx * X, sy * Y, 0.0] for sx in (1, -1) for sy in (1, -1)])


def corner_wrench(forces, X, Y):
    """Net wrench [f; tau] at the sole centre of four corner forces (4 x 3)."""
    c = corners(X, Y)
    return np.concatenate([forces.sum(axis=0), np.cross(c, forces).sum(axis=0)])


class PyramidLp:
    """max t s.t. sum_k f_k = f, sum_k c_k x f_k = tau, mu fz_k -+ fx_k >= t, mu fz_k -+ fy_k >= t."""

    def __init__(self, mu, X, Y):
        c = corners(X, Y)
        n = 13  # 12 forces + t
        A_eq = np.zeros((6, n))
        for k in range(4):
            A_eq[0:3, 3 * k:3 * k + 3] = np.eye(3)
            cx, cy, _ = c[k]
            # c x f = (cy fz, -cx fz, cx fy - cy fx)
            A_eq[3, 3 * k + 2] = cy
            A_eq[4, 3 * k + 2] = -cx
            A_eq[5, 3 * k + 0] = -cy
            A_eq[5, 3 * k + 1] = cx
        A_ub = []
        for k in range(4):
            for axis in (0, 1):
                for s in (1.0, -1.0):
                    row = np.zeros(n)
                    row[3 * k + axis] = s   # s f_axis - mu fz + t <= 0
                    row[3 * k + 2] = -mu
                    row[12] = 1.0
                    A_ub.append(row)
        self.A_eq, self.A_ub = A_eq, np.array(A_ub)
        self.cost = np.zeros(n)
        self.cost[12] = -1.0

    def slack(self, w):
        scale = max(1.0, np.abs(w).max())
        bounds = [(None, None)] * 12 + [(None, scale)]
        res = linprog(self.cost, A_ub=self.A_ub, b_ub=np.zeros(len(self.A_ub)), A_eq=self.A_eq,
                      b_eq=w, bounds=bounds, method="highs")
        assert res.status == 0, res.message
        return -res.fun


def random_wrenches(rng, n, mu, X, Y):
    """Wrenches around the cone: about half inside, half outside."""
    fz = rng.uniform(-20.0, 400.0, n)
    a = (np.abs(fz) + 1.0) * rng.uniform(0.1, 1.2, n)  # how far out the other components go
    w = np.column_stack([
        rng.uniform(-1.2, 1.2, n) * mu * a,
        rng.uniform(-1.2, 1.2, n) * mu * a,
        fz,
        rng.uniform(-1.1, 1.1, n) * Y * a,
        rng.uniform(-1.1, 1.1, n) * X * a,
        rng.uniform(-1.0, 1.0, n) * mu * (X + Y) * a,
    ])
    return w


@pytest.fixture(scope="module", autouse=True)
def tool_exists():
    if not os.path.isfile(TOOL):
        pytest.fail(f"wrench_cone tool not built at {TOOL} (set REACH_BIN)")


@pytest.mark.parametrize("mu,X,Y", CASES)
def test_cone_matches_lp_on_random_wrenches(mu, X, Y):
    C, _, _ = cone_from_tool(mu, X, Y)
    assert C.shape == (16, 6)
    lp = PyramidLp(mu, X, Y)
    rng = np.random.default_rng(20200 + int(100 * mu))
    n = 3400  # 3 cases: 10200 random wrenches in all
    inside = outside = 0
    for w in random_wrenches(rng, n, mu, X, Y):
        margin = (C @ w).min()
        t = lp.slack(w)
        scale = np.abs(w).max()
        # Both verdicts must be clear-cut and agree (the LP solver works to ~1e-9).
        assert abs(margin) > 1e-9 * scale or abs(t) < 1e-6 * scale
        assert (margin >= 0) == (t >= 0), (w, margin, t)
        inside += margin >= 0
        outside += margin < 0
    assert inside > n // 5 and outside > n // 5  # the sample really probes both sides


@pytest.mark.parametrize("mu,X,Y", CASES)
def test_cone_matches_lp_near_faces(mu, X, Y):
    """Points at relative distance 1e-6 on either side of the cone boundary along random rays."""
    C, _, _ = cone_from_tool(mu, X, Y)
    lp = PyramidLp(mu, X, Y)
    rng = np.random.default_rng(7 + int(100 * mu))
    checked = 0
    rel = 1e-6
    attempts = 0
    while checked < 1000 and attempts < 5000:
        attempts += 1
        forces = np.column_stack([rng.uniform(-0.5, 0.5, (4, 2)) * mu, np.ones(4)])
        forces *= rng.uniform(10.0, 200.0, (4, 1))
        w_in = corner_wrench(forces, X, Y)           # strictly inside
        w_out = random_wrenches(rng, 1, mu, X, Y)[0]
        if (C @ w_out).min() >= 0:
            continue
        lo, hi = 0.0, 1.0                             # bisect the boundary on the segment
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            if (C @ (w_in + mid * (w_out - w_in))).min() >= 0:
                lo = mid
            else:
                hi = mid
        d = w_out - w_in
        for s, expect_inside in ((lo - rel, True), (hi + rel, False)):
            w = w_in + s * d
            margin = (C @ w).min()
            assert (margin >= 0) == expect_inside
            t = lp.slack(w)
            assert (t >= 0) == expect_inside, (w, margin, t)
            checked += 1
    assert checked >= 1000


@pytest.mark.parametrize("mu,X,Y", CASES)
def test_corner_force_wrenches_always_pass(mu, X, Y):
    C, _, _ = cone_from_tool(mu, X, Y)
    rng = np.random.default_rng(11)
    for _ in range(3000):
        fz = rng.uniform(0.0, 300.0, 4) * (rng.uniform(size=4) > 0.2)
        txy = rng.uniform(-1.0, 1.0, (4, 2))
        # Some corners right on the pyramid's edges, |fx| = |fy| = mu fz.
        edge = rng.uniform(size=4) < 0.3
        txy[edge] = np.sign(txy[edge])
        forces = np.column_stack([txy * mu * fz[:, None], fz])
        w = corner_wrench(forces, X, Y)
        assert (C @ w).min() >= -1e-10 * max(1.0, np.abs(w).max())


def test_world_cone_is_sole_cone_rotated():
    """C_world [R f; R tau] = C [f; tau] for a tilted, turned sole (eq. 8)."""
    mu, X, Y = CASES[0]
    C, Cw, R = cone_from_tool(mu, X, Y, rpy=(0.1, -0.2, 0.7))
    assert np.allclose(R.T @ R, np.eye(3), atol=1e-12)
    rng = np.random.default_rng(3)
    for w in random_wrenches(rng, 200, mu, X, Y):
        w_world = np.concatenate([R @ w[:3], R @ w[3:]])
        assert np.allclose(Cw @ w_world, C @ w, atol=1e-9 * np.abs(w).max())


@pytest.mark.parametrize("args", [["--mu", "0"], ["--mu", "-0.5"], ["--half-length", "0"],
                                  ["--half-width", "0"], ["--mu", "nan"]])
def test_tool_rejects_bad_parameters(args):
    out = subprocess.run([TOOL, *args], capture_output=True, text=True)
    assert out.returncode == 2
    assert "must be positive" in out.stderr


@pytest.mark.parametrize("args", [["--mu", "1e308", "--half-length", "1e308"],
                                  ["--half-width", "1e200"], ["--mu", "1e5"]])
def test_tool_rejects_parameters_that_overflow_the_cone(args):
    # Before: exit 0 with null (NaN) entries in the printed cone.
    out = subprocess.run([TOOL, *args], capture_output=True, text=True)
    assert out.returncode == 2, out.stdout[-300:]
    assert "must be <=" in out.stderr
