#include "reach_trajopt/ocp/stance_reduced_dynamics.h"

#include <Eigen/LU>
#include <cmath>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/model/model_tree.h"

namespace reach_trajopt {

namespace {

/// Copies the terms that depend on the configuration alone (q, G, J_sb^-1, J_2, the swing
/// sole's position) from `from` (the scratch or a saved kinematic) into `k`.
template <class From>
void copyConfigurationTerms(const From& from, StanceReducedDynamics::Scratch::Kinematic& k) {
  k.q = from.q;
  k.G = from.G;
  k.Jb_inv = from.Jb_inv;
  k.J2 = from.J2;
  k.swing_position = from.swing_position;
}

}  // namespace

StanceReducedDynamics::StanceReducedDynamics(std::shared_ptr<const RobotModel> model,
                                             FrameId stance_frame,
                                             const Eigen::Isometry3d& stance_pose,
                                             FrameId swing_frame,
                                             const Eigen::Isometry3d& swing_target,
                                             double yaw_reference)
    : model_(std::move(model)),
      nq_(model_ ? model_->nq() : 0),
      nu_(model_ ? model_->nu() : 0),
      stance_frame_(stance_frame),
      swing_frame_(swing_frame),
      stance_pose_(stance_pose),
      swing_(swing_frame, swing_target),
      yaw_reference_(yaw_reference),
      rnea_(model_),
      kin_(model_) {
  if (!model_ || !model_->floatingBase()) {
    throw ModelError("StanceReducedDynamics: needs a floating-base model");
  }
  const ModelTree& tree = model_->tree();
  if (stance_frame < 0 || stance_frame >= static_cast<int>(tree.frames.size()))
    throw ModelError("StanceReducedDynamics: invalid stance frame id");
  on_stance_path_.assign(nu_, false);
  const int stance_body = tree.frames[stance_frame].body;
  if (stance_body >= 0) {
    for (int b : tree.bodies[stance_body].support)
      if (b >= 6) on_stance_path_[b - 6] = true;
  }
  // Validates the stance pose the same way as the swing target.
  const ContactConstraint check(stance_frame, stance_pose);
  (void)check;
  if (!std::isfinite(yaw_reference)) {
    throw RequestError("StanceReducedDynamics: non-finite yaw reference");
  }
}

StanceReducedDynamics::Scratch::Scratch(const StanceReducedDynamics& d)
    : ws(d.model()),
      qz(Eigen::VectorXd::Zero(d.nq())),
      vz(Eigen::VectorXd::Zero(d.nq())),
      q(d.nq()),
      qd(d.nq()),
      qdd(d.nq()),
      tau(d.nq()),
      tau_ext(d.nq()),
      qd_nominal(d.nq()),
      signals_pert(d.signalCount()),
      input_pert(d.inputCount()),
      Js(6, d.nq()),
      J2(6, d.nq()),
      swing(d.nq()),
      G(6, d.nu()),
      MT(d.nq(), d.nu()),
      M(d.nq(), d.nq()),
      rd(d.model()),
      tau_rd(d.nq()),
      r0(d.nq()),
      dtau_dq(d.nq(), d.nq()),
      dtau_dqd(d.nq(), d.nq()),
      k0(d.nq(), d.nu()),
      kp(d.nq(), d.nu()),
      km(d.nq(), d.nu()),
      dq(d.nq()),
      dqd(d.nq()),
      dqdd(d.nq()),
      dtau(d.nq()),
      dr(d.nq()),
      kd(d.model()),
      fs(d.nq()),
      f2(d.nq()),
      Qd(6, d.nu()),
      Qdd(6, d.nu()),
      D6(6, d.nu()),
      dvel2(6, d.nu()),
      dacc2(6, d.nu()),
      dr_cols(d.nq(), d.nu()) {}

StanceReducedDynamics::Scratch::Kinematic::Kinematic(int nq, int nu)
    : q(nq), qd(nq), qdd(nq), G(6, nu), J2(6, nq) {}

void StanceReducedDynamics::kinematics(Scratch& s, const Eigen::Ref<const Eigen::VectorXd>& qa,
                                       const Eigen::Ref<const Eigen::VectorXd>& qda) const {
  const RobotModel& m = *model_;
  // Stance sole relative to the base (base at the world origin) and its relative velocity.
  s.qz.tail(nu_) = qa;
  s.vz.tail(nu_) = qda;
  m.update(s.ws, s.qz, s.vz);
  const Eigen::Isometry3d T_bs = m.framePose(s.ws, stance_frame_);
  const Vector6d v_rel = m.frameVelocity(s.ws, stance_frame_);

  const Eigen::Isometry3d T_wb = stance_pose_ * T_bs.inverse();
  const Eigen::Matrix3d R = T_wb.linear();
  const Eigen::Vector3d p_b = T_wb.translation();
  // R = Rz(yaw) Ry(pitch) Rx(roll).
  double yaw = std::atan2(R(1, 0), R(0, 0));
  const double pitch = std::atan2(-R(2, 0), std::hypot(R(2, 1), R(2, 2)));
  const double roll = std::atan2(R(2, 1), R(2, 2));
  constexpr double kTwoPi = 2.0 * M_PI;
  yaw += kTwoPi * std::round((yaw_reference_ - yaw) / kTwoPi);
  s.q.head<3>() = p_b;
  s.q[3] = yaw;
  s.q[4] = pitch;
  s.q[5] = roll;
  s.q.tail(nu_) = qa;

  // The stance sole does not move: omega_b = -R omega_rel, v_b = -R v_rel - omega_b x (p_s - p_b).
  const Eigen::Vector3d w_b = -R * v_rel.tail<3>();
  const Eigen::Vector3d v_b = -R * v_rel.head<3>() - w_b.cross(stance_pose_.translation() - p_b);
  // omega = E [yawd; pitchd; rolld], E = [e_z, Rz e_y, Rz Ry e_x].
  const double cy = std::cos(yaw), sy = std::sin(yaw), cp = std::cos(pitch), sp = std::sin(pitch);
  Eigen::Matrix3d E;
  E << 0.0, -sy, cy * cp, 0.0, cy, sy * cp, 1.0, 0.0, -sp;
  s.qd.head<3>() = v_b;
  s.qd.segment<3>(3) = E.partialPivLu().solve(w_b);
  s.qd.tail(nu_) = qda;

  velocityTerms(s);
  m.frameJacobian(s.ws, stance_frame_, s.Js);
  m.frameJacobian(s.ws, swing_frame_, s.J2);
  s.swing_position = m.framePose(s.ws, swing_frame_).translation();
  s.Jb_inv = s.Js.leftCols<6>().partialPivLu().inverse();
  s.G.noalias() = -s.Jb_inv * s.Js.rightCols(nu_);
}

void StanceReducedDynamics::velocityTerms(Scratch& s) const {
  model_->update(s.ws, s.q, s.qd);
  s.drift_s = model_->frameJdotQd(s.ws, stance_frame_);
  swing_.evaluate(*model_, s.ws, s.swing);
}

void StanceReducedDynamics::dynamics(Scratch& s, const Eigen::Ref<const Eigen::VectorXd>& qdda,
                                     const Eigen::Ref<const Vector6d>& lambda2,
                                     Eigen::Ref<Eigen::VectorXd> out) const {
  // qdd = T qdd_a + k.
  s.qdd.tail(nu_) = qdda;
  s.qdd.head<6>().noalias() = s.G * qdda;
  s.qdd.head<6>().noalias() -= s.Jb_inv * s.drift_s;
  model_->inverseDynamics(s.ws, s.qdd, s.tau);  // M qdd + b
  // tau - J_2^T lambda_2 is what the stance wrench and the torques balance.
  Eigen::VectorXd& r = s.tau_ext;
  r = s.tau;
  r.noalias() -= s.J2.transpose() * lambda2;
  s.lambda_s.noalias() = s.Jb_inv.transpose() * r.head<6>();
  out.segment(uOffset(), nu_) = r.tail(nu_);
  out.segment(uOffset(), nu_).noalias() += s.G.transpose() * r.head<6>();
  out.segment<6>(lambdaOffset()) = s.lambda_s;
  out.segment<3>(swingPositionOffset()) = s.swing_position;
  out.segment<6>(phi2Offset()) = s.swing.phi;
  out.segment<6>(phidot2Offset()) = s.swing.phidot;
  out.segment<6>(phiddot2Offset()) = s.swing.drift;
  out.segment<6>(phiddot2Offset()).noalias() += s.swing.J_phi * s.qdd;
  out.segment(qOffset(), nq_) = s.q;
  out.segment(qdOffset(), nq_) = s.qd;
}

void StanceReducedDynamics::configuration(Scratch& s, const Eigen::Ref<const Eigen::VectorXd>& qa,
                                          Eigen::Ref<Eigen::VectorXd> q) const {
  requireSize("StanceReducedDynamics: q_a", qa.size(), nu_);
  requireSize("StanceReducedDynamics: q", q.size(), nq_);
  s.vz.setZero();
  kinematics(s, qa, s.vz.tail(nu_));
  q = s.q;
}

void StanceReducedDynamics::evaluate(Scratch& s, const Eigen::Ref<const Eigen::VectorXd>& input,
                                     Eigen::Ref<Eigen::VectorXd> signals) const {
  requireSize("StanceReducedDynamics: input", input.size(), inputCount());
  requireSize("StanceReducedDynamics: signals", signals.size(), signalCount());
  kinematics(s, input.head(nu_), input.segment(nu_, nu_));
  dynamics(s, input.segment(2 * nu_, nu_), input.tail<6>(), signals);
}

void StanceReducedDynamics::evaluate(Scratch& s, const Eigen::Ref<const Eigen::VectorXd>& input,
                                     Eigen::Ref<Eigen::VectorXd> signals,
                                     Eigen::Ref<Eigen::MatrixXd> jac, double fd_step,
                                     bool central) const {
  jacobianCommon(s, input, signals, jac);
  const Eigen::Ref<const Eigen::VectorXd> qdda = input.segment(2 * nu_, nu_);
  saveKinematic(s, qdda, s.k0);  // the unperturbed kinematic state
  s.r0 = s.tau_ext;              // tau - J_2^T lambda_2
  velocityColumns(s, qdda, input.tail<6>(), jac);
  positionColumns(s, input, fd_step, central, jac);
}

void StanceReducedDynamics::evaluate(Scratch& s, const Eigen::Ref<const Eigen::VectorXd>& input,
                                     Eigen::Ref<Eigen::VectorXd> signals,
                                     Eigen::Ref<Eigen::MatrixXd> jac) const {
  jacobianCommon(s, input, signals, jac);
  analyticColumns(s, input, jac);
}

void StanceReducedDynamics::jacobianCommon(Scratch& s,
                                           const Eigen::Ref<const Eigen::VectorXd>& input,
                                           Eigen::Ref<Eigen::VectorXd> signals,
                                           Eigen::Ref<Eigen::MatrixXd> jac) const {
  requireSize("StanceReducedDynamics: Jacobian rows", jac.rows(), signalCount());
  requireSize("StanceReducedDynamics: Jacobian columns", jac.cols(), inputCount());
  evaluate(s, input, signals);
  jac.setZero();

  // qdd_a and lambda_2: the signals are affine in both. d(tau)/d(qdd_a) = M T.
  model_->massMatrix(s.ws, s.M);
  s.MT.topRows<6>().noalias() = s.M.topLeftCorner<6, 6>() * s.G;
  s.MT.topRows<6>() += s.M.block(0, 6, 6, nu_);
  s.MT.bottomRows(nu_).noalias() = s.M.block(6, 0, nu_, 6) * s.G;
  s.MT.bottomRows(nu_) += s.M.block(6, 6, nu_, nu_);
  const int c_qdd = 2 * nu_, c_l2 = 3 * nu_;
  auto du_dqdd = jac.block(uOffset(), c_qdd, nu_, nu_);
  du_dqdd = s.MT.bottomRows(nu_);
  du_dqdd.noalias() += s.G.transpose() * s.MT.topRows<6>();
  jac.block(lambdaOffset(), c_qdd, 6, nu_).noalias() = s.Jb_inv.transpose() * s.MT.topRows<6>();
  auto dphiddot = jac.block(phiddot2Offset(), c_qdd, 6, nu_);
  dphiddot = s.swing.J_phi.rightCols(nu_);
  dphiddot.noalias() += s.swing.J_phi.leftCols<6>() * s.G;
  // d(u)/d(lambda_2) = -T^T J_2^T, d(lambda_s)/d(lambda_2) = -J_sb^-T J_2b^T.
  auto du_dl2 = jac.block(uOffset(), c_l2, nu_, 6);
  du_dl2 = -s.J2.rightCols(nu_).transpose();
  du_dl2.noalias() -= s.G.transpose() * s.J2.leftCols<6>().transpose();
  jac.block<6, 6>(lambdaOffset(), c_l2).noalias() =
      -s.Jb_inv.transpose() * s.J2.leftCols<6>().transpose();

  // The unperturbed state and the analytic RNEA derivatives there (model_->update() of the
  // sample is current: evaluate() ended with velocityTerms at (q, qd)).
  rnea_.compute(s.rd, s.q, s.qd, s.qdd, s.tau_rd, s.dtau_dq, s.dtau_dqd);
}

// The q_a and qd_a columns, analytic (see the header's file comment), all columns at once: with
// T = [G; I], A T = A_b G + A_a for any A with n_q columns.
void StanceReducedDynamics::analyticColumns(Scratch& s,
                                            const Eigen::Ref<const Eigen::VectorXd>& input,
                                            Eigen::Ref<Eigen::MatrixXd> jac) const {
  const Vector6d lambda2 = input.tail<6>();
  const bool wrench2 = !lambda2.isZero(0.0);
  const auto timesT = [this, &s](const auto& A, auto&& out) {
    out.noalias() = A.template leftCols<6>() * s.G;
    out += A.rightCols(nu_);
  };
  kin_.compute(s.kd, s.q, s.qd);
  kin_.frameMatrices(s.kd, stance_frame_, s.qdd, &s.lambda_s, s.fs);
  kin_.frameMatrices(s.kd, swing_frame_, s.qdd, wrench2 ? &lambda2 : nullptr, s.f2);
  // The swing sole's raw velocity and classical acceleration (J_2 qdd + Jdot_2 qd), and the
  // rotation rows' Jl^-1(e) of phi_2 with its derivative contracted with them, L_v de =
  // dJl^-1[de] v (s.ws is at (q, qd): evaluate() ended with velocityTerms).
  const Vector6d vel2 = model_->frameVelocity(s.ws, swing_frame_);
  Vector6d acc2 = model_->frameJdotQd(s.ws, swing_frame_);
  acc2.noalias() += s.J2 * s.qdd;
  const Eigen::Vector3d e2 = s.swing.phi.tail<3>();
  const Eigen::Matrix3d Jl_inv = ContactConstraint::inverseLeftJacobian(e2);
  Eigen::Matrix3d L_vel, L_acc;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Matrix3d dJl = inverseLeftJacobianDerivative(e2, Eigen::Vector3d::Unit(k));
    L_vel.col(k) = dJl * vel2.tail<3>();
    L_acc.col(k) = dJl * acc2.tail<3>();
  }
  auto dq_cols = jac.leftCols(nu_);
  auto dqd_cols = jac.middleCols(nu_, nu_);

