/// \file whole_body_controller.cpp
/// Inverse-dynamics QP whole-body controller (see the header for the QP).

#include "reach_trajopt/control/whole_body_controller.h"

#include <cmath>

#include "reach_trajopt/common/config_fields.h"

namespace reach_trajopt {
namespace {

/// World-frame rotation vector e with exp([e]) R = R_des (small-angle orientation error).
Eigen::Vector3d orientationError(const Eigen::Matrix3d& R_des, const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R_des * R.transpose());
  return aa.angle() * aa.axis();
}

}  // namespace

void WbcConfig::validate() const { fields().checkRanges(*this); }

const ConfigFields<WbcConfig>& WbcConfig::fields() {
  using C = WbcConfig;
  static const ConfigFields<C> f =
      ConfigFields<C>("WbcConfig", "wbc", "include/reach_trajopt/control/whole_body_controller.h",
                      "Whole-body controller: task weights (>= 0; larger wins over the other "
                      "tasks) and PD gains (>= 0; larger tracks faster but amplifies the "
                      "simulator's contact noise).")
          .add("w_com", &C::w_com, "", Range::nonNegative(), "weight of the CoM height task")
          .add("kp_com", &C::kp_com, "1/s^2", Range::nonNegative(), "its stiffness")
          .add("kd_com", &C::kd_com, "1/s", Range::nonNegative(), "its damping")
          .add("w_com_xy", &C::w_com_xy, "", Range::nonNegative(),
               "horizontal CoM weight; small: the CoM moves as the pendulum the TVR planner "
               "assumes")
          .add("w_pelvis", &C::w_pelvis, "", Range::nonNegative(),
               "weight of the pelvis orientation task")
          .add("kp_pelvis", &C::kp_pelvis, "1/s^2", Range::nonNegative(), "its stiffness")
          .add("kd_pelvis", &C::kd_pelvis, "1/s", Range::nonNegative(), "its damping")
          .add("w_swing", &C::w_swing, "", Range::nonNegative(),
               "weight of the swing sole pose task")
          .add("kp_swing", &C::kp_swing, "1/s^2", Range::nonNegative(), "its stiffness")
          .add("kd_swing", &C::kd_swing, "1/s", Range::nonNegative(), "its damping")
          .add("w_posture", &C::w_posture, "", Range::nonNegative(),
               "weight of the joint posture task")
          .add("kp_posture", &C::kp_posture, "1/s^2", Range::nonNegative(), "its stiffness")
          .add("kd_posture", &C::kd_posture, "1/s", Range::nonNegative(), "its damping")
          .add("w_qdd", &C::w_qdd, "", Range::positive(),
               "regularization of qdd (keeps the QP strictly convex)")
          .add("w_lambda", &C::w_lambda, "1/N^2", Range::positive(),
               "regularization of the contact wrenches (keeps the QP strictly convex)")
          .add("leg_clearance", &C::leg_clearance, "",
               "in single support a barrier row keeps the legs' collision capsules "
               "(model/leg_clearance.h) leg_clearance_margin apart: d'' >= kp (margin - d) - "
               "kd d'")
          .add("leg_clearance_margin", &C::leg_clearance_margin, "m", Range::nonNegative(),
               "distance the barrier holds between the legs' capsules")
          .add("leg_clearance_activation", &C::leg_clearance_activation, "m", Range::nonNegative(),
               "a capsule pair closer than this gets a barrier row (one row per pair)")
          .add("kp_leg_clearance", &C::kp_leg_clearance, "1/s^2", Range::nonNegative(),
               "the barrier's stiffness")
          .add("kd_leg_clearance", &C::kd_leg_clearance, "1/s", Range::nonNegative(),
               "its damping: the barrier acts from about kd / kp * (closing speed) before the "
               "margin")
          .add("min_normal_force", &C::min_normal_force, "N", Range::nonNegative(),
               "double support: each sole's wrench is at least this normal force at its centre "
               "plus a wrench of its cone (both soles stay loaded)");
  return f;
}

WbcConfig WbcConfig::fromYaml(const YamlSection& s) { return fields().read(s); }

