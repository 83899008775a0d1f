/// \file kinematic_derivatives.cpp
/// Directional derivatives of a frame's Jacobian, velocity and drift (see the header for the
/// equations). Spatial vectors are [angular; linear] at the world origin.

#include "reach_trajopt/model/kinematic_derivatives.h"

#include <Eigen/Geometry>
#include <cmath>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/model/model_tree.h"
#include "reach_trajopt/model/spatial_algebra.h"

namespace reach_trajopt {

KinematicDerivatives::KinematicDerivatives(std::shared_ptr<const RobotModel> model)
    : model_(std::move(model)) {
  if (!model_) throw ModelError("KinematicDerivatives: null model");
}

KinematicDerivatives::Data::Data(const RobotModel& model) {
  const std::size_t n = model.tree().bodies.size();
  S.resize(n);
  V.resize(n);
  A.resize(n);
  R_world.resize(n);
  p_world.resize(n);
}

void KinematicDerivatives::compute(Data& d, const Eigen::Ref<const Eigen::VectorXd>& q,
                                   const Eigen::Ref<const Eigen::VectorXd>& qd) const {
  const RobotModel& m = *model_;
  m.checkState(q, qd);
  const auto& bodies = m.tree().bodies;
  const int n = static_cast<int>(bodies.size());
  if (static_cast<int>(d.S.size()) != n) {
    throw ModelError("KinematicDerivatives: Data of another model");
  }
  for (int i = 0; i < n; ++i) {
    const Body& b = bodies[i];
    const int pa = b.parent;
    bodyWorldMotion(b, i, q[i], d.R_world, d.p_world, d.S[i]);
    const Vector6d& S = d.S[i];
    const Vector6d Sqd = S * qd[i];
    if (pa < 0) {
      d.V[i] = Sqd;
      d.A[i].setZero();  // V_i x S_i qd_i = 0 for the first body
    } else {
      d.V[i] = d.V[pa] + Sqd;
      d.A[i] = d.A[pa] + crossMotion(d.V[i], Sqd);
    }
  }
  d.computed = true;
}

void KinematicDerivatives::frameDerivatives(const Data& d, FrameId frame,
                                            const Eigen::Ref<const Eigen::VectorXd>& dq,
                                            const Eigen::Ref<const Eigen::VectorXd>& dqd,
                                            Matrix6Xd* dJ, Vector6d* dvelocity,
                                            Vector6d* ddrift) const {
  const RobotModel& m = *model_;
  if (!d.computed) throw ReachError("KinematicDerivatives: call compute(d, q, qd) first");
  requireSize("KinematicDerivatives: dq", dq.size(), m.nq());
  requireSize("KinematicDerivatives: dqd", dqd.size(), m.nq());
  const ModelTree& tree = m.tree();
  if (frame < 0 || frame >= static_cast<int>(tree.frames.size())) {
    throw ModelError("KinematicDerivatives: invalid frame id " + std::to_string(frame));
  }
  if (dJ) {
    requireSize("KinematicDerivatives: columns of dJ", dJ->cols(), m.nq());
    dJ->setZero();
  }
  if (dvelocity) dvelocity->setZero();
  if (ddrift) ddrift->setZero();
  const Frame& f = tree.frames[frame];
  if (f.body < 0) return;  // attached to the world
  const int b = f.body;
  const Eigen::Vector3d p = d.p_world[b] + d.R_world[b] * f.placement.translation();
  const std::vector<int>& support = tree.bodies[b].support;  // leaf to root
  const Vector6d& Vb = d.V[b];
  const Vector6d& Ab = d.A[b];
  const bool motion = dvelocity != nullptr || ddrift != nullptr;

  // Root to leaf: W = sum of dq_m S_m over the bodies before j, so dS_j = W x S_j; dV, dA of the
  // body (spatial, world origin) summed over the path.
  Vector6d W = Vector6d::Zero(), dV = Vector6d::Zero(), dA = Vector6d::Zero();
  for (auto it = support.rbegin(); it != support.rend(); ++it) {
    const int j = *it;
    const Vector6d& S = d.S[j];
    if (dJ) dJ->col(j) = crossMotion(W, S);  // spatial [dw; dv] for now
    const double a = dq[j], c = dqd[j];
    if (motion && (a != 0.0 || c != 0.0)) {
      const Vector6d& Vj = d.V[j];
      const Vector6d Vrel = Vb - Vj;
      const Vector6d SxVrel = crossMotion(S, Vrel);
      if (a != 0.0) {
        dV += a * SxVrel;
        dA += a * (crossMotion(S, Ab - d.A[j] - crossMotion(Vj, Vrel)) + crossMotion(Vj, SxVrel));
      }
      if (c != 0.0) {
        dV += c * S;
        dA += c * (SxVrel - crossMotion(S, Vj));  // S x (V_b - 2 V_j)
      }
    }
    W += a * S;
  }
  // The frame's point moves by dp = J_lin dq = v_W + w_W x p.
  const Eigen::Vector3d dp = W.tail<3>() + W.head<3>().cross(p);
  if (dJ) {
    for (int j : support) {
      const Vector6d dS = dJ->col(j);
      const Eigen::Vector3d w = d.S[j].head<3>();
      dJ->col(j).head<3>() = dS.tail<3>() + dS.head<3>().cross(p) + w.cross(dp);
      dJ->col(j).tail<3>() = dS.head<3>();
    }
  }
  if (!motion) return;
  const Eigen::Vector3d w = Vb.head<3>();
  const Eigen::Vector3d v_p = Vb.tail<3>() + w.cross(p);
  const Eigen::Vector3d dw = dV.head<3>();
  const Eigen::Vector3d dv_p = dV.tail<3>() + dw.cross(p) + w.cross(dp);
  if (dvelocity) {
    dvelocity->head<3>() = dv_p;
    dvelocity->tail<3>() = dw;
  }
  if (ddrift) {
    const Eigen::Vector3d alpha = Ab.head<3>();
    ddrift->head<3>() =
        dA.tail<3>() + dA.head<3>().cross(p) + alpha.cross(dp) + dw.cross(v_p) + w.cross(dv_p);
    ddrift->tail<3>() = dA.head<3>();
  }
}

KinematicDerivatives::FrameMatrices::FrameMatrices(int nq)
    : dJx_dq(6, nq),
      dvelocity_dq(6, nq),
      ddrift_dq(6, nq),
      ddrift_dqd(6, nq),
      dJTlambda_dq(nq, nq) {}

void KinematicDerivatives::frameMatrices(const Data& d, FrameId frame,
                                         const Eigen::Ref<const Eigen::VectorXd>& x,
                                         const Vector6d* lambda, FrameMatrices& out) const {
  const RobotModel& m = *model_;
  const int nq = m.nq();
  if (!d.computed) throw ReachError("KinematicDerivatives: call compute(d, q, qd) first");
  requireSize("KinematicDerivatives: x", x.size(), nq);
  requireSize("KinematicDerivatives: columns of FrameMatrices", out.dJx_dq.cols(), nq);
  const ModelTree& tree = m.tree();
  if (frame < 0 || frame >= static_cast<int>(tree.frames.size())) {
    throw ModelError("KinematicDerivatives: invalid frame id " + std::to_string(frame));
  }
  out.dJx_dq.setZero();
  out.dvelocity_dq.setZero();
  out.ddrift_dq.setZero();
  out.ddrift_dqd.setZero();
  if (lambda) {
    requireSize("KinematicDerivatives: rows of dJTlambda_dq", out.dJTlambda_dq.rows(), nq);
    requireSize("KinematicDerivatives: columns of dJTlambda_dq", out.dJTlambda_dq.cols(), nq);
    out.dJTlambda_dq.setZero();
  }
  const Frame& f = tree.frames[frame];
  if (f.body < 0) return;
  const int b = f.body;
  const Eigen::Vector3d p = d.p_world[b] + d.R_world[b] * f.placement.translation();
  const std::vector<int>& support = tree.bodies[b].support;  // leaf to root
  const Vector6d& Vb = d.V[b];
  const Vector6d& Ab = d.A[b];
  Vector6d Xb = Vector6d::Zero();  // sum of x_j S_j over the path
  for (int j : support) Xb += x[j] * d.S[j];
  const Eigen::Vector3d w = Vb.head<3>(), alpha = Ab.head<3>(), wx = Xb.head<3>();
  const Eigen::Vector3d v_p = Vb.tail<3>() + w.cross(p);
  Vector6d F = Vector6d::Zero();  // lambda at the world origin, [moment; force]
  if (lambda) {
    F.head<3>() = lambda->tail<3>() + p.cross(lambda->head<3>());
    F.tail<3>() = lambda->head<3>();
  }
  Vector6d Xm = Vector6d::Zero();  // sum of x_j S_j up to m (m included)
  for (auto it = support.rbegin(); it != support.rend(); ++it) {
    const int k = *it;
    const Vector6d& S = d.S[k];
    const Vector6d& Vk = d.V[k];
    Xm += x[k] * S;
    const Eigen::Vector3d dp = S.tail<3>() + S.head<3>().cross(p);  // J_lin of joint k at p
    // d(J x)/dq_k: dS_j = S_k x S_j for the joints j after k.
    const Vector6d U = crossMotion(S, Xb - Xm);
    out.dJx_dq.col(k).head<3>() = U.tail<3>() + U.head<3>().cross(p) + wx.cross(dp);
    out.dJx_dq.col(k).tail<3>() = U.head<3>();
    // d(J qd)/dq_k.
    const Vector6d Vrel = Vb - Vk;
    const Vector6d dV = crossMotion(S, Vrel);
    const Eigen::Vector3d dw = dV.head<3>();
    const Eigen::Vector3d dv_p = dV.tail<3>() + dw.cross(p) + w.cross(dp);
    out.dvelocity_dq.col(k).head<3>() = dv_p;
    out.dvelocity_dq.col(k).tail<3>() = dw;
    // d(Jdot qd)/dq_k.
    const Vector6d dA = crossMotion(S, Ab - d.A[k] - crossMotion(Vk, Vrel)) + crossMotion(Vk, dV);
    out.ddrift_dq.col(k).head<3>() =
        dA.tail<3>() + dA.head<3>().cross(p) + alpha.cross(dp) + dw.cross(v_p) + w.cross(dv_p);
    out.ddrift_dq.col(k).tail<3>() = dA.head<3>();
    // d(Jdot qd)/dqd_k: dV = S_k, dA = S_k x (V_b - 2 V_k), the point does not move.
    const Vector6d dAd = dV - crossMotion(S, Vk);
    out.ddrift_dqd.col(k).head<3>() =
        dAd.tail<3>() + dAd.head<3>().cross(p) + S.head<3>().cross(v_p) + w.cross(dp);
    out.ddrift_dqd.col(k).tail<3>() = dAd.head<3>();
    if (lambda) {
      // Column k of d(J^T lambda)/dq: (S_k x S_j) . F = -S_j . (S_k x* F) for j after k, and
      // w_j . (dp x f) for every j.
      const Vector6d Y = -crossForce(S, F);
      const Eigen::Vector3d z = dp.cross(lambda->head<3>());
      bool after = false;
      for (auto jt = support.rbegin(); jt != support.rend(); ++jt) {
        const int j = *jt;
        double h = d.S[j].head<3>().dot(z);
        if (after) h += d.S[j].dot(Y);
        out.dJTlambda_dq(j, k) = h;
        if (j == k) after = true;
      }
    }
  }
}

Eigen::Matrix3d inverseLeftJacobianDerivative(const Eigen::Vector3d& e, const Eigen::Vector3d& de) {
  const double theta = e.norm();
  const Eigen::Matrix3d E = skew(e), dE = skew(de);
  // c as ContactConstraint::inverseLeftJacobian computes it.
  double c;
  if (theta < 1e-4) {
    c = 1.0 / 12.0 + theta * theta / 720.0;
  } else {
    c = 1.0 / (theta * theta) - (1.0 + std::cos(theta)) / (2.0 * theta * std::sin(theta));
  }
  // c'(theta) / theta: c = 1/theta^2 - cot(theta/2) / (2 theta), so
  // c' = -2/theta^3 + 1 / (4 theta sin^2(theta/2)) + cot(theta/2) / (2 theta^2); its series
  // (from c = 1/12 + theta^2/720 + theta^4/30240 + theta^6/1209600 + theta^8/47900160 + ...)
  // below 0.1, where the closed form loses digits to cancellation.
  double cp_over_theta;
  const double t2 = theta * theta;
  if (theta < 0.1) {
    cp_over_theta = 1.0 / 360.0 + t2 * (1.0 / 7560.0 + t2 * (1.0 / 201600.0 + t2 / 5987520.0));
  } else {
    const double sh = std::sin(0.5 * theta);
    const double cot_h = std::cos(0.5 * theta) / sh;
    const double cp = -2.0 / (t2 * theta) + 1.0 / (4.0 * theta * sh * sh) + cot_h / (2.0 * t2);
    cp_over_theta = cp / theta;
  }
  return -0.5 * dE + (cp_over_theta * e.dot(de)) * (E * E) + c * (dE * E + E * dE);
}

}  // namespace reach_trajopt
