"""Crocoddyl 3.2.1 (FDDP) and mim-solvers (CSQP) on our TALOS step OCP, re-checked by our checker.

  .venv-croc/bin/python bench/crocoddyl/talos_step.py --request REQ.json --config config/talos.yaml
      --out-dir DIR [--repeats 3] [--knot-dt 0.01] [--solvers fddp,csqp]

REQ.json is plan_transition's request with "qf"/"qdf" (bench/crocoddyl/talos_step_request.json):
single support on `stance`, the other sole to `swing_target`, landing in double support at
t_f = horizon; x_0 = (q0, qd0), x_f = (qf, qdf), in our coordinates.

The robot: the config's robot.urdf with its robot.locked_joints held and removed
(pin.buildReducedModel, as model_oracle.reduced_model does for the model oracle). The problem
(Crocoddyl's usual walking formulation, on 6-D contacts, LOCAL frame, no Baumgarte gains):
  knots 0 .. N-1 (knot_dt each, N = horizon / knot_dt): single support on the stance sole;
  knot N (at t_f): double support, its control holding the landed robot; terminal knot N+1.
Costs: |x - x_f|^2 (weighted, everywhere; heavy at knots N, N+1), |u / u_max|^2, swing sole
placement on the target and zero velocity at t_f, state bounds (joint limits) as a barrier.
FDDP: the wrench cone (config contact: mu, half_length, half_width; the 16 rows of our cone:
4 facets, outer approximation) and |u| <= u_max as quadratic-barrier penalties.
CSQP: the same costs without those two penalties; cone and torque bounds as hard constraints.

The 1 ms trajectory the checker sees: Crocoddyl's controls rolled out from x_0 through 1 ms
contact-dynamics action models of the same robot (zero-order hold of each knot's control, open
loop: what the solution commands), single support until t_f, and at t_f the double-support
dynamics with knot N's control. Every sample is converted to our coordinates (q = [x, y, z, yaw,
pitch, roll, joints], qd and qdd their time derivatives) through model_oracle's composite root
joint (PX PY PZ RZ RY RX), wrenches to the world at the sole centres. Writes
DIR/crocoddyl_<solver>.json (check_transition's trajectory format) and prints per solver:
  REF solver=<crocoddyl_fddp|mim_solvers_csqp> ref_s=<median solve wall s> iters=<n>
      converged=<0|1> cost=<solver's cost> knot_dt=<s>
ref_s is solver.solve() alone (problem built beforehand, not timed).
"""

import argparse
import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pinocchio as pin
import yaml

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "test" / "oracle"))
import crocoddyl  # noqa: E402
import mim_solvers  # noqa: E402
from model_oracle import Reference, reduced_model  # noqa: E402

ROLLOUT_DT = 0.001  # [s] the checker's (and the controller's) rate


def fail(msg):
    print(f"[talos_step] {msg}", file=sys.stderr)
    sys.exit(2)


def load_config(path):
    cfg = yaml.safe_load(Path(path).read_text())
    try:
        robot, contact = cfg["robot"], cfg["contact"]
        urdf = os.path.expandvars(robot["urdf"])
        out = {
            "urdf": urdf,
            "locked": {k: float(v) for k, v in robot.get("locked_joints", {}).items()},
            "mu": float(contact["mu"]),
            "half_length": float(contact["half_length"]),
            "half_width": float(contact["half_width"]),
            "sole": {"left": contact["left_sole_frame"], "right": contact["right_sole_frame"]},
        }
    except KeyError as e:
        fail(f"{path}: missing key {e}")
    if "$" in out["urdf"] or not Path(out["urdf"]).is_file():
        fail(f"{path}: robot.urdf '{out['urdf']}' not found (source scripts/env.sh)")
    return out


