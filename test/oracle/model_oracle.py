"""Pinocchio as the oracle of our robot model, shared by the model oracle tests.

  Reference(urdf, floating)   Pinocchio model of a URDF, its coordinates mapped onto ours
  ModelCheck(...)             runs `model_info --state` on seeded random states and compares
                              every quantity with Pinocchio; failures() lists what disagrees
  random_urdf(rng, name)      a random URDF tree (see its doc string)

Coordinates: our floating base is q = [x, y, z, yaw, pitch, roll, joints...], R = Rz Ry Rx, qd the
time derivatives, i.e. Pinocchio's composite root joint PX PY PZ RZ RY RX. Joints are matched by
name (model_info prints its joint_names in q order).

Continuous joints: we use one angle per joint; Pinocchio's RevoluteUnbounded joint has
q = (cos t, sin t) and one velocity. The oracle converts (Reference.configuration).

Mimic joints: like KDL (and Pinocchio's buildModelFromUrdf with mimic=False, its default), a
<mimic> tag is ignored and the joint is an independent degree of freedom.
"""

import math
import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin

from conftest import run_tool, write_json

TOL = 1e-8  # relative to max(1, |reference|), Frobenius / Euclidean norms
VIRTUAL = ["base_x", "base_y", "base_z", "base_yaw", "base_pitch", "base_roll"]
LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED


def floating_root_joint():
    """Pinocchio joint equal to our floating base: x, y, z then yaw, pitch, roll (Rz Ry Rx)."""
    root = pin.JointModelComposite()
    for joint in (pin.JointModelPX(), pin.JointModelPY(), pin.JointModelPZ(),
                  pin.JointModelRZ(), pin.JointModelRY(), pin.JointModelRX()):
        root.addJoint(joint)
    return root


def urdf_root_link(urdf_text):
    """Name of the root link of a URDF (the link that is no joint's child)."""
    root = ET.fromstring(urdf_text)
    children = {j.find("child").get("link") for j in root.iter("joint")
                if j.find("child") is not None}
    roots = [link.get("name") for link in root.findall("link") if link.get("name") not in children]
    return roots[0] if roots else None


def reduced_model(model, locked):
    """`model` with the joints of `locked` (name -> position [rad or m]) held there and removed
    (pin.buildReducedModel); a continuous joint's position is its angle."""
    q_ref = pin.neutral(model)
    ids = []
    for name, position in locked.items():
        jid = model.getJointId(name)
        assert jid < model.njoints, f"Pinocchio has no joint '{name}'"
        jm = model.joints[jid]
        if jm.nq == 2:
            q_ref[jm.idx_q:jm.idx_q + 2] = [math.cos(position), math.sin(position)]
        else:
            q_ref[jm.idx_q] = position
        ids.append(jid)
    return pin.buildReducedModel(model, sorted(ids), q_ref)