  // q_a: dq = T; from J_s qd = 0 and J_s qdd + Jdot_s qd = 0 the base velocity and acceleration
  //   Qd = -J_sb^-1 d(J_s qd)/dq T,
  //   Qdd = -J_sb^-1 [(d(J_s qdd)/dq + d(Jdot_s qd)/dq) T + d(Jdot_s qd)/dqd_b Qd].
  timesT(s.fs.dvelocity_dq, s.D6);
  s.Qd.noalias() = -s.Jb_inv * s.D6;
  s.fs.dJx_dq += s.fs.ddrift_dq;
  timesT(s.fs.dJx_dq, s.D6);
  s.D6.noalias() += s.fs.ddrift_dqd.leftCols<6>() * s.Qd;
  s.Qdd.noalias() = -s.Jb_inv * s.D6;
  // dr' = dtau - d(J_2^T lambda_2) - d(J_s^T lambda_s).
  timesT(s.dtau_dq, s.dr_cols);
  s.dr_cols.noalias() += s.dtau_dqd.leftCols<6>() * s.Qd;
  s.dr_cols.noalias() += s.M.leftCols<6>() * s.Qdd;
  s.fs.dJTlambda_dq.leftCols<6>() *= -1.0;
  s.dr_cols.noalias() += s.fs.dJTlambda_dq.leftCols<6>() * s.G;
  s.dr_cols -= s.fs.dJTlambda_dq.rightCols(nu_);
  if (wrench2) {
    s.dr_cols.noalias() -= s.f2.dJTlambda_dq.leftCols<6>() * s.G;
    s.dr_cols -= s.f2.dJTlambda_dq.rightCols(nu_);
  }
  dq_cols.middleRows(uOffset(), nu_) = s.dr_cols.bottomRows(nu_);
  dq_cols.middleRows(uOffset(), nu_).noalias() += s.G.transpose() * s.dr_cols.topRows<6>();
  dq_cols.middleRows<6>(lambdaOffset()).noalias() = s.Jb_inv.transpose() * s.dr_cols.topRows<6>();
  // Swing terms: position and phi_2 along T; phidot_2 = B vel2, phiddot_2 = B acc2 with
  // B = blkdiag(I, Jl^-1(e)), e moving by the rotation rows of dphi_2.
  timesT(s.J2, s.D6);
  dq_cols.middleRows<3>(swingPositionOffset()) = s.D6.topRows<3>();
  auto dphi = dq_cols.middleRows<6>(phi2Offset());
  timesT(s.swing.J_phi, dphi);
  timesT(s.f2.dvelocity_dq, s.dvel2);
  s.dvel2.noalias() += s.J2.leftCols<6>() * s.Qd;
  s.f2.dJx_dq += s.f2.ddrift_dq;
  timesT(s.f2.dJx_dq, s.dacc2);
  s.dacc2.noalias() += s.f2.ddrift_dqd.leftCols<6>() * s.Qd;
  s.dacc2.noalias() += s.J2.leftCols<6>() * s.Qdd;
  dq_cols.middleRows<3>(phidot2Offset()) = s.dvel2.topRows<3>();
  dq_cols.middleRows<3>(phidot2Offset() + 3).noalias() = L_vel * dphi.bottomRows<3>();
  dq_cols.middleRows<3>(phidot2Offset() + 3).noalias() += Jl_inv * s.dvel2.bottomRows<3>();
  dq_cols.middleRows<3>(phiddot2Offset()) = s.dacc2.topRows<3>();
  dq_cols.middleRows<3>(phiddot2Offset() + 3).noalias() = L_acc * dphi.bottomRows<3>();
  dq_cols.middleRows<3>(phiddot2Offset() + 3).noalias() += Jl_inv * s.dacc2.bottomRows<3>();
  dq_cols.middleRows<6>(qOffset()) = s.G;
  dq_cols.middleRows(qOffset() + 6, nu_).setIdentity();
  dq_cols.middleRows<6>(qdOffset()) = s.Qd;