class Coordinates:
    """Pinocchio's free-flyer model (the one Crocoddyl solves on) and the map to our coordinates
    through model_oracle's Reference (composite root PX PY PZ RZ RY RX = ours)."""

    def __init__(self, cfg, our_joint_names):
        self.ours = Reference(cfg["urdf"], floating=True, locked=cfg["locked"])
        full = pin.buildModelFromUrdf(cfg["urdf"], pin.JointModelFreeFlyer())
        self.ff = reduced_model(full, cfg["locked"]) if cfg["locked"] else full
        mc = self.ours.model
        self.dc = mc.createData()
        if list(self.ours.v_names) != list(our_joint_names):
            # our order (model_info) from the oracle's: a permutation of names
            missing = set(our_joint_names) ^ set(self.ours.v_names)
            if missing:
                fail(f"joints of model_info and Pinocchio differ: {sorted(missing)}")
        self.perm = np.array([self.ours.v_names.index(n) for n in our_joint_names])
        self.inv = np.argsort(self.perm)
        ff_names = [self.ff.names[j] for j in range(2, self.ff.njoints)]
        assert ff_names == self.ours.v_names[6:], "free-flyer and composite joint orders differ"
        self.nq_ours = mc.nv

    def _base_jacobian(self, qc):
        """S(q) of the composite root: base-body local twist = S vc[:6]."""
        J = pin.computeJointJacobian(self.ours.model, self.dc, qc, 1)
        return J[:, :6].copy()

    def to_ff(self, q, qd):
        """Our (q, qd) -> Crocoddyl's state [q_ff; v_ff]."""
        qc, vc = np.asarray(q)[self.inv], np.asarray(qd)[self.inv]
        R = pin.rpy.rpyToMatrix(qc[5], qc[4], qc[3])
        quat = pin.Quaternion(R).coeffs()
        q_ff = np.concatenate([qc[:3], quat, qc[6:]])
        pin.forwardKinematics(self.ours.model, self.dc, qc, vc)
        v_ff = np.concatenate([self.dc.v[1].vector, vc[6:]])
        return np.concatenate([q_ff, v_ff])

    def to_ours(self, x_ff, a_ff):
        """Crocoddyl's state and acceleration -> our (q, qd, qdd)."""
        nq = self.ff.nq
        q_ff, v_ff = x_ff[:nq], x_ff[nq:]
        R = pin.Quaternion(q_ff[3:7]).toRotationMatrix()
        roll, pitch, yaw = pin.rpy.matrixToRpy(R)
        qc = np.concatenate([q_ff[:3], [yaw, pitch, roll], q_ff[7:]])
        S = self._base_jacobian(qc)
        vc = np.concatenate([np.linalg.solve(S, v_ff[:6]), v_ff[6:]])
        ac = np.concatenate([np.zeros(6), a_ff[6:]])
        pin.forwardKinematics(self.ours.model, self.dc, qc, vc, ac)
        drift = self.dc.a[1].vector  # S-dot vc of the root (its joint acceleration at zero)
        ac[:6] = np.linalg.solve(S, a_ff[:6] - drift)
        return qc[self.perm], vc[self.perm], ac[self.perm]