class Reference:
    """Pinocchio model of a URDF plus the map between its coordinates and ours."""

    def __init__(self, urdf_path, floating, locked=None):
        if floating:
            self.model = pin.buildModelFromUrdf(str(urdf_path), floating_root_joint())
        else:
            self.model = pin.buildModelFromUrdf(str(urdf_path))
        if locked:  # joint name -> position: Pinocchio's buildReducedModel
            self.model = reduced_model(self.model, locked)
        self.data = self.model.createData()
        self.floating = floating
        m = self.model
        self.v_names = []  # name of every velocity coordinate, in Pinocchio's v order
        for j in range(1, m.njoints):
            if floating and j == 1:
                self.v_names += VIRTUAL
                continue
            assert m.joints[j].nv == 1, f"joint {m.names[j]}: nv {m.joints[j].nv}"
            self.v_names.append(m.names[j])

    def body_frame_id(self, link):
        """Pinocchio's BODY frame of a URDF link."""
        fid = self.model.getFrameId(link, pin.FrameType.BODY)
        assert fid < self.model.nframes, f"Pinocchio has no body frame '{link}'"
        return fid

    def sample(self, rng):
        """A random state in Pinocchio's v coordinates: positions within the joint limits (an
        unlimited joint in [-pi, pi]), a random base pose, moderate velocities."""
        m = self.model
        qv = np.zeros(m.nv)
        v = np.zeros(m.nv)
        for j in range(1, m.njoints):
            jm = m.joints[j]
            if self.floating and j == 1:
                qv[0:6] = np.concatenate([rng.uniform(-1.0, 1.0, 2), rng.uniform(0.3, 1.5, 1),
                                          rng.uniform(-math.pi, math.pi, 1),
                                          rng.uniform(-1.3, 1.3, 1),
                                          rng.uniform(-math.pi, math.pi, 1)])
                v[0:6] = np.concatenate([rng.uniform(-1.0, 1.0, 3), rng.uniform(-2.0, 2.0, 3)])
                continue
            if jm.nq == 1:
                lo, hi = m.lowerPositionLimit[jm.idx_q], m.upperPositionLimit[jm.idx_q]
            else:  # continuous joint (cos, sin)
                lo, hi = -math.pi, math.pi
            if not (math.isfinite(lo) and math.isfinite(hi) and hi - lo < 1e6):
                lo, hi = -math.pi, math.pi
            qv[jm.idx_v] = rng.uniform(lo, hi)
            v[jm.idx_v] = rng.uniform(-3.0, 3.0)
        return qv, v

    def configuration(self, qv):
        """Pinocchio's q from positions in v coordinates (a continuous joint: cos, sin)."""
        m = self.model
        q = np.zeros(m.nq)
        for j in range(1, m.njoints):
            jm = m.joints[j]
            if jm.nq == jm.nv:
                q[jm.idx_q:jm.idx_q + jm.nq] = qv[jm.idx_v:jm.idx_v + jm.nv]
            else:
                assert jm.nq == 2 and jm.nv == 1, f"joint {m.names[j]} not supported"
                angle = qv[jm.idx_v]
                q[jm.idx_q:jm.idx_q + 2] = [math.cos(angle), math.sin(angle)]
        return q

    def evaluate(self, qv, v, frames):
        """Every compared quantity at (qv, v), in Pinocchio's v order."""
        m, d = self.model, self.data
        q = self.configuration(qv)
        out = {}
        M = pin.crba(m, d, q).copy()
        out["M"] = np.triu(M) + np.triu(M, 1).T
        out["b"] = pin.nonLinearEffects(m, d, q, v).copy()
        out["com"] = pin.centerOfMass(m, d, q).copy()
        out["com_jacobian"] = pin.jacobianCenterOfMass(m, d, q).copy().reshape(3, m.nv)
        pin.computeJointJacobians(m, d, q)
        pin.forwardKinematics(m, d, q, v, np.zeros(m.nv))
        pin.updateFramePlacements(m, d)
        out["frames"] = {}
        for name in frames:
            fid = self.body_frame_id(name)
            linear = pin.getFrameClassicalAcceleration(m, d, fid, LWA).linear
            angular = pin.getFrameAcceleration(m, d, fid, LWA).angular
            out["frames"][name] = {
                "position": d.oMf[fid].translation.copy(),
                "rotation": d.oMf[fid].rotation.copy(),
                "jacobian": pin.getFrameJacobian(m, d, fid, LWA).copy().reshape(6, m.nv),
                "jdot_qd": np.concatenate([linear, angular]),
            }
        return out


def rel_err(a, b):
    return float(np.linalg.norm(a - b)) / max(1.0, float(np.linalg.norm(b)))