WholeBodyController::WholeBodyController(std::shared_ptr<const RobotModel> model,
                                         const ContactConfig& contact, const WbcConfig& config,
                                         const Eigen::VectorXd& posture)
    : model_(std::move(model)),
      contact_(contact),
      config_(config),
      cone_(contact),
      left_sole_(model_->frameId(contact.left_sole_frame)),
      right_sole_(model_->frameId(contact.right_sole_frame)),
      pelvis_(model_->frameId(config.pelvis_frame.empty() ? model_->linkNames().front()
                                                          : config.pelvis_frame)),
      posture_(posture),
      legs_(config.leg_clearance
                ? LegClearance(*model_, contact.left_sole_frame, contact.right_sole_frame)
                : LegClearance()),
      ws_(*model_),
      qp_single_(model_->nq() + 6, 6 + 6,
                 ContactWrenchCone::kRows + legs_.pairCount() + 2 * model_->nu()),
      qp_double_(model_->nq() + 12, 6 + 12, 2 * ContactWrenchCone::kRows + 2 * model_->nu()) {
  contact_.validate();
  config_.validate();
  if (!model_->floatingBase())
    throw ModelError("WholeBodyController needs a floating-base model, got " + model_->source());
  requireSize("WholeBodyController: posture", posture_.size(), model_->nq());
  requireFinite("WholeBodyController: posture", posture_);
  const int n = model_->nq();
  M_.resize(n, n);
  b_.resize(n);
  for (auto& J : J_sole_) J.resize(6, n);
  J_pelvis_.resize(6, n);
  J_com_.resize(3, n);
  const int nx = n + 12;
  G_.resize(nx, nx);
  g_.resize(nx);
  A_eq_.resize(18, nx);
  b_eq_.resize(18);
  A_in_.resize(2 * ContactWrenchCone::kRows + legs_.pairCount() + 2 * model_->nu(), nx);
  leg_pairs_.reserve(legs_.pairCount());
  leg_gradients_.resize(legs_.pairCount(), n);
  leg_drifts_.resize(legs_.pairCount());
  b_in_.resize(A_in_.rows());
  out_.u = Eigen::VectorXd::Zero(model_->nu());
  u_max_ = model_->effortLimits();
  posture_acc_.resize(model_->nu());
  out_.qdd = Eigen::VectorXd::Zero(n);
}

void WholeBodyController::addTask(const Eigen::Ref<const Eigen::MatrixXd>& J,
                                  const Eigen::Ref<const Eigen::VectorXd>& drift,
                                  const Eigen::Ref<const Eigen::VectorXd>& a_des, double weight) {
  const int n = model_->nq();
  G_.topLeftCorner(n, n).noalias() += weight * J.transpose() * J;
  g_.head(n).noalias() += weight * J.transpose() * (drift - a_des);
}

const WbcOutput& WholeBodyController::compute(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                              const ContactMode& mode, const WbcReference& ref) {
  const RobotModel& m = *model_;
  const int n = m.nq();
  const int nc = mode.contactCount();
  if (nc == 0) throw ReachError("WholeBodyController: no sole in contact (flight is not handled)");
  m.update(ws_, q, qd);
  m.massMatrix(ws_, M_);
  m.bias(ws_, b_);
  const int nx = n + 6 * nc;
  G_.topLeftCorner(nx, nx).setZero();
  g_.head(nx).setZero();
  addTasks(q, qd, mode, ref);
  addConstraints(mode, qd);
  return solveQp(mode);
}

void WholeBodyController::addTasks(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                   const ContactMode& mode, const WbcReference& ref) {
  const RobotModel& m = *model_;
  const int n = m.nq(), nu = m.nu();
  const int nc = mode.contactCount();
  const WbcConfig& c = config_;
  m.centerOfMassJacobian(ws_, J_com_);
  {
    const Eigen::Vector3d com = m.centerOfMass(ws_);
    const Eigen::Vector3d com_vel = J_com_ * qd;
    const Eigen::Vector3d a = ref.com_acceleration + c.kd_com * (ref.com_velocity - com_vel) +
                              c.kp_com * (ref.com_position - com);
    const Eigen::Vector3d drift = m.centerOfMassJdotQd(ws_);
    addTask(J_com_.topRows<2>(), drift.head<2>(), a.head<2>(),
            ref.w_com_xy >= 0.0 ? ref.w_com_xy : c.w_com_xy);
    addTask(J_com_.bottomRows<1>(), drift.tail<1>(), a.tail<1>(), c.w_com);
  }
  {
    m.frameJacobian(ws_, pelvis_, J_pelvis_);
    const Eigen::Matrix3d R = m.framePose(ws_, pelvis_).linear();
    const Eigen::Vector3d w = J_pelvis_.bottomRows<3>() * qd;
    const Eigen::Vector3d a =
        -c.kd_pelvis * w + c.kp_pelvis * orientationError(ref.pelvis_rotation, R);
    addTask(J_pelvis_.bottomRows<3>(), m.frameJdotQd(ws_, pelvis_).tail<3>(), a, c.w_pelvis);
  }
  for (int s = 0; s < 2; ++s) m.frameJacobian(ws_, s == 0 ? left_sole_ : right_sole_, J_sole_[s]);
  if (mode.isSingleSupport()) {
    const int sw = mode.swing() == Side::kLeft ? 0 : 1;
    const FrameId id = sw == 0 ? left_sole_ : right_sole_;
    const Eigen::Isometry3d T = m.framePose(ws_, id);
    const Vector6d v = J_sole_[sw] * qd;
    Vector6d a;
    a.head<3>() = ref.swing_acceleration + c.kd_swing * (ref.swing_velocity - v.head<3>()) +
                  c.kp_swing * (ref.swing_position - T.translation());
    a.tail<3>() =
        -c.kd_swing * v.tail<3>() + c.kp_swing * orientationError(ref.swing_rotation, T.linear());
    addTask(J_sole_[sw], m.frameJdotQd(ws_, id), a, c.w_swing);
  }
  {
    const bool ff = ref.q_ff.size() == n;
    const Eigen::VectorXd& q_ref =
        ff ? ref.q_ff : (ref.posture.size() == n ? ref.posture : posture_);
    const int off = n - nu;
    Eigen::VectorXd& a = posture_acc_;
    a.noalias() = c.kp_posture * (q_ref.tail(nu) - q.tail(nu)) - c.kd_posture * qd.tail(nu);
    if (ff && ref.qd_ff.size() == n) a += c.kd_posture * ref.qd_ff.tail(nu);
    if (ff && ref.qdd_ff.size() == n) a += ref.qdd_ff.tail(nu);
    G_.block(off, off, nu, nu).diagonal().array() += c.w_posture;
    g_.segment(off, nu) -= c.w_posture * a;
  }
  G_.topLeftCorner(n, n).diagonal().array() += c.w_qdd;
  G_.block(n, n, 6 * nc, 6 * nc).diagonal().array() += c.w_lambda;
}

