/// \file forward_step.cpp
/// The forward step (15)-(16) in reduced form (see the header).

#include "reach_trajopt/reach/forward_step.h"

#include <cmath>

#include "reach_trajopt/reach/sample_slice.h"

namespace reach_trajopt {

namespace {
/// Right-hand side of a one-sided position row without that bound (the QP takes finite data).
constexpr double kNoBound = -1e20;

/// The ground row exists in bridge steps only (sampling rejects children below the ground).
bool hasGroundRow(const ReachContext& c, const ForwardStepCost& cost) {
  return cost.bridge && c.swing_frame >= 0;
}

int inequalityRows(const ReachContext& c, const ForwardStepCost& cost) {
  return 2 * c.nu + ContactWrenchCone::kRows * c.nc +
         2 * static_cast<int>(c.finite_velocity.size()) +
         2 * static_cast<int>(c.finite_position.size()) + (hasGroundRow(c, cost) ? 1 : 0);
}
}  // namespace

ForwardStepCost ForwardStepCost::sampling(const ReachConfig& config) {
  ForwardStepCost c;
  c.w_qdd = config.w_qdd;
  c.w_du = config.w_du;
  c.w_lambda = config.w_lambda;
  return c;
}

ForwardStep::ForwardStep(const ReachContext& context)
    : ForwardStep(context, ForwardStepCost::sampling(context.config)) {}

ForwardStep::ForwardStep(const ReachContext& context, const ForwardStepCost& cost)
    : ctx_(context),
      cost_(cost),
      ws_(*context.model),
      n_(context.n),
      nu_(context.nu),
      m_(context.m()),
      rows_(inequalityRows(context, cost)),
      lu_(context.n + context.m()),
      terms_(context.n),
      factor_(context.nu),
      qp_(context.nu, 0, inequalityRows(context, cost)),
      empty_eq_(0, context.nu),
      empty_beq_(0) {
  const int k = n_ + m_;
  q_.resize(n_);
  qd_.resize(n_);
  M_.resize(n_, n_);
  b_.resize(n_);
  K_.setZero(k, k);
  E_.setZero(k, nu_);
  E_.block(n_ - nu_, 0, nu_, nu_).setIdentity();  // [S^T; 0]
  P_.resize(k, nu_);
  PtW_.resize(nu_, k);
  G_.resize(nu_, nu_);
  A_in_.setZero(rows_, nu_);
  b_in_.resize(rows_);
  J_.resize(6, n_);
  r0_.resize(k);
  s_.resize(k);
  g_.resize(nu_);
  z_.resize(k);
  w_.resize(k);
  w_.head(n_).setConstant(cost_.w_qdd);
  w_.tail(m_).setConstant(cost_.w_lambda);
  swing_jz_.setZero(n_);
  target_.resize(k);
  warm_.reserve(rows_);
}

bool ForwardStep::setParent(const Eigen::Ref<const Eigen::VectorXd>& q,
                            const Eigen::Ref<const Eigen::VectorXd>& qd) {
  parent_ok_ = false;
  qp_matrices_.refilled();  // setParent rewrites the QP's matrices
  warm_.clear();
  const RobotModel& model = *ctx_.model;
  const ReachConfig& cfg = ctx_.config;
  const double dt = cfg.dt;
  q_ = q;
  qd_ = qd;
  if (!ctx_.config.semiImplicit()) {
    // Explicit Euler: every child has q_{j+1} = q + dt qd, so check it once here.
    for (int i : ctx_.finite_position) {
      const double qn = q_[i] + dt * qd_[i];
      if (qn < ctx_.q_min[i] - cfg.limit_tolerance || qn > ctx_.q_max[i] + cfg.limit_tolerance)
        return false;
    }
  }
  model.update(ws_, q_, qd_);
  model.massMatrix(ws_, M_);
  model.bias(ws_, b_);
  fillDynamicsAndContactRows();
  lu_.compute(K_);
  // A singular K (contact Jacobian losing rank): no child from this parent.
  const double piv = lu_.matrixLU().diagonal().cwiseAbs().minCoeff();
  const double scale = lu_.matrixLU().diagonal().cwiseAbs().maxCoeff();
  if (!(piv > 1e-12 * scale)) return false;
  P_ = lu_.solve(E_);
  r0_ = lu_.solve(r0_);
  // Hessian 2 (w_du I + P^T W P) of the reduced cost.
  PtW_ = P_.transpose() * w_.asDiagonal();
  G_.noalias() = 2.0 * PtW_ * P_;
  G_.diagonal().array() += 2.0 * cost_.w_du;
  if (!factor_.compute(G_)) return false;
  fillInequalityRows();
  parent_ok_ = true;
  return true;
}

void ForwardStep::fillDynamicsAndContactRows() {
  const RobotModel& model = *ctx_.model;
  const double dt = ctx_.config.dt;
  // K = [M, -J^T; J_phi, 0]; right-hand side of the contact rows a_c.
  K_.topLeftCorner(n_, n_) = M_;
  r0_.head(n_) = -b_;
  const double beta = ctx_.config.contact_stabilization;
  for (int c = 0; c < ctx_.nc; ++c) {
    const ContactConstraint& cc = ctx_.contacts[c];
    cc.evaluate(model, ws_, terms_);
    model.frameJacobian(ws_, cc.frame(), J_);
    K_.block(0, n_ + 6 * c, n_, 6) = -J_.transpose();
    K_.block(n_ + 6 * c, 0, 6, n_) = terms_.J_phi;
    r0_.segment<6>(n_ + 6 * c) =
        -terms_.drift - beta * (terms_.phi / (dt * dt) + 2.0 * terms_.phidot / dt);
    ctx_.cone.worldMatrix(model.framePose(ws_, cc.frame()).linear(), cone_world_[c]);
  }
}

void ForwardStep::fillInequalityRows() {
  const RobotModel& model = *ctx_.model;
  const ReachConfig& cfg = ctx_.config;
  const double dt = cfg.dt;
  // Inequality matrix (rows depend on the parent only; right-hand sides on the child).
  int r = 0;
  A_in_.block(r, 0, nu_, nu_).setIdentity();
  r += nu_;
  A_in_.block(r, 0, nu_, nu_) = -Eigen::MatrixXd::Identity(nu_, nu_);
  r += nu_;
  for (int c = 0; c < ctx_.nc; ++c) {
    A_in_.block(r, 0, ContactWrenchCone::kRows, nu_).noalias() =
        cone_world_[c] * P_.middleRows(n_ + 6 * c, 6);
    r += ContactWrenchCone::kRows;
  }
  for (int i : ctx_.finite_velocity) {
    A_in_.row(r++) = -P_.row(i);
    A_in_.row(r++) = P_.row(i);
  }
  for (int i : ctx_.finite_position) {
    A_in_.row(r++) = -P_.row(i);
    A_in_.row(r++) = P_.row(i);
  }
  if (hasGroundRow(ctx_, cost_)) {
    // The ground row of a bridge step: the swing sole above the ground one step ahead, to
    // first order (hence within half the certificate's tolerance):
    // z + dt (zdot + dt (J_z qdd + Jdot_z qd)) >= ground.
    model.frameJacobian(ws_, ctx_.swing_frame, J_);
    swing_jz_ = J_.row(2);
    const double z = model.framePose(ws_, ctx_.swing_frame).translation().z();
    const double zdot = model.frameVelocity(ws_, ctx_.swing_frame)[2];
    const double ground = ctx_.ground_height - 0.5 * cfg.certificate_tolerance;
    ground_rhs_ = ((ground - z) / dt - zdot) / dt - model.frameJdotQd(ws_, ctx_.swing_frame)[2];
    A_in_.row(r++).noalias() = swing_jz_ * P_.topRows(n_);
  }
}

bool ForwardStep::child(const Eigen::Ref<const Eigen::VectorXd>& u,
                        Eigen::Ref<Eigen::VectorXd> q_child, Eigen::Ref<Eigen::VectorXd> qd_child,
                        Eigen::Ref<Eigen::VectorXd> y, Eigen::Ref<Eigen::VectorXd> y_rate,
                        Eigen::Ref<Eigen::VectorXd> u_out, Eigen::Ref<Eigen::VectorXd> lambda_out) {
  return solveChild(u, nullptr, q_child, qd_child, y, y_rate, u_out, lambda_out);
}

bool ForwardStep::trackChild(const Eigen::Ref<const Eigen::VectorXd>& u,
                             const Eigen::Ref<const Eigen::VectorXd>& qdd_target,
                             Eigen::Ref<Eigen::VectorXd> q_child,
                             Eigen::Ref<Eigen::VectorXd> qd_child, Eigen::Ref<Eigen::VectorXd> y,
                             Eigen::Ref<Eigen::VectorXd> y_rate, Eigen::Ref<Eigen::VectorXd> u_out,
                             Eigen::Ref<Eigen::VectorXd> lambda_out) {
  target_.setZero();
  target_.head(n_) = qdd_target;
  return solveChild(u, &target_, q_child, qd_child, y, y_rate, u_out, lambda_out);
}

bool ForwardStep::solveChild(const Eigen::Ref<const Eigen::VectorXd>& u,
                             const Eigen::VectorXd* target, Eigen::Ref<Eigen::VectorXd> q_child,
                             Eigen::Ref<Eigen::VectorXd> qd_child, Eigen::Ref<Eigen::VectorXd> y,
                             Eigen::Ref<Eigen::VectorXd> y_rate, Eigen::Ref<Eigen::VectorXd> u_out,
                             Eigen::Ref<Eigen::VectorXd> lambda_out) {
  if (!parent_ok_) return false;
  const ReachConfig& cfg = ctx_.config;
  const double dt = cfg.dt;
  const bool semi = cfg.semiImplicit();
  // s = [qdd; lambda] at du = 0; cost gradient 2 P^T W (s - target).
  s_.noalias() = P_ * u;
  s_ += r0_;
  if (target) {
    z_ = s_ - *target;
    g_.noalias() = 2.0 * PtW_ * z_;
  } else {
    g_.noalias() = 2.0 * PtW_ * s_;
  }
  int r = 0;
  for (int i = 0; i < nu_; ++i) b_in_[r + i] = -ctx_.u_max[i] - u[i];  // du >= -u_max - u
  r += nu_;
  for (int i = 0; i < nu_; ++i) b_in_[r + i] = -ctx_.u_max[i] + u[i];  // -du >= -u_max + u
  r += nu_;
  for (int c = 0; c < ctx_.nc; ++c) {
    b_in_.segment<ContactWrenchCone::kRows>(r).noalias() =
        -cone_world_[c] * s_.segment<6>(n_ + 6 * c);
    r += ContactWrenchCone::kRows;
  }
  for (int i : ctx_.finite_velocity) {  // |qd + dt qdd| <= qd_max, rows scaled by 1/dt
    b_in_[r++] = (qd_[i] - ctx_.qd_max[i]) / dt + s_[i];
    b_in_[r++] = (-ctx_.qd_max[i] - qd_[i]) / dt - s_[i];
  }
  // Position rows on q + c1 dt qd + dt^2 qdd (q_{j+1} semi-implicit, q_{j+2} explicit).
  const double c1 = semi ? 1.0 : 2.0;
  for (int i : ctx_.finite_position) {
    const double qn = q_[i] + c1 * dt * qd_[i];
    b_in_[r++] = std::isfinite(ctx_.q_max[i]) ? (qn - ctx_.q_max[i]) / (dt * dt) + s_[i] : kNoBound;
    b_in_[r++] = std::isfinite(ctx_.q_min[i]) ? (ctx_.q_min[i] - qn) / (dt * dt) - s_[i] : kNoBound;
  }
  if (hasGroundRow(ctx_, cost_)) b_in_[r++] = ground_rhs_ - swing_jz_.dot(s_.head(n_));
  ++qp_count_;
  const qp::QpResult& res = qp_.solve(factor_, g_, empty_eq_, empty_beq_, A_in_, b_in_,
                                      warm_.empty() ? nullptr : &warm_, qp_matrices_.nextSolve());
  if (res.status != qp::QpStatus::kOptimal) return false;
  warm_ = res.active_set;
  u_out = u + res.x;
  z_.noalias() = P_ * u_out;
  z_ += r0_;
  qd_child = qd_ + dt * z_.head(n_);
  forwardConfiguration(q_, qd_, qd_child, dt, semi, q_child);
  lambda_out = z_.tail(m_);
  if (!cost_.bridge && !ctx_.withinLimits(q_child, qd_child)) return false;
  const RobotModel& model = *ctx_.model;
  model.update(ws_, q_child, qd_child);
  if (!cost_.bridge && !ctx_.stateConstraintsHold(ws_)) return false;
  ctx_.output(ws_, y, y_rate);
  return true;
}

}  // namespace reach_trajopt