  // qd_a: dqd = T at fixed q, Qdd = -J_sb^-1 d(Jdot_s qd)/dqd T.
  timesT(s.fs.ddrift_dqd, s.D6);
  s.Qdd.noalias() = -s.Jb_inv * s.D6;
  timesT(s.dtau_dqd, s.dr_cols);
  s.dr_cols.noalias() += s.M.leftCols<6>() * s.Qdd;
  dqd_cols.middleRows(uOffset(), nu_) = s.dr_cols.bottomRows(nu_);
  dqd_cols.middleRows(uOffset(), nu_).noalias() += s.G.transpose() * s.dr_cols.topRows<6>();
  dqd_cols.middleRows<6>(lambdaOffset()).noalias() = s.Jb_inv.transpose() * s.dr_cols.topRows<6>();
  // phidot_2 = J_phi qd; phiddot_2 = B Jdot_2 qd + J_phi qdd.
  dqd_cols.middleRows<6>(phidot2Offset()) = dphi;
  timesT(s.f2.ddrift_dqd, s.dacc2);
  auto dphiddot = dqd_cols.middleRows<6>(phiddot2Offset());
  dphiddot.topRows<3>() = s.dacc2.topRows<3>();
  dphiddot.bottomRows<3>().noalias() = Jl_inv * s.dacc2.bottomRows<3>();
  dphiddot.noalias() += s.swing.J_phi.leftCols<6>() * s.Qdd;
  dqd_cols.middleRows<6>(qdOffset()) = s.G;
  dqd_cols.middleRows(qdOffset() + 6, nu_).setIdentity();
}

