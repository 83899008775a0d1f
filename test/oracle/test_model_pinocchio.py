"""The robot model of eq. (1) checked against Pinocchio, through the `model_info` tool.

  model_info <urdf> [--fixed-base] [--state FILE] [--frames a,b,...]

For each robot, seeded random states (q within the URDF joint limits, a random base pose,
moderate velocities) are written to one state file; every quantity the tool prints is compared
with Pinocchio 4 (the `pin` wheel) at the same state:
  M(q)         crba (upper triangle mirrored)
  b(q, qd)     nonLinearEffects, gravity -9.81 z
  frame pose   oMf (position, world-from-frame rotation)
  J_frame      getFrameJacobian(LOCAL_WORLD_ALIGNED): origin of the frame, world axes, [lin; ang]
  Jdot*qd      forwardKinematics(q, qd, 0): classical linear acceleration and angular
               acceleration of the frame, LOCAL_WORLD_ALIGNED
  CoM, J_CoM   centerOfMass, jacobianCenterOfMass
Pass: |ours - ref| <= 1e-8 * max(1, |ref|) (Frobenius / Euclidean norms) at every state.

Coordinates: our floating base is q = [x, y, z, yaw, pitch, roll, joints...], R = Rz Ry Rx, qd the
time derivatives, i.e. Pinocchio's composite root joint PX PY PZ RZ RY RX. Joint order may differ:
the columns are mapped by joint name (the tool prints its joint_names in q order).

On failure each check names the states, joints (columns) and components that disagree, so the
message says where the model is wrong.
"""

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from conftest import EXAMPLE_ROBOTS, REPO, run_tool, write_json
from model_oracle import TOL, VIRTUAL, Reference, rel_err

ROWS6 = ["vx", "vy", "vz", "wx", "wy", "wz"]
XYZ = ["x", "y", "z"]


@dataclass(frozen=True)
class Robot:
    key: str
    urdf: Path
    feet: tuple  # two frames (links or fixed frames) whose Jacobians are checked
    floating: bool = True
    n_states: int = 200


ROBOTS = [
    Robot("biped", REPO / "urdf" / "biped.urdf", ("l_sole", "r_sole")),
    # Unitree G1, 29 revolute joints, no mimic joints; the ankle roll links carry the soles.
    Robot("g1", EXAMPLE_ROBOTS / "g1_description" / "urdf" / "g1_29dof_rev_1_0.urdf",
          ("left_ankle_roll_link", "right_ankle_roll_link")),
    # Romeo (reduced hands), 31 revolute joints, sole frames on fixed joints.
    Robot("romeo", EXAMPLE_ROBOTS / "romeo_description" / "urdf" / "romeo_small.urdf",
          ("l_sole", "r_sole")),
    # The same biped welded to the world: the tool's --fixed-base against Pinocchio without root.
    Robot("biped_fixed", REPO / "urdf" / "biped.urdf", ("l_sole", "r_sole"), floating=False,
          n_states=50),
]


class Case:
    """One robot: the tool's JSON output and Pinocchio's values at the same states, both in
    our coordinate order."""

    def __init__(self, robot, tmp_dir):
        self.robot = robot
        self.ref = Reference(robot.urdf, robot.floating)
        rng = np.random.default_rng(20200701)
        samples = [self.ref.sample(rng) for _ in range(robot.n_states)]

        # Learn our joint order first (one state at the neutral configuration).
        nv = self.ref.model.nv
        probe = write_json(Path(tmp_dir) / f"{robot.key}_probe.json",
                           {"q": [0.0] * nv, "qd": [0.0] * nv})
        self.probe_run = run_tool("model_info", *self.base_args(), "--state", probe)
        head = self.probe_run.json()
        assert head.get("nq") == nv, (
            f"{robot.key}: nq {head.get('nq')} but Pinocchio has n_v {nv}; joint_names "
            f"{head.get('joint_names')} vs Pinocchio {self.ref.v_names}")
        self.names = list(head["joint_names"])
        missing = sorted(set(self.ref.v_names) - set(self.names))
        extra = sorted(set(self.names) - set(self.ref.v_names))
        assert not missing and not extra, (
            f"{robot.key}: joint names differ: missing {missing}, unexpected {extra}")
        # perm[i] = Pinocchio v index of our coordinate i.
        self.perm = np.array([self.ref.v_names.index(n) for n in self.names])

        self.states = [{"q": qv[self.perm].tolist(), "qd": v[self.perm].tolist()}
                       for qv, v in samples]
        state_file = write_json(Path(tmp_dir) / f"{robot.key}_states.json",
                                {"states": self.states})
        self.run = run_tool("model_info", *self.base_args(), "--state", state_file,
                            "--frames", ",".join(robot.feet))
        self.out = self.run.json()
        results = self.out.get("results")
        assert isinstance(results, list) and len(results) == len(self.states), (
            f"{robot.key}: expected {len(self.states)} results, got "
            f"{None if results is None else len(results)}")
        self.ours = results
        P = self.perm
        self.refs = []
        for qv, v in samples:
            r = self.ref.evaluate(qv, v, robot.feet)
            r["M"] = r["M"][np.ix_(P, P)]
            r["b"] = r["b"][P]
            r["com_jacobian"] = r["com_jacobian"][:, P]
            for f in r["frames"].values():
                f["jacobian"] = f["jacobian"][:, P]
            self.refs.append(r)

    def base_args(self):
        return [self.robot.urdf] + ([] if self.robot.floating else ["--fixed-base"])


