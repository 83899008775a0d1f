/// \file rnea_derivatives.cpp
/// The derivatives of the recursive Newton-Euler algorithm in the world frame (see the header for
/// the equations). Spatial vectors are [angular; linear] at the world origin.

#include "reach_trajopt/model/rnea_derivatives.h"

#include <Eigen/Geometry>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/model/model_tree.h"
#include "reach_trajopt/model/spatial_algebra.h"

namespace reach_trajopt {

namespace {

using Matrix6d = RneaDerivatives::Matrix6d;

}  // namespace

RneaDerivatives::RneaDerivatives(std::shared_ptr<const RobotModel> model)
    : model_(std::move(model)) {
  if (!model_) throw ModelError("RneaDerivatives: null model");
}

RneaDerivatives::Data::Data(const RobotModel& model) {
  const std::size_t n = model.tree().bodies.size();
  S.resize(n);
  v.resize(n);
  a.resize(n);
  F.resize(n);
  u.resize(n);
  c.resize(n);
  Isub.resize(n);
  Bsub.resize(n);
  R_world.resize(n);
  p_world.resize(n);
}

namespace {

/// Forward pass of body i: its world pose, S_i, v_i, a_i and the derivative terms u_i, c_i
/// (a0: the base's acceleration, minus gravity).
void forwardKinematics(const Body& b, int i, double q, double qd, double qdd, const Vector6d& a0,
                       RneaDerivatives::Data& d) {
  const int pa = b.parent;
  bodyWorldMotion(b, i, q, d.R_world, d.p_world, d.S[i]);
  const Vector6d& S = d.S[i];
  const Vector6d v_parent = pa < 0 ? Vector6d::Zero() : Vector6d(d.v[pa]);
  const Vector6d a_parent = pa < 0 ? a0 : Vector6d(d.a[pa]);
  d.v[i] = v_parent + S * qd;
  d.a[i] = a_parent + S * qdd + crossMotion(d.v[i], S * qd);
  d.u[i] = crossMotion(S, v_parent);
  d.c[i] = -crossMotion(S, a_parent) + crossMotion(d.u[i], v_parent);
}

/// Body i's own spatial inertia I_i, its derivative term B_i and its force f_i (into Isub,
/// Bsub and F, summed over the subtree by the backward pass).
void bodyDynamics(const Body& b, int i, RneaDerivatives::Data& d) {
  // Spatial inertia at the world origin: [[Ic - m [c][c], m [c]], [-m [c], m 1]].
  const double mass = b.mass;
  const Eigen::Matrix3d I_com_body =
      b.inertia_origin -
      mass * (b.com.squaredNorm() * Eigen::Matrix3d::Identity() - b.com * b.com.transpose());
  const Eigen::Vector3d c_w = d.p_world[i] + d.R_world[i] * b.com;
  const Eigen::Matrix3d C = skew(c_w);
  Matrix6d& I = d.Isub[i];
  I.topLeftCorner<3, 3>() = d.R_world[i] * I_com_body * d.R_world[i].transpose() - mass * C * C;
  I.topRightCorner<3, 3>() = mass * C;
  I.bottomLeftCorner<3, 3>() = -mass * C;
  I.bottomRightCorner<3, 3>() = mass * Eigen::Matrix3d::Identity();
  const Vector6d h = I * d.v[i];
  d.F[i] = I * d.a[i] + crossForce(d.v[i], h);
  // B = (v x*) I + (h xbar*) - I (v x).
  const Eigen::Matrix3d W = skew(d.v[i].head<3>()), V = skew(d.v[i].tail<3>());
  Matrix6d vxs;  // v x*
  vxs << W, V, Eigen::Matrix3d::Zero(), W;
  Matrix6d vx;  // v x
  vx << W, Eigen::Matrix3d::Zero(), V, W;
  Matrix6d hbar;  // m x* h = hbar m
  const Eigen::Matrix3d N = skew(h.head<3>()), Fh = skew(h.tail<3>());
  hbar << -N, -Fh, -Fh, Eigen::Matrix3d::Zero();
  Matrix6d& B = d.Bsub[i];
  B.noalias() = vxs * I;
  B += hbar;
  B.noalias() -= I * vx;
}

/// dtau/dq and dtau/dqd from the passes' terms (Carpentier and Mansard, RSS 2018): row j,
/// column k for k on j's support path, then for j a strict ancestor of k.
void assembleDerivatives(const std::vector<Body>& bodies, const RneaDerivatives::Data& d,
                         Eigen::Ref<Eigen::MatrixXd> dtau_dq,
                         Eigen::Ref<Eigen::MatrixXd> dtau_dqd) {
  const int n = static_cast<int>(bodies.size());
  dtau_dq.setZero();
  dtau_dqd.setZero();
  for (int j = 0; j < n; ++j) {
    const Eigen::Matrix<double, 1, 6> r1 = d.S[j].transpose() * d.Isub[j];
    const Eigen::Matrix<double, 1, 6> r2 = d.S[j].transpose() * d.Bsub[j];
    // k <= j: k on the support path of j (j included).
    for (int k : bodies[j].support) {
      dtau_dq(j, k) = r1.dot(d.c[k]) - r2.dot(d.u[k]);
      dtau_dqd(j, k) = r2.dot(d.S[k]) - 2.0 * r1.dot(d.u[k]);
    }
  }
  for (int k = 0; k < n; ++k) {
    // j < k: the strict ancestors of k see the whole subtree of k move.
    const Vector6d Y = crossForce(d.S[k], d.F[k]) + d.Isub[k] * d.c[k] - d.Bsub[k] * d.u[k];
    const Vector6d Z = d.Bsub[k] * d.S[k] - 2.0 * (d.Isub[k] * d.u[k]);
    for (int j : bodies[k].support) {
      if (j == k) continue;
      dtau_dq(j, k) = d.S[j].dot(Y);
      dtau_dqd(j, k) = d.S[j].dot(Z);
    }
  }
}

}  // namespace

void RneaDerivatives::compute(Data& d, const Eigen::Ref<const Eigen::VectorXd>& q,
                              const Eigen::Ref<const Eigen::VectorXd>& qd,
                              const Eigen::Ref<const Eigen::VectorXd>& qdd,
                              Eigen::Ref<Eigen::VectorXd> tau, Eigen::Ref<Eigen::MatrixXd> dtau_dq,
                              Eigen::Ref<Eigen::MatrixXd> dtau_dqd) const {
  const RobotModel& m = *model_;
  const int n = m.nq();
  m.checkState(q, qd);
  requireSize("RneaDerivatives: qdd", qdd.size(), n);
  requireFinite("RneaDerivatives: qdd", qdd);
  requireSize("RneaDerivatives: tau", tau.size(), n);
  requireSize("RneaDerivatives: rows of dtau_dq", dtau_dq.rows(), n);
  requireSize("RneaDerivatives: columns of dtau_dq", dtau_dq.cols(), n);
  requireSize("RneaDerivatives: rows of dtau_dqd", dtau_dqd.rows(), n);
  requireSize("RneaDerivatives: columns of dtau_dqd", dtau_dqd.cols(), n);
  const auto& bodies = m.tree().bodies;
  if (static_cast<int>(d.S.size()) != n) throw ModelError("RneaDerivatives: Data of another model");

  Vector6d a0 = Vector6d::Zero();
  a0.tail<3>() = -m.gravity();
  // Forward pass: poses, S, v, a, u, c, and each body's own I, B, f (into Isub, Bsub, F).
  for (int i = 0; i < n; ++i) {
    forwardKinematics(bodies[i], i, q[i], qd[i], qdd[i], a0, d);
    bodyDynamics(bodies[i], i, d);
  }
  // Backward pass: subtree sums and tau.
  for (int i = n - 1; i >= 0; --i) {
    tau[i] = d.S[i].dot(d.F[i]);
    const int pa = bodies[i].parent;
    if (pa >= 0) {
      d.Isub[pa] += d.Isub[i];
      d.Bsub[pa] += d.Bsub[i];
      d.F[pa] += d.F[i];
    }
  }
  assembleDerivatives(bodies, d, dtau_dq, dtau_dqd);
}

}  // namespace reach_trajopt