// One column c of the Jacobian from the changes of the full state (dq, dqd, dqdd) and of the
// kinematic terms (d = (k_plus - k_minus) / span) about s.k0: u and lambda_s by the chain rule,
// the rest directly.
void StanceReducedDynamics::chainRuleColumn(Scratch& s, int c, const Scratch::Kinematic& kp,
                                            const Scratch::Kinematic& km, double span,
                                            bool kinematic_terms_move,
                                            const Eigen::Ref<const Vector6d>& lambda2,
                                            Eigen::Ref<Eigen::MatrixXd> jac) const {
  const Scratch::Kinematic& k0 = s.k0;
  const double inv = 1.0 / span;
  s.dq = (kp.q - km.q) * inv;
  s.dqd = (kp.qd - km.qd) * inv;
  s.dqdd = (kp.qdd - km.qdd) * inv;
  s.dtau.noalias() = s.dtau_dq * s.dq;
  s.dtau.noalias() += s.dtau_dqd * s.dqd;
  s.dtau.noalias() += s.M * s.dqdd;
  s.dr = s.dtau;
  auto out = jac.col(c);
  out.segment(uOffset(), nu_) = s.dr.tail(nu_);
  out.segment(uOffset(), nu_).noalias() += k0.G.transpose() * s.dr.head<6>();
  out.segment<6>(lambdaOffset()).noalias() = k0.Jb_inv.transpose() * s.dr.head<6>();
  if (kinematic_terms_move) {
    // d(J_2^T lambda_2), d(G^T) r_b, d(J_sb^-T) r_b.
    s.dr.noalias() = ((kp.J2 - km.J2) * inv).transpose() * lambda2;
    out.segment(uOffset(), nu_) -= s.dr.tail(nu_);
    out.segment(uOffset(), nu_).noalias() -= k0.G.transpose() * s.dr.head<6>();
    out.segment<6>(lambdaOffset()).noalias() -= k0.Jb_inv.transpose() * s.dr.head<6>();
    out.segment(uOffset(), nu_).noalias() += ((kp.G - km.G) * inv).transpose() * s.r0.head<6>();
    out.segment<6>(lambdaOffset()).noalias() +=
        ((kp.Jb_inv - km.Jb_inv) * inv).transpose() * s.r0.head<6>();
  }
  out.segment<3>(swingPositionOffset()) = (kp.swing_position - km.swing_position) * inv;
  out.segment<6>(phi2Offset()) = (kp.phi2 - km.phi2) * inv;
  out.segment<6>(phidot2Offset()) = (kp.phidot2 - km.phidot2) * inv;
  out.segment<6>(phiddot2Offset()) = (kp.phiddot2 - km.phiddot2) * inv;
  out.segment(qOffset(), nq_) = s.dq;
  out.segment(qdOffset(), nq_) = s.dqd;
}