@pytest.fixture(scope="module", params=ROBOTS, ids=[r.key for r in ROBOTS])
def case(request, tmp_path_factory):
    robot = request.param
    if not robot.urdf.is_file():
        pytest.fail(f"URDF {robot.urdf} not found")
    return Case(robot, tmp_path_factory.mktemp(robot.key))


# ---- comparison and reporting ------------------------------------------------------------------

def _as_array(value, shape, where):
    try:
        a = np.array(value, dtype=float)
    except (TypeError, ValueError) as e:
        raise AssertionError(f"{where}: not a numeric array ({e}): {str(value)[:200]}")
    assert a.shape == shape, f"{where}: shape {a.shape}, expected {shape}"
    return a


def compare(case, label, ours_of, ref_of, row_names, col_names=None):
    """Compares one quantity at every state. ours_of(result), ref_of(reference) give the raw tool
    value and the reference array. Fails with a report naming the worst states and, across all
    states, the columns (joints) and rows (components) that disagree."""
    with np.errstate(over="ignore", invalid="ignore"):  # garbage values are reported, not warned
        _compare(case, label, ours_of, ref_of, row_names, col_names)


def _compare(case, label, ours_of, ref_of, row_names, col_names):
    n = len(case.refs)
    errs = np.zeros(n)
    # Worst error per row / column over all states, each relative to its state's matrix norm.
    row_worst = np.zeros(len(row_names))
    col_worst = np.zeros(len(col_names)) if col_names else None
    worst = (-1.0, None)
    for k in range(n):
        ref = np.asarray(ref_of(case.refs[k]), dtype=float)
        where = f"{case.robot.key} state {k} {label}"
        ours = _as_array(ours_of(case.ours[k]), ref.shape, where)
        err = rel_err(ours, ref)
        if not err <= TOL:  # NaN counts as a failure
            err = err if math.isfinite(err) else math.inf
        errs[k] = err
        scale = max(1.0, float(np.linalg.norm(ref)))
        diff = np.abs(ours - ref) / scale
        diff[~np.isfinite(diff)] = math.inf
        if ref.ndim == 1:
            row_worst = np.maximum(row_worst, diff)
        else:
            row_worst = np.maximum(row_worst, np.linalg.norm(diff, axis=1))
            col_worst = np.maximum(col_worst, np.linalg.norm(diff, axis=0))
        if err > worst[0]:
            worst = (err, k)
    bad = np.flatnonzero(errs > TOL)
    if bad.size == 0:
        return
    k = worst[1]
    lines = [f"{case.robot.key}: {label} disagrees with Pinocchio at {bad.size}/{n} states "
             f"(tolerance {TOL:g} relative); worst relative error {worst[0]:.3e} at state {k} "
             f"(first failing states {bad[:8].tolist()})"]

    def top(values, names, what):
        order = np.argsort(-values)
        items = [f"{names[i]} {values[i]:.2e}" for i in order if values[i] > TOL][:12]
        if items:
            lines.append(f"  {what} over tolerance (worst over states): " + ", ".join(items))

    top(row_worst, row_names, "rows")
    if col_names:
        top(col_worst, col_names, "columns")
    ref = np.asarray(ref_of(case.refs[k]), dtype=float)
    ours = np.array(ours_of(case.ours[k]), dtype=float)
    np.set_printoptions(precision=6, suppress=True, linewidth=150)
    if ref.ndim == 1 or ref.size <= 24:
        lines.append(f"  state {k} ours: {ours.tolist()}")
        lines.append(f"  state {k} ref:  {ref.tolist()}")
    else:
        i, j = np.unravel_index(np.argmax(np.abs(ours - ref)), ref.shape)
        cn = col_names[j] if col_names else j
        lines.append(f"  state {k} largest entry difference at ({row_names[i]}, {cn}): "
                     f"ours {ours[i, j]:.9g}, ref {ref[i, j]:.9g}")
        zero_ref = (ref == 0.0) & ~(ours == 0.0)
        if zero_ref.any():
            pairs = [f"({row_names[a]}, {col_names[c] if col_names else c})"
                     for a, c in zip(*np.nonzero(zero_ref))][:6]
            lines.append(f"  state {k}: {int(zero_ref.sum())} entries are exactly 0 in Pinocchio "
                         f"(no common ancestor joint) but not in ours (left unwritten?), e.g. "
                         + ", ".join(pairs))
        if ours.shape[0] == ours.shape[1]:
            asym = rel_err(ours, ours.T)
            if not asym <= TOL:
                lines.append(f"  ours is not symmetric at state {k}: |A - A^T| / max(1, |A|) "
                             f"= {asym:.3e} (lower triangle not filled?)")
    lines.append(f"  state {k}: q = {case.states[k]['q']}")
    lines.append(f"             qd = {case.states[k]['qd']}")
    lines.append(f"  joint order (ours): {case.names}")
    pytest.fail("\n".join(lines), pytrace=False)