class ModelCheck:
    """model_info against Pinocchio on one URDF at `n_states` seeded random states, for M, b, the
    CoM, its Jacobian and the pose, Jacobian and Jdot*qd of every frame in `frames` (default: every
    link of the URDF). `failures` lists each disagreeing quantity with its worst relative error."""

    def __init__(self, urdf_path, tmp_dir, key, floating, n_states=10, seed=20200701,
                 frames=None, config=None, locked=None):
        """`config`, `locked`: a config file whose robot.locked_joints model_info applies
        (--config) and the same joints for Pinocchio's reduced model."""
        self.key = key
        self.ref = Reference(urdf_path, floating, locked)
        m = self.ref.model
        if frames is None:
            frames = [f.name for f in m.frames if f.type == pin.FrameType.BODY
                      and f.name != "universe"]
        self.frames = list(frames)
        rng = np.random.default_rng(seed)
        samples = [self.ref.sample(rng) for _ in range(n_states)]
        base = [urdf_path] + ([] if floating else ["--fixed-base"])
        if config is not None:
            base += ["--config", config]

        summary = run_tool("model_info", *base, "--json").json()
        self.summary = summary
        self.names = list(summary["joint_names"])
        self.failures = []
        missing = sorted(set(self.ref.v_names) - set(self.names))
        extra = sorted(set(self.names) - set(self.ref.v_names))
        if missing or extra or len(self.names) != m.nv:
            self.failures.append(f"{key}: joints differ from Pinocchio's: missing {missing}, "
                                 f"unexpected {extra}")
            return
        perm = np.array([self.ref.v_names.index(n) for n in self.names])
        states = [{"q": qv[perm].tolist(), "qd": v[perm].tolist()} for qv, v in samples]
        state_file = write_json(tmp_dir / f"{key}_states.json", {"states": states})
        out = run_tool("model_info", *base, "--state", state_file,
                       "--frames", ",".join(self.frames)).json()
        self.mass = out["mass"]
        mass = pin.computeTotalMass(m)
        if abs(self.mass - mass) > 1e-9 * max(1.0, mass):
            self.failures.append(f"{key}: total mass {self.mass} vs Pinocchio {mass}")
        self.worst = {}
        for k, ((qv, v), ours) in enumerate(zip(samples, out["results"])):
            r = self.ref.evaluate(qv, v, self.frames)
            self._compare("M", ours["M"], r["M"][np.ix_(perm, perm)], k)
            self._compare("b", ours["b"], r["b"][perm], k)
            self._compare("com", ours["com"], r["com"], k)
            self._compare("com_jacobian", ours["com_jacobian"], r["com_jacobian"][:, perm], k)
            for f in self.frames:
                o, rf = ours["frames"][f], r["frames"][f]
                self._compare(f"{f}.position", o["position"], rf["position"], k)
                self._compare(f"{f}.rotation", o["rotation"], rf["rotation"], k)
                self._compare(f"{f}.jacobian", o["jacobian"], rf["jacobian"][:, perm], k)
                self._compare(f"{f}.jdot_qd", o["jdot_qd"], rf["jdot_qd"], k)
        for label, (err, k) in sorted(self.worst.items(), key=lambda kv: -kv[1][0]):
            if not err <= TOL:
                self.failures.append(f"{key}: {label} relative error {err:.3e} (state {k})")

    def _compare(self, label, ours, ref, k):
        ours = np.array(ours, dtype=float)
        err = rel_err(ours, ref) if ours.shape == ref.shape else math.inf
        if not math.isfinite(err):
            err = math.inf
        if err > self.worst.get(label, (-1.0, 0))[0]:
            self.worst[label] = (err, k)


# ---- random URDF trees ---------------------------------------------------------------------------

def _vec(v):
    return " ".join(f"{x:.17g}" for x in v)


def _random_rotation(rng):
    q = rng.normal(size=4)
    q /= np.linalg.norm(q)
    return pin.Quaternion(q[0], q[1], q[2], q[3]).toRotationMatrix()