// The qd_a columns (nu_ .. 2 nu_ - 1) about s.k0.
void StanceReducedDynamics::velocityColumns(Scratch& s,
                                            const Eigen::Ref<const Eigen::VectorXd>& qdda,
                                            const Eigen::Ref<const Vector6d>& lambda2,
                                            Eigen::Ref<Eigen::MatrixXd> jac) const {
  const Scratch::Kinematic& k0 = s.k0;
  // qd_a: quadratic at fixed q, so central differences are exact (the step only sets roundoff).
  // Only the velocity pass runs: q, G, J_sb^-1, J_2 stay those of k0.
  constexpr double kVelocityStep = 1.0;  // [rad/s]
  for (int i = 0; i < nu_; ++i) {
    for (int side = 0; side < 2; ++side) {
      Scratch::Kinematic& k = side == 0 ? s.kp : s.km;
      const double h = side == 0 ? kVelocityStep : -kVelocityStep;
      s.qd = k0.qd;
      s.qd.head<6>() += h * k0.G.col(i);
      s.qd[6 + i] += h;
      model_->updateVelocity(s.ws, s.qd);
      s.drift_s = model_->frameJdotQd(s.ws, stance_frame_);
      swing_.evaluate(*model_, s.ws, s.swing);
      copyConfigurationTerms(k0, k);
      k.qd = s.qd;
      accelerationTerms(k0.G, k0.Jb_inv, s.drift_s, s.swing, qdda, k);
    }
    chainRuleColumn(s, nu_ + i, s.kp, s.km, 2.0 * kVelocityStep, false, lambda2, jac);
  }
}