# ---- the checks ------------------------------------------------------------------------------

def test_model_metadata(case):
    out, ref = case.out, case.ref
    nv = ref.model.nv
    assert out["nq"] == nv
    assert out["nu"] == nv - (6 if case.robot.floating else 0)
    mass = pin.computeTotalMass(ref.model)
    assert abs(out["mass"] - mass) <= 1e-9 * mass, f"mass {out['mass']} vs Pinocchio {mass}"
    if case.robot.floating:
        assert case.names[:6] == VIRTUAL, f"virtual coordinates first: {case.names[:6]}"
    else:
        assert not set(VIRTUAL) & set(case.names), "fixed base has no virtual joints"
    # Limits of every actuated joint as in the URDF (Pinocchio's copy of it).
    q_min, q_max = out["q_min"], out["q_max"]
    assert len(q_min) == nv and len(q_max) == nv
    wrong = []
    m = ref.model
    for i, name in enumerate(case.names):
        if name in VIRTUAL:
            continue
        jm = m.joints[m.getJointId(name)]
        if jm.nq != 1:
            continue
        lo, hi = m.lowerPositionLimit[jm.idx_q], m.upperPositionLimit[jm.idx_q]
        if q_min[i] is None or q_max[i] is None or abs(q_min[i] - lo) > 1e-12 or \
                abs(q_max[i] - hi) > 1e-12:
            wrong.append(f"{name}: ours [{q_min[i]}, {q_max[i]}], URDF [{lo}, {hi}]")
    assert not wrong, "joint limits differ: " + "; ".join(wrong)


def test_mass_matrix(case):
    compare(case, "M", lambda o: o["M"], lambda r: r["M"], case.names, case.names)


def test_bias(case):
    compare(case, "b", lambda o: o["b"], lambda r: r["b"], case.names)


def test_center_of_mass(case):
    compare(case, "com", lambda o: o["com"], lambda r: r["com"], XYZ)


def test_center_of_mass_jacobian(case):
    compare(case, "com_jacobian", lambda o: o["com_jacobian"], lambda r: r["com_jacobian"],
            XYZ, case.names)


@pytest.mark.parametrize("foot", [0, 1], ids=["foot0", "foot1"])
def test_frame_position(case, foot):
    f = case.robot.feet[foot]
    compare(case, f"{f}.position", lambda o: o["frames"][f]["position"],
            lambda r: r["frames"][f]["position"], XYZ)


@pytest.mark.parametrize("foot", [0, 1], ids=["foot0", "foot1"])
def test_frame_rotation(case, foot):
    f = case.robot.feet[foot]
    compare(case, f"{f}.rotation", lambda o: o["frames"][f]["rotation"],
            lambda r: r["frames"][f]["rotation"], ["r0", "r1", "r2"], ["c0", "c1", "c2"])


@pytest.mark.parametrize("foot", [0, 1], ids=["foot0", "foot1"])
def test_frame_jacobian(case, foot):
    f = case.robot.feet[foot]
    compare(case, f"{f}.jacobian", lambda o: o["frames"][f]["jacobian"],
            lambda r: r["frames"][f]["jacobian"], ROWS6, case.names)