class StepProblem:
    """The Crocoddyl action models of the step (see the file comment)."""

    def __init__(self, cfg, req, coords, knot_dt, hard):
        self.cfg, self.req, self.c = cfg, req, coords
        m = coords.ff
        self.state = crocoddyl.StateMultibody(m)
        self.act = crocoddyl.ActuationModelFloatingBase(self.state)
        self.nu = self.act.nu
        self.u_max = m.effortLimit[6:].copy()
        stance = req["stance"]
        swing = "right" if stance == "left" else "left"
        self.stance_id = m.getFrameId(cfg["sole"][stance])
        self.swing_id = m.getFrameId(cfg["sole"][swing])
        self.stance_name, self.swing_name = stance, swing
        self.x0 = coords.to_ff(req["q0"], req.get("qd0", [0.0] * coords.nq_ours))
        self.xf = coords.to_ff(req["qf"], req.get("qdf", [0.0] * coords.nq_ours))
        self.stance_pose = self._pose(req["stance_pose"])
        self.target_pose = self._pose(req["swing_target"])
        self.hard = hard
        self.knot_dt = knot_dt
        self.n_ss = int(round(req["horizon"] / knot_dt))
        if abs(self.n_ss * knot_dt - req["horizon"]) > 1e-9:
            fail(f"horizon {req['horizon']} s is not a multiple of the knot dt {knot_dt} s")
        cone = crocoddyl.WrenchCone(np.eye(3), cfg["mu"],
                                    np.array([2 * cfg["half_length"], 2 * cfg["half_width"]]),
                                    4, False)
        self.cone = cone

    @staticmethod
    def _pose(p):
        yaw = float(p.get("yaw", 0.0))
        return pin.SE3(pin.rpy.rpyToMatrix(0.0, 0.0, yaw), np.array(p["position"], dtype=float))

    def _contacts(self, ids):
        contacts = crocoddyl.ContactModelMultiple(self.state, self.nu)
        for name, fid, pose in ids:
            c = crocoddyl.ContactModel6D(self.state, fid, pose, pin.LOCAL, self.nu,
                                         np.array([0.0, 0.0]))
            contacts.addContact(name, c)
        return contacts

    def _stance_contacts(self, double):
        ids = [(self.stance_name, self.stance_id, self.stance_pose)]
        if double:
            ids.append((self.swing_name, self.swing_id, self.target_pose))
        return ids

    def _costs(self, ids, w_state, terminal=False):
        s, nu = self.state, self.nu
        costs = crocoddyl.CostModelSum(s, nu)
        nv = s.nv
        # |x - x_f|^2: base pose and joints, velocities lighter (like our w_position, w_velocity)
        wx = np.concatenate([np.full(nv, 1.0), np.full(nv, 0.1)])
        costs.addCost("state", crocoddyl.CostModelResidual(
            s, crocoddyl.ActivationModelWeightedQuad(wx ** 2),
            crocoddyl.ResidualModelState(s, self.xf, nu)), w_state)
        # joint limits as a barrier on the state
        lb = np.concatenate([s.lb[1:s.nv + 1], s.lb[-s.nv:]])
        ub = np.concatenate([s.ub[1:s.nv + 1], s.ub[-s.nv:]])
        costs.addCost("limits", crocoddyl.CostModelResidual(
            s, crocoddyl.ActivationModelQuadraticBarrier(crocoddyl.ActivationBounds(lb, ub)),
            crocoddyl.ResidualModelState(s, nu)), 1e3)
        if terminal:
            costs.addCost("swing_pose", crocoddyl.CostModelResidual(
                s, crocoddyl.ResidualModelFramePlacement(s, self.swing_id, self.target_pose, nu)),
                1e5)
            return costs
        # |u / u_max|^2
        costs.addCost("torque", crocoddyl.CostModelResidual(
            s, crocoddyl.ActivationModelWeightedQuad(1.0 / self.u_max ** 2),
            crocoddyl.ResidualModelControl(s, nu)), 1.0)
        if not self.hard:
            costs.addCost("torque_bounds", crocoddyl.CostModelResidual(
                s, crocoddyl.ActivationModelQuadraticBarrier(
                    crocoddyl.ActivationBounds(-self.u_max, self.u_max)),
                crocoddyl.ResidualModelControl(s, nu)), 1e2)
            for name, fid, _ in ids:
                costs.addCost(f"cone_{name}", crocoddyl.CostModelResidual(
                    s, crocoddyl.ActivationModelQuadraticBarrier(
                        crocoddyl.ActivationBounds(self.cone.lb, self.cone.ub)),
                    crocoddyl.ResidualModelContactWrenchCone(s, fid, self.cone, nu)), 1e2)
        return costs

    def _constraints(self, ids):
        s, nu = self.state, self.nu
        cons = crocoddyl.ConstraintModelManager(s, nu)
        cons.addConstraint("torque", crocoddyl.ConstraintModelResidual(
            s, crocoddyl.ResidualModelControl(s, nu), -self.u_max, self.u_max))
        for name, fid, _ in ids:
            cons.addConstraint(f"cone_{name}", crocoddyl.ConstraintModelResidual(
                s, crocoddyl.ResidualModelContactWrenchCone(s, fid, self.cone, nu),
                self.cone.lb, self.cone.ub))
        return cons

    def differential(self, double, w_state, terminal=False, with_costs=True):
        ids = self._stance_contacts(double)
        contacts = self._contacts(ids)
        costs = self._costs(ids, w_state, terminal) if with_costs else \
            crocoddyl.CostModelSum(self.state, self.nu)
        if self.hard and not terminal and with_costs:
            return crocoddyl.DifferentialActionModelContactFwdDynamics(
                self.state, self.act, contacts, costs, self._constraints(ids), 0.0, True)
        return crocoddyl.DifferentialActionModelContactFwdDynamics(
            self.state, self.act, contacts, costs, 0.0, True)

    def shooting_problem(self):
        dt = self.knot_dt
        running = [crocoddyl.IntegratedActionModelEuler(self.differential(False, 1.0), dt)
                   for _ in range(self.n_ss)]
        running.append(crocoddyl.IntegratedActionModelEuler(self.differential(True, 1e4), dt))
        terminal = crocoddyl.IntegratedActionModelEuler(
            self.differential(True, 1e4, terminal=True), 0.0)
        return crocoddyl.ShootingProblem(self.x0, running, terminal)