def _random_inertial(rng, parent):
    """An <inertial> with a random mass, a random com offset, a random rotated frame and a
    physically valid rotational inertia (a box's principal moments, rotated)."""
    m = rng.uniform(0.2, 5.0)
    a, b, c = rng.uniform(0.05, 0.5, 3)
    principal = m / 12.0 * np.array([b * b + c * c, a * a + c * c, a * a + b * b])
    R = _random_rotation(rng)
    inertia = R @ np.diag(principal) @ R.T  # full tensor in the inertial frame
    inertial = ET.SubElement(parent, "inertial")
    ET.SubElement(inertial, "origin", xyz=_vec(rng.uniform(-0.2, 0.2, 3)),
                  rpy=_vec(rng.uniform(-math.pi, math.pi, 3)))
    ET.SubElement(inertial, "mass", value=f"{m:.17g}")
    ET.SubElement(inertial, "inertia", ixx=f"{inertia[0, 0]:.17g}", ixy=f"{inertia[0, 1]:.17g}",
                  ixz=f"{inertia[0, 2]:.17g}", iyy=f"{inertia[1, 1]:.17g}",
                  iyz=f"{inertia[1, 2]:.17g}", izz=f"{inertia[2, 2]:.17g}")


def random_urdf(rng, name, max_links=9):
    """A random URDF tree: a root link (massive, or massless with its mass on rotated fixed
    children), then links attached to random earlier links (chains and branches) by revolute,
    continuous, prismatic and fixed joints with random origins and rotations, chains of rotated
    fixed joints, rotated inertial frames, massless links, random axes of random length (urdfdom
    and Pinocchio normalize them), joints with and without limits. Returns the XML text."""
    robot = ET.Element("robot", name=name)
    links = ["root"]
    root = ET.SubElement(robot, "link", name="root")
    massless_root = rng.random() < 0.3
    if not massless_root:
        _random_inertial(rng, root)
    n = int(rng.integers(2, max_links + 1))
    kinds = ["revolute", "continuous", "prismatic", "fixed"]
    for i in range(1, n + 1):
        if massless_root and i == 1:
            parent, kind = "root", "fixed"  # the root's mass on a rotated fixed child
        elif rng.random() < 0.25:
            parent, kind = links[-1], "fixed"  # chains of fixed joints
        else:
            parent = links[int(rng.integers(0, len(links)))] if rng.random() < 0.5 else links[-1]
            kind = kinds[int(rng.choice(4, p=[0.45, 0.15, 0.2, 0.2]))]
        link = f"link{i}"
        el = ET.SubElement(robot, "link", name=link)
        if (massless_root and i == 1) or rng.random() < 0.8:
            _random_inertial(rng, el)
        joint = ET.SubElement(robot, "joint", name=f"joint{i}", type=kind)
        ET.SubElement(joint, "parent", link=parent)
        ET.SubElement(joint, "child", link=link)
        origin = {"xyz": _vec(rng.uniform(-0.4, 0.4, 3))}
        if rng.random() < 0.85:
            origin["rpy"] = _vec(rng.uniform(-math.pi, math.pi, 3))
        ET.SubElement(joint, "origin", **origin)
        if kind != "fixed":
            axis = rng.normal(size=3)
            if rng.random() < 0.3:
                axis = np.eye(3)[int(rng.integers(0, 3))] * (1 if rng.random() < 0.5 else -1)
            axis *= rng.uniform(0.3, 3.0) if rng.random() < 0.4 else 1.0 / np.linalg.norm(axis)
            ET.SubElement(joint, "axis", xyz=_vec(axis))
        if kind in ("revolute", "prismatic"):
            lo = rng.uniform(-2.0, 0.0)
            ET.SubElement(joint, "limit", lower=f"{lo:.17g}",
                          upper=f"{lo + rng.uniform(0.1, 2.5):.17g}",
                          effort=f"{rng.uniform(1, 100):.17g}",
                          velocity=f"{rng.uniform(1, 10):.17g}")
        elif kind == "continuous" and rng.random() < 0.5:
            ET.SubElement(joint, "limit", effort="10", velocity="5")
        links.append(link)
    return ET.tostring(robot, encoding="unicode")