@pytest.mark.parametrize("foot", [0, 1], ids=["foot0", "foot1"])
def test_frame_jdot_qd(case, foot):
    f = case.robot.feet[foot]
    compare(case, f"{f}.jdot_qd", lambda o: o["frames"][f]["jdot_qd"],
            lambda r: r["frames"][f]["jdot_qd"], ROWS6)


# ---- behaviour on bad input --------------------------------------------------------------------

BIPED = REPO / "urdf" / "biped.urdf"
BIPED_NQ = 18  # 6 virtual + 12 leg joints


def assert_clean_failure(run, *must_mention):
    """Nonzero exit (not a crash by signal), an error message mentioning one of `must_mention`
    (case-insensitive), and no result JSON on stdout."""
    assert run.returncode > 0, "expected a nonzero exit status, not " + (
        "success" if run.returncode == 0 else f"signal {-run.returncode}") + "\n" + run.describe()
    assert '"results"' not in run.stdout, "results printed despite the error\n" + run.describe()
    text = run.output.lower()
    assert any(str(w).lower() in text for w in must_mention), (
        f"error message should mention one of {list(must_mention)}\n" + run.describe())


def good_state():
    q = [0.0] * BIPED_NQ
    q[2] = 0.9
    return {"q": q, "qd": [0.1] * BIPED_NQ}


def test_summary_without_state():
    run = run_tool("model_info", BIPED)
    assert run.returncode == 0, run.describe()
    assert run.stdout.strip(), "no summary printed"


def test_error_missing_file(tmp_path):
    missing = tmp_path / "no_such_robot.urdf"
    assert_clean_failure(run_tool("model_info", missing), "no_such_robot.urdf")
    state = write_json(tmp_path / "s.json", good_state())
    assert_clean_failure(run_tool("model_info", missing, "--state", state),
                         "no_such_robot.urdf")


@pytest.mark.parametrize("xml", [
    "<robot name='broken'><link name='a'><inertial><mass value='1'/></inertial></robot",
    "this is not xml at all",
    # Well-formed XML, but the joint's child link does not exist.
    "<robot name='broken'><link name='a'/><joint name='j' type='revolute'><parent link='a'/>"
    "<child link='ghost'/><axis xyz='0 0 1'/><limit lower='-1' upper='1' effort='1' "
    "velocity='1'/></joint></robot>",
], ids=["truncated", "not_xml", "dangling_joint"])
def test_error_malformed_urdf(tmp_path, xml):
    bad = tmp_path / "malformed_robot.urdf"
    bad.write_text(xml)
    assert_clean_failure(run_tool("model_info", bad), "malformed_robot.urdf")


def test_error_unknown_frame(tmp_path):
    state = write_json(tmp_path / "s.json", good_state())
    run = run_tool("model_info", BIPED, "--state", state, "--frames", "l_sole,no_such_frame")
    assert_clean_failure(run, "no_such_frame")


@pytest.mark.parametrize("field,nan", [("q", float("nan")), ("qd", float("nan")),
                                       ("q", "nan"), ("qd", "NaN")],
                         ids=["q_literal", "qd_literal", "q_string", "qd_string"])
def test_error_nan_in_state(tmp_path, field, nan):
    # JSON has no NaN. Python writes the common extension `NaN` (the JSON reader must reject it);
    # model_info also reads the strings "nan"/"NaN" as NaN, which the model's finiteness check
    # must reject. Either way: a clean failure naming the file, the NaN or the bad number.
    s = good_state()
    s[field][7] = nan
    state = write_json(tmp_path / "nan_state.json", s)
    run = run_tool("model_info", BIPED, "--state", state, "--frames", "l_sole")
    assert_clean_failure(run, "nan_state.json", "nan", "finite", "number")
    # Also inside a list of states, after a good one.
    state = write_json(tmp_path / "nan_states.json", {"states": [good_state(), s]})
    run = run_tool("model_info", BIPED, "--state", state, "--frames", "l_sole")
    assert_clean_failure(run, "nan_states.json", "nan", "finite", "number")


@pytest.mark.parametrize("field,size", [("q", BIPED_NQ - 1), ("qd", BIPED_NQ + 1), ("q", 0)])
def test_error_wrong_size(tmp_path, field, size):
    s = good_state()
    s[field] = [0.0] * size
    state = write_json(tmp_path / "wrong_size.json", s)
    run = run_tool("model_info", BIPED, "--state", state, "--frames", "l_sole")
    assert_clean_failure(run, "size", str(BIPED_NQ))
