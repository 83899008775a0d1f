"""The bundled QP (DualActiveSetQp through the `qp_solve` tool) against quadprog and the KKT
conditions, on seeded random problems.

Matrix entries are rounded to a few decimals before the exact relations (right-hand sides,
dependent rows, g of a chosen optimum) are computed from them, so the JSON stays small.

Problem form (as in include/reach_trajopt/qp/dual_active_set_qp.h):
    min 1/2 x^T G x + g^T x  s.t.  Aeq x = beq,  Ain x >= bin,
    G x + g = Aeq^T l_eq + Ain^T l_in,  l_in >= 0,  l_in * (Ain x - bin) = 0.

Feasible problems are built from a known feasible point (or a known optimum with chosen active
and weakly active rows). Degenerate copies (duplicated and scaled inequality rows, equality rows
that are combinations of others, zero rows, inequalities implied by others) do not change the
feasible set or the optimum, so the reference is quadprog on the non-degenerate base problem
(quadprog itself refuses dependent equality rows; daqp stands in where quadprog gives up).
Infeasible problems carry a Farkas certificate by construction. All problems go to one `qp_solve` process (batch mode: a JSON list).
"""

import daqp
import numpy as np
import pytest
import quadprog

from conftest import run_tool, write_json

N_FEASIBLE = 2000
N_INFEASIBLE = 300
N_WARM = 400
X_TOL = 1e-7  # |x - x_quadprog|_inf / max(1, |x_quadprog|_inf)
KKT_TOL = 1e-8


def pick_n(rng):
    """Mostly the small sizes of the contact QPs, some up to 120 variables."""
    u = rng.random()
    if u < 0.65:
        return int(rng.integers(5, 31))
    if u < 0.9:
        return int(rng.integers(31, 61))
    return int(rng.integers(61, 121))


def random_spd(rng, n):
    """Q diag(e) Q^T with eigenvalues log-uniform in [0.1, 10] (condition number <= 100)."""
    q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    e = np.exp(rng.uniform(np.log(0.1), np.log(10.0), n))
    G = (q * e) @ q.T
    return np.round(0.5 * (G + G.T), 6)  # short decimals keep the batch JSON small


def rows(rng, m, n):
    """Random constraint rows with 4 decimals (exact relations are built from these values)."""
    return np.round(rng.standard_normal((m, n)), 4)


