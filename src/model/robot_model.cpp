/// \file robot_model.cpp
/// Kinematics and rigid-body dynamics on the flattened KDL tree: forward kinematics with body
/// velocities and velocity-product accelerations, the composite rigid body algorithm for M(q),
/// recursive Newton-Euler for b(q, qd), frame Jacobians and the CoM (Featherstone, Rigid Body
/// Dynamics Algorithms, 2008, ch. 5-6). Spatial vectors are kept as pairs of 3-vectors in body
/// coordinates, [angular; linear] internally; the public API returns [linear; angular].

#include "reach_trajopt/model/robot_model.h"

#include <cmath>
#include <limits>

#include "reach_trajopt/model/model_tree.h"

namespace reach_trajopt {

/// Per-body scratch of one thread. Body-frame quantities unless the name says world.
struct Workspace::Buffers {
  explicit Buffers(int n)
      : R(n),
        p(n),
        R_world(n),
        p_world(n),
        w(n),
        v(n),
        dw(n),
        dv(n),
        fn(n),
        ff(n),
        Ic_m(n),
        Ic_h(n),
        Ic_I(n),
        sub_m(n),
        sub_mc(n),
        q(n),
        qd(n) {}
  template <typename T>
  using Vec = std::vector<T, Eigen::aligned_allocator<T>>;
  Vec<Eigen::Matrix3d> R;        ///< body rotation in its parent
  Vec<Eigen::Vector3d> p;        ///< body origin in its parent
  Vec<Eigen::Matrix3d> R_world;  ///< body rotation in the world
  Vec<Eigen::Vector3d> p_world;  ///< body origin in the world
  Vec<Eigen::Vector3d> w, v;     ///< body angular velocity and origin velocity
  Vec<Eigen::Vector3d> dw, dv;   ///< spatial acceleration with qdd = 0, no gravity
  Vec<Eigen::Vector3d> fn, ff;   ///< spatial force: moment about the origin, force
  std::vector<double> Ic_m;      ///< composite inertia: mass
  Vec<Eigen::Vector3d> Ic_h;     ///< composite inertia: first moment m c
  Vec<Eigen::Matrix3d> Ic_I;     ///< composite inertia: rotational inertia about the origin
  std::vector<double> sub_m;     ///< subtree mass (CoM Jacobian)
  Vec<Eigen::Vector3d> sub_mc;   ///< subtree first moment in the world
  Eigen::VectorXd q, qd;
  bool updated = false;
};

Workspace::Workspace(const RobotModel& model)
    : buffers_(std::make_unique<Buffers>(static_cast<int>(model.tree().bodies.size()))) {
  buffers_->q.setZero(model.nq());
  buffers_->qd.setZero(model.nq());
}
Workspace::~Workspace() = default;
Workspace::Workspace(Workspace&&) noexcept = default;
Workspace& Workspace::operator=(Workspace&&) noexcept = default;

RobotModel::RobotModel() = default;
RobotModel::~RobotModel() = default;

namespace {

inline Eigen::Matrix3d axisRotation(const Eigen::Vector3d& a, double angle) {
  return Eigen::AngleAxisd(angle, a).toRotationMatrix();
}

const Frame& frameAt(const ModelTree& tree, FrameId frame, const std::string& source) {
  if (frame < 0 || frame >= static_cast<int>(tree.frames.size()))
    throw ModelError("invalid frame id " + std::to_string(frame) + " for " + source);
  return tree.frames[frame];
}

const Workspace::Buffers& requireUpdated(const Workspace& ws) {
  if (!ws.buffers().updated) throw ReachError("RobotModel: call update(ws, q, qd) first");
  return ws.buffers();
}

}  // namespace

int RobotModel::jointIndex(const std::string& name) const {
  for (size_t i = 0; i < joints_.size(); ++i)
    if (joints_[i].name == name) return static_cast<int>(i);
  throw ModelError("unknown joint '" + name + "' in " + source_);
}

Eigen::VectorXd RobotModel::positionLowerLimits() const {
  Eigen::VectorXd v(nq());
  for (int i = 0; i < nq(); ++i) v[i] = joints_[i].q_min;
  return v;
}
Eigen::VectorXd RobotModel::positionUpperLimits() const {
  Eigen::VectorXd v(nq());
  for (int i = 0; i < nq(); ++i) v[i] = joints_[i].q_max;
  return v;
}
Eigen::VectorXd RobotModel::velocityLimits() const {
  Eigen::VectorXd v(nq());
  for (int i = 0; i < nq(); ++i) v[i] = joints_[i].qd_max;
  return v;
}
Eigen::VectorXd RobotModel::effortLimits() const {
  const int off = nq() - nu();
  Eigen::VectorXd v(nu());
  for (int i = 0; i < nu(); ++i) v[i] = joints_[off + i].effort_max;
  return v;
}
Eigen::MatrixXd RobotModel::selectionMatrix() const {
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(nu(), nq());
  S.rightCols(nu()).setIdentity();
  return S;
}

FrameId RobotModel::frameId(const std::string& name) const {
  for (size_t i = 0; i < frame_names_.size(); ++i)
    if (frame_names_[i] == name) return static_cast<FrameId>(i);
  throw ModelError("unknown frame '" + name + "' in " + source_);
}
bool RobotModel::hasFrame(const std::string& name) const {
  for (const auto& f : frame_names_)
    if (f == name) return true;
  return false;
}
const std::string& RobotModel::parentLink(const std::string& link) const {
  for (size_t i = 0; i < link_names_.size(); ++i)
    if (link_names_[i] == link) return link_parents_[i];
  throw ModelError("unknown link '" + link + "' in " + source_);
}

Eigen::VectorXd RobotModel::neutralConfiguration() const {
  Eigen::VectorXd q(nq());
  for (int i = 0; i < nq(); ++i) {
    const JointInfo& j = joints_[i];
    if (std::isfinite(j.q_min) && std::isfinite(j.q_max))
      q[i] = 0.5 * (j.q_min + j.q_max);
    else if (std::isfinite(j.q_min))
      q[i] = std::max(0.0, j.q_min);
    else if (std::isfinite(j.q_max))
      q[i] = std::min(0.0, j.q_max);
    else
      q[i] = 0.0;
    if (j.q_min <= 0.0 && 0.0 <= j.q_max) q[i] = 0.0;
  }
  return q;
}

void RobotModel::checkState(const Eigen::Ref<const Eigen::VectorXd>& q,
                            const Eigen::Ref<const Eigen::VectorXd>& qd) const {
  requireSize("RobotModel: q", q.size(), nq());
  requireSize("RobotModel: qd", qd.size(), nq());
  requireFinite("RobotModel: q", q);
  requireFinite("RobotModel: qd", qd);
}

void RobotModel::update(Workspace& ws, const Eigen::Ref<const Eigen::VectorXd>& q,
                        const Eigen::Ref<const Eigen::VectorXd>& qd) const {
  checkState(q, qd);
  Workspace::Buffers& d = ws.buffers();
  d.q = q;
  const auto& bodies = tree_->bodies;
  for (size_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    // Pose in the parent: placement * joint motion.
    if (b.prismatic) {
      d.R[i] = b.placement.linear();
      d.p[i] = b.placement.translation() + b.placement.linear() * (b.axis * q[i]);
    } else {
      d.R[i] = b.placement.linear() * axisRotation(b.axis, q[i]);
      d.p[i] = b.placement.translation();
    }
    if (b.parent < 0) {
      d.R_world[i] = d.R[i];
      d.p_world[i] = d.p[i];
    } else {
      d.R_world[i] = d.R_world[b.parent] * d.R[i];
      d.p_world[i] = d.p_world[b.parent] + d.R_world[b.parent] * d.p[i];
    }
  }
  velocityPass(ws, qd);
}

void RobotModel::updateVelocity(Workspace& ws, const Eigen::Ref<const Eigen::VectorXd>& qd) const {
  Workspace::Buffers& d = ws.buffers();
  if (!d.updated) throw ReachError("RobotModel::updateVelocity: call update() first");
  requireSize("RobotModel: qd", qd.size(), nq());
  requireFinite("RobotModel: qd", qd);
  velocityPass(ws, qd);
}

void RobotModel::velocityPass(Workspace& ws, const Eigen::Ref<const Eigen::VectorXd>& qd) const {
  Workspace::Buffers& d = ws.buffers();
  d.qd = qd;
  const auto& bodies = tree_->bodies;
  for (size_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    const Eigen::Vector3d s_w = b.prismatic ? Eigen::Vector3d::Zero() : Eigen::Vector3d(b.axis);
    const Eigen::Vector3d s_v = b.prismatic ? Eigen::Vector3d(b.axis) : Eigen::Vector3d::Zero();
    if (b.parent < 0) {
      d.w[i] = s_w * qd[i];
      d.v[i] = s_v * qd[i];
      d.dw[i].setZero();
      d.dv[i].setZero();
    } else {
      const int pa = b.parent;
      const Eigen::Matrix3d& R = d.R[i];
      // v_i = X v_parent + S qd_i.
      const Eigen::Vector3d w_in = R.transpose() * d.w[pa];
      const Eigen::Vector3d v_in = R.transpose() * (d.v[pa] + d.w[pa].cross(d.p[i]));
      d.w[i] = w_in + s_w * qd[i];
      d.v[i] = v_in + s_v * qd[i];
      // a_i = X a_parent + v_i x (S qd_i)  (qdd = 0).
      d.dw[i] = R.transpose() * d.dw[pa];
      d.dv[i] = R.transpose() * (d.dv[pa] + d.dw[pa].cross(d.p[i]));
    }
    const Eigen::Vector3d sw = s_w * qd[i];
    const Eigen::Vector3d sv = s_v * qd[i];
    d.dw[i] += d.w[i].cross(sw);
    d.dv[i] += d.w[i].cross(sv) + d.v[i].cross(sw);
  }
  d.updated = true;
}

Eigen::Isometry3d RobotModel::framePose(const Workspace& ws, FrameId frame) const {
  const Workspace::Buffers& d = requireUpdated(ws);
  const Frame& f = frameAt(*tree_, frame, source_);
  if (f.body < 0) return f.placement;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = d.R_world[f.body];
  T.translation() = d.p_world[f.body];
  return T * f.placement;
}

void RobotModel::frameJacobian(const Workspace& ws, FrameId frame, Eigen::Ref<Matrix6Xd> J) const {
  const Workspace::Buffers& d = requireUpdated(ws);
  requireSize("frameJacobian: columns of J", J.cols(), nq());
  J.setZero();
  const Frame& f = frameAt(*tree_, frame, source_);
  if (f.body < 0) return;
  const Eigen::Vector3d p_f = d.p_world[f.body] + d.R_world[f.body] * f.placement.translation();
  for (int j : tree_->bodies[f.body].support) {
    const Body& b = tree_->bodies[j];
    const Eigen::Vector3d a = d.R_world[j] * b.axis;
    if (b.prismatic) {
      J.col(j).head<3>() = a;
    } else {
      J.col(j).head<3>() = a.cross(p_f - d.p_world[j]);
      J.col(j).tail<3>() = a;
    }
  }
}

Vector6d RobotModel::frameVelocity(const Workspace& ws, FrameId frame) const {
  const Workspace::Buffers& d = requireUpdated(ws);
  const Frame& f = frameAt(*tree_, frame, source_);
  Vector6d out = Vector6d::Zero();
  if (f.body < 0) return out;
  const Eigen::Vector3d& r = f.placement.translation();
  const Eigen::Matrix3d& Rw = d.R_world[f.body];
  out.head<3>() = Rw * (d.v[f.body] + d.w[f.body].cross(r));
  out.tail<3>() = Rw * d.w[f.body];
  return out;
}

Vector6d RobotModel::frameJdotQd(const Workspace& ws, FrameId frame) const {
  const Workspace::Buffers& d = requireUpdated(ws);
  const Frame& f = frameAt(*tree_, frame, source_);
  Vector6d out = Vector6d::Zero();
  if (f.body < 0) return out;
  const int k = f.body;
  const Eigen::Vector3d& r = f.placement.translation();
  const Eigen::Vector3d v_r = d.v[k] + d.w[k].cross(r);
  // Classical acceleration of the point = spatial acceleration at the point + w x v.
  const Eigen::Vector3d a_r = d.dv[k] + d.dw[k].cross(r) + d.w[k].cross(v_r);
  out.head<3>() = d.R_world[k] * a_r;
  out.tail<3>() = d.R_world[k] * d.dw[k];
  return out;
}

void RobotModel::massMatrix(Workspace& ws, Eigen::Ref<Eigen::MatrixXd> M) const {
  requireUpdated(ws);
  Workspace::Buffers& d = ws.buffers();
  requireSize("massMatrix: rows of M", M.rows(), nq());
  requireSize("massMatrix: columns of M", M.cols(), nq());
  const auto& bodies = tree_->bodies;
  const int n = static_cast<int>(bodies.size());
  M.setZero();  // entries of bodies on different branches stay zero
  for (int i = 0; i < n; ++i) {
    d.Ic_m[i] = bodies[i].mass;
    d.Ic_h[i] = bodies[i].mass * bodies[i].com;
    d.Ic_I[i] = bodies[i].inertia_origin;
  }
  for (int i = n - 1; i >= 0; --i) {
    const Body& b = bodies[i];
    // F = Ic_i S_i as a spatial force (moment about the origin fn, force ff).
    Eigen::Vector3d fn, ff;
    if (b.prismatic) {
      fn = d.Ic_h[i].cross(b.axis);
      ff = d.Ic_m[i] * b.axis;
    } else {
      fn = d.Ic_I[i] * b.axis;
      ff = b.axis.cross(d.Ic_h[i]);
    }
    const Eigen::Vector3d& s = b.axis;
    M(i, i) = b.prismatic ? s.dot(ff) : s.dot(fn);
    // Walk up the support path, transforming F into each ancestor's frame.
    int j = i;
    while (bodies[j].parent >= 0) {
      const Eigen::Matrix3d& R = d.R[j];
      const Eigen::Vector3d& p = d.p[j];
      ff = R * ff;
      fn = R * fn + p.cross(ff);
      j = bodies[j].parent;
      const double Mij = bodies[j].prismatic ? bodies[j].axis.dot(ff) : bodies[j].axis.dot(fn);
      M(i, j) = Mij;
      M(j, i) = Mij;
    }
    // Ic_parent += X^T Ic_i X.
    if (b.parent >= 0) {
      const int pa = b.parent;
      const Eigen::Matrix3d& R = d.R[i];
      const Eigen::Vector3d& p = d.p[i];
      const double m = d.Ic_m[i];
      const Eigen::Vector3d Rh = R * d.Ic_h[i];
      const Eigen::Vector3d h_p = Rh + m * p;  // first moment about the parent origin
      // I about the parent origin = R I R^T + [shift of the reference point by p].
      Eigen::Matrix3d I_p = R * d.Ic_I[i] * R.transpose();
      // I_parent = I_o - m([c'] [c'] - [Rc][Rc]) with c' = Rc + p, written with h = m c:
      // -([h_p][p] + [p][Rh]) which is symmetric.
      const double pp = p.squaredNorm();
      const double ph = p.dot(Rh);
      I_p += (2.0 * ph + m * pp) * Eigen::Matrix3d::Identity() -
             (p * Rh.transpose() + Rh * p.transpose()) - m * p * p.transpose();
      d.Ic_m[pa] += m;
      d.Ic_h[pa] += h_p;
      d.Ic_I[pa] += I_p;
    }
  }
}

void RobotModel::inverseDynamics(Workspace& ws, const Eigen::Ref<const Eigen::VectorXd>& qdd,
                                 Eigen::Ref<Eigen::VectorXd> tau) const {
  requireUpdated(ws);
  requireSize("inverseDynamics: qdd", qdd.size(), nq());
  requireSize("inverseDynamics: tau", tau.size(), nq());
  requireFinite("inverseDynamics: qdd", qdd);
  Workspace::Buffers& d = ws.buffers();
  const auto& bodies = tree_->bodies;
  const int n = static_cast<int>(bodies.size());
  // Forward: a_i = drift + X a_parent(qdd part) + S qdd_i + gravity, all in fn/ff as scratch
  // (fn = angular acceleration, ff = linear acceleration) before they become forces.
  for (int i = 0; i < n; ++i) {
    const Body& b = bodies[i];
    Eigen::Vector3d aw, av;
    if (b.parent < 0) {
      aw.setZero();
      av = -(d.R_world[i].transpose() * gravity_);  // uniform field: only the rotation matters
    } else {
      const int pa = b.parent;
      aw = d.R[i].transpose() * d.fn[pa];
      av = d.R[i].transpose() * (d.ff[pa] + d.fn[pa].cross(d.p[i]));
    }
    if (b.prismatic)
      av += b.axis * qdd[i];
    else
      aw += b.axis * qdd[i];
    d.fn[i] = aw;
    d.ff[i] = av;
  }
  rneaForcesAndBackwardPass(ws, tau);
}

void RobotModel::bias(Workspace& ws, Eigen::Ref<Eigen::VectorXd> b) const {
  requireSize("bias: b", b.size(), nq());
  requireUpdated(ws);
  // RNEA with qdd = 0: the velocity-product accelerations from update() plus gravity, taken as
  // a uniform base acceleration -g expressed in each body's frame.
  Workspace::Buffers& d = ws.buffers();
  const int n = static_cast<int>(tree_->bodies.size());
  for (int i = 0; i < n; ++i) {
    d.fn[i].setZero();
    d.ff[i] = -(d.R_world[i].transpose() * gravity_);
  }
  rneaForcesAndBackwardPass(ws, b);
}

void RobotModel::rneaForcesAndBackwardPass(Workspace& ws, Eigen::Ref<Eigen::VectorXd> tau) const {
  Workspace::Buffers& d = ws.buffers();
  const auto& bodies = tree_->bodies;
  const int n = static_cast<int>(bodies.size());
  // Add the velocity-product accelerations (already propagated in dw, dv) and form forces.
  for (int i = 0; i < n; ++i) {
    const Body& b = bodies[i];
    const Eigen::Vector3d aw = d.fn[i] + d.dw[i];
    const Eigen::Vector3d av = d.ff[i] + d.dv[i];
    const double m = b.mass;
    const Eigen::Vector3d h = m * b.com;
    const Eigen::Vector3d& w = d.w[i];
    const Eigen::Vector3d& v = d.v[i];
    // f = I a + v x* (I v), I = (m, h, I_o) at the body origin.
    const Eigen::Vector3d Iv_n = b.inertia_origin * w + h.cross(v);
    const Eigen::Vector3d Iv_f = m * v - h.cross(w);
    d.fn[i] = b.inertia_origin * aw + h.cross(av) + w.cross(Iv_n) + v.cross(Iv_f);
    d.ff[i] = m * av - h.cross(aw) + w.cross(Iv_f);
  }
  // Backward: each body's force onto its joint, then into its parent.
  for (int i = n - 1; i >= 0; --i) {
    const Body& b = bodies[i];
    tau[i] = b.prismatic ? b.axis.dot(d.ff[i]) : b.axis.dot(d.fn[i]);
    if (b.parent >= 0) {
      const Eigen::Vector3d f = d.R[i] * d.ff[i];
      d.fn[b.parent] += d.R[i] * d.fn[i] + d.p[i].cross(f);
      d.ff[b.parent] += f;
    }
  }
}

Eigen::Vector3d RobotModel::centerOfMass(const Workspace& ws) const {
  const Workspace::Buffers& d = requireUpdated(ws);
  Eigen::Vector3d mc = Eigen::Vector3d::Zero();
  double m = 0.0;
  const auto& bodies = tree_->bodies;
  for (size_t i = 0; i < bodies.size(); ++i) {
    mc += bodies[i].mass * (d.p_world[i] + d.R_world[i] * bodies[i].com);
    m += bodies[i].mass;
  }
  if (m <= 0.0) throw ModelError("centerOfMass: the robot in " + source_ + " has no mass");
  return mc / m;
}

Eigen::Vector3d RobotModel::centerOfMassJdotQd(const Workspace& ws) const {
  const Workspace::Buffers& d = requireUpdated(ws);
  if (total_mass_ <= 0.0)
    throw ModelError("centerOfMassJdotQd: the robot in " + source_ + " has no mass");
  Eigen::Vector3d ma = Eigen::Vector3d::Zero();
  const auto& bodies = tree_->bodies;
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].mass <= 0.0) continue;
    const Eigen::Vector3d& r = bodies[i].com;
    const Eigen::Vector3d v_r = d.v[i] + d.w[i].cross(r);
    ma += bodies[i].mass * (d.R_world[i] * (d.dv[i] + d.dw[i].cross(r) + d.w[i].cross(v_r)));
  }
  return ma / total_mass_;
}