// The q_a columns (0 .. nu_ - 1) about s.k0, by differences of the kinematic chain.
void StanceReducedDynamics::positionColumns(Scratch& s,
                                            const Eigen::Ref<const Eigen::VectorXd>& input,
                                            double fd_step, bool central,
                                            Eigen::Ref<Eigen::MatrixXd> jac) const {
  const Scratch::Kinematic& k0 = s.k0;
  const Eigen::Ref<const Eigen::VectorXd> qa = input.head(nu_);
  const Eigen::Ref<const Eigen::VectorXd> qda = input.segment(nu_, nu_);
  const Eigen::Ref<const Eigen::VectorXd> qdda = input.segment(2 * nu_, nu_);
  const Eigen::Ref<const Vector6d> lambda2 = input.tail<6>();
  // q_a: differences of the kinematic chain (base reconstruction included).
  s.input_pert.head(nu_) = qa;
  for (int i = 0; i < nu_; ++i) {
    const double h = fd_step * std::max(1.0, std::abs(qa[i]));
    const bool swing_only = !on_stance_path_[i];
    s.input_pert[i] = qa[i] + h;
    perturbedKinematic(s, s.input_pert.head(nu_), qda, qdda, swing_only, s.kp);
    if (central) {
      s.input_pert[i] = qa[i] - h;
      perturbedKinematic(s, s.input_pert.head(nu_), qda, qdda, swing_only, s.km);
    }
    s.input_pert[i] = qa[i];
    if (swing_only) {  // dq = e_i exactly; the base state, G, J_sb^-1 do not move
      s.kp.q = k0.q;
      s.kp.q[6 + i] += 1.0;
      s.km.q = k0.q;
    }
    const double span = swing_only ? 1.0 : (central ? 2.0 * h : h);
    if (swing_only) {
      // The swing terms over their own step, rescaled to the unit span of dq.
      const Scratch::Kinematic& kb = central ? s.km : k0;
      const double scale = 1.0 / (central ? 2.0 * h : h);
      s.kp.swing_position = (s.kp.swing_position - kb.swing_position) * scale;
      s.kp.phi2 = (s.kp.phi2 - kb.phi2) * scale;
      s.kp.phidot2 = (s.kp.phidot2 - kb.phidot2) * scale;
      s.kp.phiddot2 = (s.kp.phiddot2 - kb.phiddot2) * scale;
      s.kp.J2 = (s.kp.J2 - kb.J2) * scale;
      s.km.swing_position.setZero();
      s.km.phi2.setZero();
      s.km.phidot2.setZero();
      s.km.phiddot2.setZero();
      s.km.J2.setZero();
      s.kp.qd = k0.qd;
      s.km.qd = k0.qd;
      s.kp.qdd = k0.qdd;
      s.km.qdd = k0.qdd;
      s.kp.G = k0.G;
      s.km.G = k0.G;
      s.kp.Jb_inv = k0.Jb_inv;
      s.km.Jb_inv = k0.Jb_inv;
      chainRuleColumn(s, i, s.kp, s.km, span, true, lambda2, jac);
    } else {
      chainRuleColumn(s, i, s.kp, central ? s.km : k0, span, true, lambda2, jac);
    }
  }
}