def initial_guess(problem, x0):
    xs = [x0.copy() for _ in range(problem.T + 1)]
    us = list(problem.quasiStatic(xs[:-1]))
    return xs, us


def solve(step, solver_name, repeats):
    """Median wall time of solver.solve() over `repeats` fresh solves; the last solver and its
    problem (the caller keeps the problem alive: mim_solvers' solver does not own it, and its
    xs / us read garbage once the problem is freed)."""
    times, solver, problem = [], None, None
    for _ in range(repeats):
        problem = step.shooting_problem()
        if solver_name == "fddp":
            solver = crocoddyl.SolverFDDP(problem)
            maxiter = 300
        else:
            solver = mim_solvers.SolverCSQP(problem)
            solver.termination_tolerance = 1e-4
            solver.max_qp_iters = 1000
            solver.with_callbacks = False
            maxiter = 100
        xs, us = initial_guess(problem, step.x0)
        t0 = time.perf_counter()
        converged = solver.solve(xs, us, maxiter, False)
        times.append(time.perf_counter() - t0)
        # copies while the solve's inputs are alive (mim_solvers' xs / us may alias them)
        sol_us = [np.array(u, copy=True) for u in solver.us]
        sol_xs = [np.array(x, copy=True) for x in solver.xs]
        sol_K = [np.array(K, copy=True) for K in solver.K]
    return solver, problem, (sol_xs, sol_us, sol_K), bool(converged), float(np.median(times))