void WholeBodyController::addConstraints(const ContactMode& mode, const Eigen::VectorXd& qd) {
  const RobotModel& m = *model_;
  const int n = m.nq(), nu = m.nu();
  const int nc = mode.contactCount();
  const int nx = n + 6 * nc;
  const int m_eq = 6 + 6 * nc;
  const int t_barrier = ContactWrenchCone::kRows * nc;
  auto Ain_all = A_in_.topLeftCorner(A_in_.rows(), nx);
  Ain_all.setZero();
  const int barrier_rows_before = barrier_rows_;
  barrier_rows_ = mode.isSingleSupport() ? addLegBarrier(t_barrier, nx, qd) : 0;
  // The warm start numbers the rows: the torque rows moved with the barrier's count.
  if (barrier_rows_ != barrier_rows_before) warm_single_.clear();
  const int t0 = t_barrier + barrier_rows_;  // the torque rows
  auto Aeq = A_eq_.topLeftCorner(m_eq, nx);
  auto Ain = A_in_.topLeftCorner(t0 + 2 * nu, nx);
  Aeq.setZero();
  Aeq.topLeftCorner(6, n) = M_.topRows(6);
  b_eq_.head(6) = -b_.head(6);
  ContactWrenchCone::Matrix Cw;
  int k = 0;
  for (int s = 0; s < 2; ++s) {
    if (!mode.inContact(s == 0 ? Side::kLeft : Side::kRight)) continue;
    const int col = n + 6 * k;
    const FrameId id = s == 0 ? left_sole_ : right_sole_;
    Aeq.block(0, col, 6, 6) = -J_sole_[s].leftCols(6).transpose();
    Aeq.block(6 + 6 * k, 0, 6, n) = J_sole_[s];
    b_eq_.segment(6 + 6 * k, 6) = -m.frameJdotQd(ws_, id);
    cone_.worldMatrix(m.framePose(ws_, id).linear(), Cw);
    Ain.block(ContactWrenchCone::kRows * k, col, ContactWrenchCone::kRows, 6) = Cw;
    // Torque rows: u = M_a qdd + b_a - J_a^T lambda.
    Ain.block(t0, col, nu, 6) = J_sole_[s].rightCols(nu).transpose();
    Ain.block(t0 + nu, col, nu, 6) = -J_sole_[s].rightCols(nu).transpose();
    ++k;
  }
  // C (lambda - lambda_min) >= 0, lambda_min the sole-frame normal force min_normal_force at
  // the sole centre (double support): C blkdiag(R^T, R^T) lambda_min = C e_z f_min.
  const double f_min = nc == 2 ? config_.min_normal_force : 0.0;
  for (int c = 0; c < nc; ++c)
    b_in_.segment(ContactWrenchCone::kRows * c, ContactWrenchCone::kRows) =
        f_min * cone_.soleMatrix().col(2);
  const Eigen::VectorXd& u_max = u_max_;
  Ain.block(t0, 0, nu, n) = -M_.bottomRows(nu);  // u <= u_max
  b_in_.segment(t0, nu) = b_.tail(nu) - u_max;
  Ain.block(t0 + nu, 0, nu, n) = M_.bottomRows(nu);  // u >= -u_max
  b_in_.segment(t0 + nu, nu) = -u_max - b_.tail(nu);
}