def base_problem(rng, n):
    """A feasible problem from a random point x_f: equalities through it, inequalities with
    slacks, a third of them zero (active at x_f)."""
    m_eq = int(rng.integers(0, n // 2 + 1))
    m_in = int(rng.integers(0, 2 * n + 1))
    G = random_spd(rng, n)
    g = rng.standard_normal(n) * rng.choice([0.1, 1.0, 10.0])
    x_f = rng.standard_normal(n)
    Aeq = rows(rng, m_eq, n)
    beq = Aeq @ x_f
    Ain = rows(rng, m_in, n)
    slack = rng.exponential(1.0, m_in) * (rng.random(m_in) > 0.33)
    bin_ = Ain @ x_f - slack
    return dict(G=G, g=g, Aeq=Aeq, beq=beq, Ain=Ain, bin=bin_)


def kkt_problem(rng, n):
    """A problem whose optimum x* is chosen: m_eq equalities, strongly active rows (l > 0),
    weakly active rows (on the boundary with l = 0) and inactive rows; g = -G x* + A^T l."""
    m_eq = int(rng.integers(0, n // 3 + 1))
    n_strong = int(rng.integers(0, n - m_eq + 1))
    n_weak = int(rng.integers(0, max(1, (n - m_eq - n_strong) + 1)))
    n_inactive = int(rng.integers(0, 2 * n))
    G = random_spd(rng, n)
    x = rng.standard_normal(n)
    Aeq = rows(rng, m_eq, n)
    beq = Aeq @ x
    A_act = rows(rng, n_strong + n_weak, n)
    b_act = A_act @ x
    A_ina = rows(rng, n_inactive, n)
    b_ina = A_ina @ x - rng.uniform(0.1, 2.0, n_inactive)
    l_eq = rng.standard_normal(m_eq)
    l_act = np.concatenate([rng.uniform(0.1, 2.0, n_strong), np.zeros(n_weak)])
    g = -G @ x + Aeq.T @ l_eq + A_act.T @ l_act
    Ain = np.vstack([A_act, A_ina])
    bin_ = np.concatenate([b_act, b_ina])
    perm = rng.permutation(Ain.shape[0])
    return dict(G=G, g=g, Aeq=Aeq, beq=beq, Ain=Ain[perm], bin=bin_[perm]), x


def degenerate(rng, p):
    """Adds rows that change neither the feasible set nor the optimum."""
    p = dict(p)
    n = p["G"].shape[0]
    Aeq, beq, Ain, bin_ = p["Aeq"], p["beq"], p["Ain"], p["bin"]
    if Aeq.shape[0] >= 2 and rng.random() < 0.7:  # equality rows dependent on others
        k = int(rng.integers(1, 3))
        W = rng.standard_normal((k, Aeq.shape[0]))
        Aeq = np.vstack([Aeq, W @ Aeq])
        beq = np.concatenate([beq, W @ beq])
    if Aeq.shape[0] >= 1 and rng.random() < 0.3:  # an exact duplicate equality row
        i = int(rng.integers(0, Aeq.shape[0]))
        Aeq = np.vstack([Aeq, Aeq[i:i + 1]])
        beq = np.concatenate([beq, beq[i:i + 1]])
    if Ain.shape[0] >= 1:
        k = int(rng.integers(1, min(6, Ain.shape[0]) + 1))
        idx = rng.integers(0, Ain.shape[0], k)
        scale = np.where(rng.random(k) < 0.5, 1.0, rng.uniform(0.5, 3.0, k))
        Ain = np.vstack([Ain, scale[:, None] * Ain[idx]])  # duplicated / scaled rows
        bin_ = np.concatenate([bin_, scale * bin_[idx]])
        if rng.random() < 0.5:  # implied by a row: same normal, looser bound
            i = int(rng.integers(0, Ain.shape[0]))
            Ain = np.vstack([Ain, Ain[i:i + 1]])
            bin_ = np.concatenate([bin_, bin_[i:i + 1] - rng.uniform(0.01, 1.0)])
    if rng.random() < 0.3:  # a zero row that holds (0 >= -c)
        Ain = np.vstack([Ain, np.zeros((1, n))])
        bin_ = np.concatenate([bin_, [-rng.uniform(0.0, 1.0)]])
    perm = rng.permutation(Ain.shape[0])
    p.update(Aeq=Aeq, beq=beq, Ain=Ain[perm], bin=bin_[perm])
    return p


def infeasible_problem(rng, n):
    """Random rows plus a contradiction with a Farkas certificate (gap > 0)."""
    p = base_problem(rng, n)
    Aeq, beq, Ain, bin_ = p["Aeq"], p["beq"], p["Ain"], p["bin"]
    gap = float(rng.uniform(1e-3, 1.0))
    kind = int(rng.integers(0, 4))
    a = rng.standard_normal(n)
    b = float(rng.standard_normal())
    if kind == 0:  # a x >= b and a x <= b - gap
        Ain = np.vstack([Ain, a, -a])
        bin_ = np.concatenate([bin_, [b, -b + gap]])
    elif kind == 1:  # sum_i w_i (a_i x - b_i) >= 0 contradicted by one more row
        k = int(rng.integers(2, min(n, 8) + 1))
        A = rng.standard_normal((k, n))
        bb = rng.standard_normal(k)
        w = rng.uniform(0.2, 2.0, k)
        Ain = np.vstack([Ain, A, -(w @ A)])
        bin_ = np.concatenate([bin_, bb, [-(w @ bb) + gap]])
    elif kind == 2:  # dependent equality rows with an inconsistent right-hand side
        E = rng.standard_normal((2, n))
        e = rng.standard_normal(2)
        Aeq = np.vstack([E, E[0] + 2.0 * E[1], Aeq[:max(0, min(Aeq.shape[0], n - 3))]])
        beq0 = Aeq[3:] @ rng.standard_normal(n) if Aeq.shape[0] > 3 else np.zeros(0)
        beq = np.concatenate([e, [e[0] + 2.0 * e[1] + gap], beq0])
    else:  # an equality and an inequality that exclude each other
        Aeq = np.vstack([Aeq, a])
        beq = np.concatenate([beq, [b]])
        Ain = np.vstack([Ain, a])
        bin_ = np.concatenate([bin_, [b + gap]])
    perm = rng.permutation(Ain.shape[0])
    return dict(G=p["G"], g=p["g"], Aeq=Aeq, beq=beq, Ain=Ain[perm], bin=bin_[perm])


def reference_solve(p):
    """quadprog's x; daqp's where quadprog gives up (it reports "constraints are inconsistent"
    at some feasible vertices where more than n rows meet)."""
    n = p["G"].shape[0]
    C = np.vstack([p["Aeq"], p["Ain"]]).reshape(-1, n)
    b = np.concatenate([p["beq"], p["bin"]])
    if b.size == 0:
        return np.linalg.solve(p["G"], -p["g"])
    try:
        return quadprog.solve_qp(p["G"], -p["g"], C.T, b, p["Aeq"].shape[0])[0]
    except ValueError:
        m_eq = p["Aeq"].shape[0]
        upper = np.concatenate([p["beq"], np.full(p["bin"].size, 1e30)])
        sense = np.concatenate([np.full(m_eq, 5), np.zeros(p["bin"].size)]).astype(np.int32)
        x, _, exitflag, _ = daqp.solve(p["G"], p["g"], C, upper, b, sense)
        assert exitflag == 1, f"daqp exit flag {exitflag} on a feasible problem"
        return np.asarray(x)


def to_json(p):
    return {k: np.asarray(v).tolist() for k, v in p.items()}


def solve_batch(tmp_path, name, problems):
    path = write_json(tmp_path / f"{name}.json", problems)
    results = run_tool("qp_solve", path).json()
    assert isinstance(results, list) and len(results) == len(problems)
    return results


def kkt_residuals(p, r):
    """Scaled KKT residuals of a result: stationarity, primal (eq, in), complementarity, sign."""
    x = np.array(r["x"])
    lam = np.array(r["multipliers"])
    m_eq = p["Aeq"].shape[0]
    n = x.size
    Aeq = p["Aeq"].reshape(-1, n)
    Ain = p["Ain"].reshape(-1, n)
    l_eq, l_in = lam[:m_eq], lam[m_eq:]
    stat = p["G"] @ x + p["g"] - Aeq.T @ l_eq - Ain.T @ l_in
    s_in = Ain @ x - p["bin"]
    scale = 1.0 + np.abs(x).max()
    return dict(
        stationarity=np.abs(stat).max(initial=0.0) / (1.0 + np.abs(lam).max(initial=0.0)) / scale,
        equality=np.abs(Aeq @ x - p["beq"]).max(initial=0.0) / scale,
        inequality=max(0.0, -s_in.min(initial=0.0)) / scale,
        complementarity=np.abs(l_in * s_in).max(initial=0.0) / scale,
        dual_sign=max(0.0, -l_in.min(initial=0.0)),
    )


@pytest.fixture(scope="module")
def feasible_set():
    """(problem, quadprog x, known x or None) for N_FEASIBLE seeded problems."""
    out = []
    for seed in range(N_FEASIBLE):
        rng = np.random.default_rng(10_000 + seed)
        n = pick_n(rng)
        known = None
        if seed % 2 == 0:
            base = base_problem(rng, n)
        else:
            base, known = kkt_problem(rng, n)
        x_ref = reference_solve(base)
        p = degenerate(rng, base) if seed % 3 != 0 else base
        out.append((p, x_ref, known))
    return out


@pytest.fixture(scope="module")
def feasible_results(tmp_path_factory, feasible_set):
    return solve_batch(tmp_path_factory.mktemp("qp"), "feasible",
                       [to_json(p) for p, _, _ in feasible_set])


def test_feasible_problems_match_quadprog_and_kkt(feasible_set, feasible_results):
    failures = []
    worst = dict(x=0.0, stationarity=0.0, equality=0.0, inequality=0.0, complementarity=0.0,
                 dual_sign=0.0)
    sizes = [p["G"].shape[0] for p, _, _ in feasible_set]
    assert min(sizes) <= 6 and max(sizes) >= 110, "the sizes must span 5..120 variables"
    for i, ((p, x_ref, known), r) in enumerate(zip(feasible_set, feasible_results)):
        if r["status"] != "optimal":
            failures.append(f"problem {i}: status {r['status']} ({r['message']})")
            continue
        x = np.array(r["x"])
        err = np.abs(x - x_ref).max() / max(1.0, np.abs(x_ref).max())
        worst["x"] = max(worst["x"], err)
        if err > X_TOL:
            failures.append(f"problem {i} (n={x.size}): |x - x_reference| = {err:.2e}")
        if known is not None:
            err_known = np.abs(x - known).max() / max(1.0, np.abs(known).max())
            if err_known > X_TOL:
                failures.append(f"problem {i}: |x - x_constructed| = {err_known:.2e}")
        for key, value in kkt_residuals(p, r).items():
            worst[key] = max(worst[key], value)
            if value > KKT_TOL:
                failures.append(f"problem {i} (n={x.size}): KKT {key} residual {value:.2e}")
    print("worst over", len(feasible_set), "problems:",
          ", ".join(f"{k} {v:.1e}" for k, v in worst.items()))
    assert not failures, f"{len(failures)} failures:\n" + "\n".join(failures[:30])


def test_multipliers_and_active_set_are_consistent(feasible_set, feasible_results):
    """Every row with a nonzero multiplier is in the active set, and active inequality rows hold
    with equality."""
    for i, ((p, _, _), r) in enumerate(zip(feasible_set, feasible_results)):
        lam = np.array(r["multipliers"])
        active = set(r["active_set"])
        m_eq = p["Aeq"].shape[0]
        assert lam.size == m_eq + p["Ain"].shape[0], f"problem {i}"
        assert all(j in active for j in np.flatnonzero(lam)), f"problem {i}"
        x = np.array(r["x"])
        for j in active:
            if j >= m_eq:
                s = p["Ain"][j - m_eq] @ x - p["bin"][j - m_eq]
                assert abs(s) <= KKT_TOL * (1.0 + np.abs(x).max()), f"problem {i} row {j}: {s}"


def test_warm_start_gives_the_cold_answer(tmp_path, feasible_set, feasible_results):
    """Warm starts from the cold active set and from random row subsets (most of them wrong)
    give the cold solution."""
    rng = np.random.default_rng(7)
    chosen = rng.choice(len(feasible_set), N_WARM, replace=False)
    problems, cold = [], []
    for i in chosen:
        p, _, _ = feasible_set[i]
        r = feasible_results[i]
        m_eq, m_in = p["Aeq"].shape[0], p["Ain"].shape[0]
        guesses = [r["active_set"],
                   (m_eq + rng.choice(m_in, min(m_in, int(rng.integers(0, m_in + 1))),
                                      replace=False)).tolist() if m_in else []]
        for guess in guesses:
            problems.append(dict(to_json(p), warm_start=[int(k) for k in guess]))
            cold.append((i, r))
    results = solve_batch(tmp_path, "warm", problems)
    for (i, r_cold), r_warm, prob in zip(cold, results, problems):
        p = feasible_set[i][0]
        assert r_warm["status"] == "optimal", f"problem {i}: {r_warm['message']}"
        x_c, x_w = np.array(r_cold["x"]), np.array(r_warm["x"])
        err = np.abs(x_c - x_w).max() / max(1.0, np.abs(x_c).max())
        assert err <= 1e-9, f"problem {i} warm {prob['warm_start']}: |x_warm - x_cold| = {err}"
        for key, value in kkt_residuals(p, r_warm).items():
            assert value <= KKT_TOL, f"problem {i} warm: KKT {key} residual {value:.2e}"


def test_infeasible_problems_are_reported_infeasible(tmp_path):
    problems = []
    for seed in range(N_INFEASIBLE):
        rng = np.random.default_rng(90_000 + seed)
        problems.append(infeasible_problem(rng, pick_n(rng)))
    results = solve_batch(tmp_path, "infeasible", [to_json(p) for p in problems])
    wrong = [f"problem {i} (n={p['G'].shape[0]}): {r['status']} {r['message']}"
             for i, (p, r) in enumerate(zip(problems, results)) if r["status"] != "infeasible"]
    assert not wrong, f"{len(wrong)} not reported infeasible:\n" + "\n".join(wrong[:30])
    for r in results:
        assert all(np.isfinite(r["x"])), "an infeasible result must still be finite"


def test_tool_reports_bad_input(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"G": [[1, 0], [0, 1]], "g": [1, ')
    run = run_tool("qp_solve", bad)
    assert run.returncode == 2 and "JSON" in run.stderr, run.describe()
    ragged = write_json(tmp_path / "ragged.json", {"G": [[1, 0], [0]], "g": [1, 1]})
    run = run_tool("qp_solve", ragged)
    assert run.returncode == 2 and "row 1" in run.stderr, run.describe()
    nan = write_json(tmp_path / "nan.json", {"G": [[1, 0], [0, 1]], "g": ["nan", 1]})
    r = run_tool("qp_solve", nan).json()
    assert r["status"] == "invalid_input" and "non-finite" in r["message"]
    psd = write_json(tmp_path / "psd.json", {"G": [[1, 0], [0, 0]], "g": [1, 1]})
    r = run_tool("qp_solve", psd).json()
    assert r["status"] == "invalid_input" and "regularization" in r["message"]
    # Missing Aeq/Ain are empty; the unconstrained minimum is -G^{-1} g.
    r = run_tool("qp_solve", write_json(tmp_path / "free.json",
                                        {"G": [[2, 0], [0, 4]], "g": [2, -4]})).json()
    assert r["status"] == "optimal" and np.allclose(r["x"], [-1.0, 1.0], atol=1e-14)