def rollout(step, policy, feedback):
    """1 ms rollout of the solver's policy; samples in our coordinates. Between knots j and j+1
    the control is knot j's (zero-order hold), with feedback u = u_j - K_j diff(x_ref, x) on
    the state reference x_ref interpolated between xs[j] and xs[j+1] (feedback=True), or open
    loop (feedback=False)."""
    xs, us, Ks = policy
    state = step.state
    c = step.c
    ss = crocoddyl.IntegratedActionModelEuler(step.differential(False, 0.0, with_costs=False),
                                              ROLLOUT_DT)
    ds = step.differential(True, 0.0, with_costs=False)
    ss_data, ds_data = ss.createData(), ds.createData()
    per_knot = int(round(step.knot_dt / ROLLOUT_DT))
    n = step.n_ss * per_knot  # samples 0 .. n-1 single support, sample n at t_f double support
    out = {k: [] for k in ("time", "q", "qd", "qdd", "u", "lambda")}
    x = step.x0.copy()
    stance_cols = slice(0, 6) if step.stance_name == "left" else slice(6, 12)

    def wrench(data, name, fid):
        # contact force in the LOCAL sole frame -> world, at the sole centre
        f = data.multibody.contacts.contacts[name].f
        R = data.multibody.pinocchio.oMf[fid].rotation
        return np.concatenate([R @ f.linear, R @ f.angular])

    for k in range(n + 1):
        if k < n:
            j = k // per_knot
            u = us[j].copy()
            if feedback:
                alpha = (k % per_knot) / per_knot
                x_ref = state.integrate(xs[j], alpha * state.diff(xs[j], xs[j + 1]))
                u -= Ks[j] @ state.diff(x_ref, x)
            ss.calc(ss_data, x, u)
            d = ss_data.differential
            a = d.xout.copy()
            lam = np.zeros(12)
            lam[stance_cols] = wrench(d, step.stance_name, step.stance_id)
            x_next = ss_data.xnext.copy()
        else:
            u = us[step.n_ss].copy()
            if feedback:
                u -= Ks[step.n_ss] @ state.diff(xs[step.n_ss], x)
            ds.calc(ds_data, x, u)
            a = ds_data.xout.copy()
            lam = np.zeros(12)
            for name, fid in ((step.stance_name, step.stance_id),
                              (step.swing_name, step.swing_id)):
                cols = slice(0, 6) if name == "left" else slice(6, 12)
                lam[cols] = wrench(ds_data, name, fid)
        q, qd, qdd = c.to_ours(x, a)
        out["time"].append(k * ROLLOUT_DT)
        out["q"].append(q.tolist())
        out["qd"].append(qd.tolist())
        out["qdd"].append(qdd.tolist())
        out["u"].append(u.tolist())
        out["lambda"].append(lam.tolist())
        if k < n:
            x = x_next
    out["relaxed"] = False
    return out


def model_info_joint_names(config):
    bin_dir = os.environ.get("BIN", str(REPO / ".build_ws/devel/lib/reach_trajopt"))
    res = subprocess.run([f"{bin_dir}/model_info", "--config", config, "--json"],
                         capture_output=True, text=True, cwd=REPO, check=False)
    if res.returncode != 0:
        fail(f"model_info --config {config}: {res.stdout}{res.stderr}")
    return json.loads(res.stdout)["joint_names"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--request", required=True)
    ap.add_argument("--config", default="config/talos.yaml")
    ap.add_argument("--out-dir", required=True)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--knot-dt", type=float, default=0.01)
    ap.add_argument("--solvers", default="fddp,csqp")
    ap.add_argument("--feedback", action="store_true",
                    help="roll out with the solver's feedback gains (default: open loop)")
    args = ap.parse_args()
    cfg = load_config(args.config)
    req = json.loads(Path(args.request).read_text())
    for key in ("stance", "stance_pose", "swing_target", "horizon", "q0", "qf"):
        if key not in req:
            fail(f"{args.request}: missing key {key}")
    coords = Coordinates(cfg, model_info_joint_names(args.config))
    out_dir = Path(args.out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    names = {"fddp": "crocoddyl_fddp", "csqp": "mim_solvers_csqp"}
    for s in args.solvers.split(","):
        if s not in names:
            fail(f"--solvers: unknown solver '{s}' (fddp, csqp)")
        step = StepProblem(cfg, req, coords, args.knot_dt, hard=(s == "csqp"))
        solver, problem, policy, converged, ref_s = solve(step, s, max(1, args.repeats))
        traj = rollout(step, policy, feedback=args.feedback)
        traj["solver"] = names[s]
        del problem
        (out_dir / f"{names[s]}.json").write_text(json.dumps(traj))
        print(f"REF solver={names[s]} ref_s={ref_s:.4f} iters={solver.iter} "
              f"converged={int(converged)} cost={solver.cost:.6g} knot_dt={args.knot_dt:g}",
              flush=True)


if __name__ == "__main__":
    main()