int WholeBodyController::addLegBarrier(int row, int nx, const Eigen::VectorXd& qd) {
  if (legs_.empty()) return 0;
  const RobotModel& m = *model_;
  const WbcConfig& cf = config_;
  // One row per capsule pair within reach of the barrier: the closest pair alone would let a
  // pair closing fast take over too late to be stopped.
  legs_.pairsWithin(m, ws_, cf.leg_clearance_activation, leg_pairs_);
  const int count = static_cast<int>(leg_pairs_.size());
  auto gradients = leg_gradients_.topRows(count);
  auto drifts = leg_drifts_.head(count);
  legs_.pairTerms(m, ws_, leg_pairs_, gradients, drifts);
  for (int k = 0; k < count; ++k) {
    const double rate = gradients.row(k).dot(qd);
    // d'' = g qdd + drift >= kp (margin - d) - kd d', as A_in x >= b_in.
    A_in_.block(row + k, 0, 1, m.nq()) = gradients.row(k);
    A_in_.block(row + k, m.nq(), 1, nx - m.nq()).setZero();
    b_in_[row + k] = cf.kp_leg_clearance * (cf.leg_clearance_margin - leg_pairs_[k].distance) -
                     cf.kd_leg_clearance * rate - drifts[k];
  }
  return count;
}

const WbcOutput& WholeBodyController::solveQp(const ContactMode& mode) {
  const int n = model_->nq(), nu = model_->nu();
  const int nc = mode.contactCount();
  const int nx = n + 6 * nc;
  const int m_eq = 6 + 6 * nc;
  const int t_barrier = ContactWrenchCone::kRows * nc;
  const int t0 = t_barrier + barrier_rows_;
  const int m_in = t0 + 2 * nu;
  auto Aeq = A_eq_.topLeftCorner(m_eq, nx);
  auto Ain = A_in_.topLeftCorner(m_in, nx);
  qp::DualActiveSetQp& solver = nc == 1 ? qp_single_ : qp_double_;
  std::vector<int>& warm = nc == 1 ? warm_single_ : warm_double_;
  const qp::QpResult& r = solver.solve(G_.topLeftCorner(nx, nx), g_.head(nx), Aeq, b_eq_.head(m_eq),
                                       Ain, b_in_.head(m_in), warm.empty() ? nullptr : &warm);
  out_.status = r.status;
  out_.message = r.message;
  if (r.status == qp::QpStatus::kInfeasible) {
    // The torque limits cannot be met together with the contacts (and the legs' barrier):
    // solve without them (the actuators saturate in the simulator), then without the barrier
    // too, and report the tick as not optimal.
    const int kept_rows[] = {t0, t_barrier};
    for (int i = 0; i < (barrier_rows_ ? 2 : 1); ++i) {
      const int rows = kept_rows[i];
      const qp::QpResult& relaxed =
          solver.solve(G_.topLeftCorner(nx, nx), g_.head(nx), Aeq, b_eq_.head(m_eq),
                       Ain.topRows(rows), b_in_.head(rows));
      if (relaxed.status != qp::QpStatus::kOptimal) continue;
      out_.message = std::string(i == 0 ? "torque limits dropped: "
                                        : "torque limits and the legs' barrier dropped: ") +
                     out_.message;
      warm.clear();
      fillOutput(relaxed, mode, n, nu);
      return out_;
    }
  }
  if (r.status != qp::QpStatus::kOptimal) {
    warm.clear();
    return out_;
  }
  warm = r.active_set;
  fillOutput(r, mode, n, nu);
  return out_;
}

void WholeBodyController::fillOutput(const qp::QpResult& r, const ContactMode& mode, int n,
                                     int nu) {
  out_.qdd = r.x.head(n);
  out_.u = M_.bottomRows(nu) * out_.qdd + b_.tail(nu);
  out_.lambda_left.setZero();
  out_.lambda_right.setZero();
  int k = 0;
  for (int s = 0; s < 2; ++s) {
    if (!mode.inContact(s == 0 ? Side::kLeft : Side::kRight)) continue;
    const Vector6d lam = r.x.segment<6>(n + 6 * k);
    out_.u -= J_sole_[s].rightCols(nu).transpose() * lam;
    (s == 0 ? out_.lambda_left : out_.lambda_right) = lam;
    ++k;
  }
}

}  // namespace reach_trajopt
