#include "reach_trajopt/ocp/stance_reduced_dynamics.h"

#include <Eigen/LU>
#include <cmath>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

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
      yaw_reference_(yaw_reference) {
  if (!model_ || !model_->floatingBase()) {
    throw ModelError("StanceReducedDynamics: needs a floating-base model");
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
      M(d.nq(), d.nq()) {}

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
  requireSize("StanceReducedDynamics: Jacobian rows", jac.rows(), signalCount());
  requireSize("StanceReducedDynamics: Jacobian columns", jac.cols(), inputCount());
  evaluate(s, input, signals);
  const Eigen::Ref<const Vector6d> lambda2 = input.tail<6>();
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

  // qd_a: quadratic at fixed q, so central differences are exact (the step only sets roundoff).
  const Eigen::Ref<const Eigen::VectorXd> qdda = input.segment(2 * nu_, nu_);
  const Eigen::VectorXd& qd0 = s.qd_nominal;
  s.qd_nominal = s.qd;
  constexpr double kVelocityStep = 1.0;  // [rad/s]
  for (int i = 0; i < nu_; ++i) {
    for (int side = 0; side < 2; ++side) {
      const double h = side == 0 ? kVelocityStep : -kVelocityStep;
      s.qd = qd0;
      s.qd.head<6>() += h * s.G.col(i);
      s.qd[6 + i] += h;
      velocityTerms(s);
      dynamics(s, qdda, lambda2, s.signals_pert);
      if (side == 0) {
        jac.col(nu_ + i) = s.signals_pert;
      } else {
        jac.col(nu_ + i) -= s.signals_pert;
        jac.col(nu_ + i) /= 2.0 * kVelocityStep;
      }
    }
  }

  // q_a: finite differences of the whole chain (base reconstruction included).
  s.input_pert = input;
  for (int i = 0; i < nu_; ++i) {
    const double h = fd_step * std::max(1.0, std::abs(input[i]));
    s.input_pert[i] = input[i] + h;
    kinematics(s, s.input_pert.head(nu_), s.input_pert.segment(nu_, nu_));
    dynamics(s, qdda, lambda2, s.signals_pert);
    jac.col(i) = s.signals_pert;
    if (central) {
      s.input_pert[i] = input[i] - h;
      kinematics(s, s.input_pert.head(nu_), s.input_pert.segment(nu_, nu_));
      dynamics(s, qdda, lambda2, s.signals_pert);
      jac.col(i) -= s.signals_pert;
      jac.col(i) /= 2.0 * h;
    } else {
      jac.col(i) -= signals;
      jac.col(i) /= h;
    }
    s.input_pert[i] = input[i];
  }
}

}  // namespace reach_trajopt