void RobotModel::centerOfMassJacobian(Workspace& ws, Eigen::Ref<Eigen::Matrix3Xd> Jc) const {
  requireUpdated(ws);
  requireSize("centerOfMassJacobian: columns", Jc.cols(), nq());
  Workspace::Buffers& d = ws.buffers();
  const auto& bodies = tree_->bodies;
  const int n = static_cast<int>(bodies.size());
  if (total_mass_ <= 0.0)
    throw ModelError("centerOfMassJacobian: the robot in " + source_ + " has no mass");
  for (int i = 0; i < n; ++i) {
    d.sub_m[i] = bodies[i].mass;
    d.sub_mc[i] = bodies[i].mass * (d.p_world[i] + d.R_world[i] * bodies[i].com);
  }
  for (int i = n - 1; i >= 0; --i) {
    const Body& b = bodies[i];
    const Eigen::Vector3d a = d.R_world[i] * b.axis;
    if (b.prismatic)
      Jc.col(i) = d.sub_m[i] * a;
    else
      Jc.col(i) = a.cross(d.sub_mc[i] - d.sub_m[i] * d.p_world[i]);
    if (b.parent >= 0) {
      d.sub_m[b.parent] += d.sub_m[i];
      d.sub_mc[b.parent] += d.sub_mc[i];
    }
  }
  Jc /= total_mass_;
}

}  // namespace reach_trajopt