void StanceReducedDynamics::saveKinematic(const Scratch& s,
                                          const Eigen::Ref<const Eigen::VectorXd>& qdda,
                                          Scratch::Kinematic& k) const {
  copyConfigurationTerms(s, k);
  k.qd = s.qd;
  accelerationTerms(s.G, s.Jb_inv, s.drift_s, s.swing, qdda, k);
}

void StanceReducedDynamics::accelerationTerms(const Eigen::MatrixXd& G,
                                              const Eigen::Matrix<double, 6, 6>& Jb_inv,
                                              const Vector6d& drift_s,
                                              const ContactConstraintTerms& swing,
                                              const Eigen::Ref<const Eigen::VectorXd>& qdda,
                                              Scratch::Kinematic& k) const {
  k.qdd.tail(nu_) = qdda;
  k.qdd.head<6>().noalias() = G * qdda;
  k.qdd.head<6>().noalias() -= Jb_inv * drift_s;
  k.phi2 = swing.phi;
  k.phidot2 = swing.phidot;
  k.phiddot2 = swing.drift;
  k.phiddot2.noalias() += swing.J_phi * k.qdd;
}

void StanceReducedDynamics::perturbedKinematic(Scratch& s,
                                               const Eigen::Ref<const Eigen::VectorXd>& qa,
                                               const Eigen::Ref<const Eigen::VectorXd>& qda,
                                               const Eigen::Ref<const Eigen::VectorXd>& qdda,
                                               bool swing_only, Scratch::Kinematic& k) const {
  if (!swing_only) {
    kinematics(s, qa, qda);
    saveKinematic(s, qdda, k);
    return;
  }
  // The stance sole's support path is unchanged: base pose, base velocity, G, J_sb^-1 and the
  // stance drift are those of k0 (the same bits kinematics() would compute).
  const Scratch::Kinematic& k0 = s.k0;
  s.q = k0.q;
  s.q.tail(nu_) = qa;
  model_->update(s.ws, s.q, k0.qd);
  swing_.evaluate(*model_, s.ws, s.swing);
  model_->frameJacobian(s.ws, swing_frame_, k.J2);
  k.swing_position = model_->framePose(s.ws, swing_frame_).translation();
  k.phi2 = s.swing.phi;
  k.phidot2 = s.swing.phidot;
  k.phiddot2 = s.swing.drift;
  k.phiddot2.noalias() += s.swing.J_phi * k0.qdd;
}

}  // namespace reach_trajopt
