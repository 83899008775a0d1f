/// \file backward_step.cpp
/// The backward step (17)-(20) (see the header).

#include "reach_trajopt/reach/backward_step.h"

#include <cmath>

#include "reach_trajopt/reach/sample_slice.h"

namespace reach_trajopt {

namespace {
/// Rows of (19): the cone and the two torque bounds.
int inequalityRows(const ReachContext& c) { return ContactWrenchCone::kRows * c.nc + 2 * c.nu; }

/// The prefilter rejects a draw whose linearized slack is below minus this share of the row's
/// range over the draw box. The linearization error is O(|qd| dt) of that range (under 1e-2
/// in the walks measured, test_reach_biped): a tenth leaves a wide safety factor and still
/// rejects most of the draws (19) rejects.
constexpr double kPrefilterRangeShare = 0.1;
}  // namespace

BackwardStep::BackwardStep(const ReachContext& context)
    : ctx_(context),
      ws_(*context.model),
      n_(context.n),
      nu_(context.nu),
      m_(context.m()),
      m_eq_(context.floating ? 6 : 0),
      rows_(inequalityRows(context)),
      llt_m_(context.n),
      lu_c_(context.m()),
      lu_b_(context.floating ? 6 : 0),
      terms_(context.n),
      factor_(context.m() > 0 ? context.m() : 1),
      qp_(context.m() > 0 ? context.m() : 1, context.floating ? 6 : 0, inequalityRows(context)) {
  q_prev_.resize(n_);
  qd_j_.resize(n_);
  b_.resize(n_);
  qdd_.resize(n_);
  v_.resize(n_);
  w_.resize(n_);
  e_.resize(m_);
  M_.resize(n_, n_);
  Jc_.resize(m_, n_);
  Jphi_.resize(m_, n_);
  MinvJt_.resize(n_, m_);
  Lambda_.resize(m_, m_);
  Jbar_.resize(n_, m_);
  jphi_d_.resize(m_);
  J_.resize(6, n_);
  A_eq_.setZero(m_eq_, m_);
  b_eq_.resize(m_eq_);
  A_in_.setZero(rows_, m_);
  b_in_.resize(rows_);
  g_.setZero(m_);
  tau_.resize(n_);
  lambda_.resize(m_);
  slack_.resize(rows_);
  row_norm_.resize(rows_);
  d_max_.resize(n_);
  for (int i = 0; i < n_; ++i) {
    const bool base = ctx_.floating && i < 6;
    d_max_[i] = ctx_.config.dt *
                (base ? ctx_.config.backward_base_accel : ctx_.config.backward_joint_accel);
  }
  if (m_ > 0) factor_.compute(Eigen::MatrixXd::Identity(m_, m_));  // cost |lambda|^2 (19)
  warm_.reserve(rows_);
  T_.resize(n_, n_);
  lambda_inv_jphi_.resize(m_, n_);
  lambda_d_.resize(m_, n_);
  slack_d_.resize(rows_, n_);
  qd_center_.resize(n_);
  tau_center_.resize(n_);
  slack_0_.resize(rows_);
  prefilter_margin_.resize(rows_);
  slack_lin_.resize(rows_);
}

bool BackwardStep::setParent(const Eigen::Ref<const Eigen::VectorXd>& q,
                             const Eigen::Ref<const Eigen::VectorXd>& qd) {
  parent_ok_ = false;
  prefilter_ = false;
  qp_matrices_.refilled();  // setParent rewrites the QP's matrices
  warm_.clear();
  const RobotModel& model = *ctx_.model;
  const double dt = ctx_.config.dt;
  qd_j_ = qd;
  backwardConfiguration(q, qd, dt, q_prev_);
  const double tol = ctx_.config.limit_tolerance;
  for (int i : ctx_.finite_position)
    if (q_prev_[i] < ctx_.q_min[i] - tol || q_prev_[i] > ctx_.q_max[i] + tol) return false;
  model.update(ws_, q_prev_, qd_j_);  // q-only quantities below (M, J, phi, poses)
  model.massMatrix(ws_, M_);
  llt_m_.compute(M_);  // M is symmetric positive definite
  if (llt_m_.info() != Eigen::Success) return false;
  const double beta = ctx_.config.contact_stabilization;
  for (int c = 0; c < ctx_.nc; ++c) {
    const ContactConstraint& cc = ctx_.contacts[c];
    cc.evaluate(model, ws_, terms_);
    model.frameJacobian(ws_, cc.frame(), J_);
    Jc_.middleRows(6 * c, 6) = J_;
    Jphi_.middleRows(6 * c, 6) = terms_.J_phi;
    e_.segment<6>(6 * c) = terms_.J_phi * qd_j_ - beta * terms_.phi / dt;
    ctx_.cone.worldMatrix(model.framePose(ws_, cc.frame()).linear(), cone_world_[c]);
  }
  if (m_ > 0) {
    // Jbar = M^-1 J^T (J M^-1 J^T)^-1 (dynamically consistent inverse of eq. 17).
    // The products below are small (at most 12 x n x 12): coefficient-based (lazyProduct)
    // instead of the blocked kernel, whose packing costs more than the flops at these sizes.
    MinvJt_ = llt_m_.solve(Jphi_.transpose());
    Lambda_.noalias() = Jphi_.lazyProduct(MinvJt_);
    lu_c_.compute(Lambda_);
    const double piv = lu_c_.matrixLU().diagonal().cwiseAbs().minCoeff();
    if (!(piv > 1e-12 * lu_c_.matrixLU().diagonal().cwiseAbs().maxCoeff())) return false;
    Jbar_ = lu_c_.solve(MinvJt_.transpose()).transpose();  // Lambda symmetric
    w_.noalias() = Jbar_ * e_;
    // Rows of (19): base rows J_b^T lambda = M_b qdd + b_b; cone; torque bounds.
    if (m_eq_ > 0) A_eq_ = Jc_.leftCols(6).transpose();
    int r = 0;
    for (int c = 0; c < ctx_.nc; ++c) {
      A_in_.block(r, 6 * c, ContactWrenchCone::kRows, 6) = cone_world_[c];
      r += ContactWrenchCone::kRows;
    }
    const int off = n_ - nu_;
    A_in_.block(r, 0, nu_, m_) = Jc_.middleCols(off, nu_).transpose();         // u <= u_max
    A_in_.block(r + nu_, 0, nu_, m_) = -Jc_.middleCols(off, nu_).transpose();  // u >= -u_max
    // One held sole: the six base rows fix lambda (J_b^T square); (19) is then a test.
    unique_lambda_ = false;
    if (m_eq_ > 0 && m_eq_ == m_) {
      lu_b_.compute(A_eq_);
      const auto pivots = lu_b_.matrixLU().diagonal().cwiseAbs();
      unique_lambda_ = pivots.minCoeff() > 1e-12 * pivots.maxCoeff();
      row_norm_ = A_in_.rowwise().norm();
      if (unique_lambda_ && ctx_.config.backward_prefilter) buildPrefilter();
    }
  } else {
    w_.setZero();
  }
  parent_ok_ = true;
  return true;
}

bool BackwardStep::child(const Eigen::Ref<const Eigen::VectorXd>& d,
                         Eigen::Ref<Eigen::VectorXd> q_prev, Eigen::Ref<Eigen::VectorXd> qd_prev,
                         Eigen::Ref<Eigen::VectorXd> y, Eigen::Ref<Eigen::VectorXd> y_rate,
                         Eigen::Ref<Eigen::VectorXd> u_out,
                         Eigen::Ref<Eigen::VectorXd> lambda_out) {
  if (!parent_ok_) return false;
  if (prefilter_) {
    slack_lin_ = slack_0_;
    slack_lin_.noalias() += slack_d_ * d;
    if ((slack_lin_ + prefilter_margin_).minCoeff() < 0.0) {
      ++prefilter_rejects_;
      return false;
    }
  }
  const RobotModel& model = *ctx_.model;
  const double dt = ctx_.config.dt;
  // v = N d + w with N = I - Jbar J_phi, applied as d - Jbar (J_phi d): O(n m), not O(n^2).
  v_ = d + w_;
  if (m_ > 0) {
    jphi_d_.noalias() = Jphi_ * d;
    v_.noalias() -= Jbar_ * jphi_d_;
  }
  qd_prev = qd_j_ - v_;
  q_prev = q_prev_;
  if (!ctx_.withinLimits(q_prev, qd_prev)) return false;
  model.updateVelocity(ws_, qd_prev);  // q_{j-1} is the parent's: its poses are current
  if (!ctx_.stateConstraintsHold(ws_)) return false;
  model.bias(ws_, b_);
  qdd_ = v_ / dt;
  tau_.noalias() = M_ * qdd_;
  tau_ += b_;  // M qdd + b = S^T u + J^T lambda
  const int off = n_ - nu_;
  if (m_ == 0) {
    u_out = tau_.tail(nu_);
    for (int i = 0; i < nu_; ++i)
      if (std::abs(u_out[i]) > ctx_.u_max[i] + ctx_.config.limit_tolerance) return false;
  } else {
    if (m_eq_ > 0) b_eq_ = tau_.head(6);
    int r = ContactWrenchCone::kRows * ctx_.nc;
    b_in_.head(r).setZero();
    for (int i = 0; i < nu_; ++i) {
      b_in_[r + i] = tau_[off + i] - ctx_.u_max[i];         // J_a^T l >= tau_a - u_max
      b_in_[r + nu_ + i] = -ctx_.u_max[i] - tau_[off + i];  // -J_a^T l >= -u_max - tau_a
    }
    ++qp_count_;
    if (unique_lambda_) {
      if (!uniqueLambdaFeasible()) return false;
    } else {
      const qp::QpResult& res =
          qp_.solve(factor_, g_, A_eq_, b_eq_, A_in_, b_in_, warm_.empty() ? nullptr : &warm_,
                    qp_matrices_.nextSolve());
      if (res.status != qp::QpStatus::kOptimal) return false;
      warm_ = res.active_set;
      lambda_ = res.x;
    }
    lambda_out = lambda_;
    u_out = tau_.tail(nu_);
    u_out.noalias() -= Jc_.middleCols(off, nu_).transpose() * lambda_;
  }
  ctx_.output(ws_, y, y_rate);
  return true;
}

void BackwardStep::buildPrefilter() {
  const RobotModel& model = *ctx_.model;
  const double dt = ctx_.config.dt;
  // The draw d = 0: qd_{j-1} = qd_j - w, qdd = w / dt; its bias, frozen for every d.
  qd_center_ = qd_j_ - w_;
  model.updateVelocity(ws_, qd_center_);
  model.bias(ws_, b_);
  tau_center_.noalias() = M_ * w_;
  tau_center_ /= dt;
  tau_center_ += b_;
  // tau(d) ~ tau_center + T d with T = M N / dt = (M - J_phi^T Lambda^-1 J_phi) / dt, since
  // M Jbar = J_phi^T Lambda^-1: n x m x n with Lambda's inverse, instead of M N's n^3.
  // The prefilter runs with one held sole only (m = 6, J_b^T square): both 6 x 6 inverses in
  // fixed size. Its rounding differs from the LU solves of setParent() in the last bits, which
  // cannot move a draw across the margin below (a share of the row's range).
  using Matrix6d = Eigen::Matrix<double, 6, 6>;
  const Matrix6d lambda_inv = Matrix6d(Lambda_).inverse();
  const Matrix6d base_rows_inv = Matrix6d(A_eq_).inverse();  // J_b^-T
  lambda_inv_jphi_.noalias() = lambda_inv.lazyProduct(Jphi_);
  T_ = M_;
  T_.noalias() -= Jphi_.transpose().lazyProduct(lambda_inv_jphi_);
  T_ /= dt;
  // lambda(d) = J_b^-T tau_b(d); slack = A_in lambda - b_in(tau), b_in as in child().
  lambda_.noalias() = base_rows_inv * tau_center_.head(6);
  lambda_d_.noalias() = base_rows_inv.lazyProduct(T_.topRows(6));
  const int r = ContactWrenchCone::kRows * ctx_.nc;
  const int off = n_ - nu_;
  b_in_.head(r).setZero();
  for (int i = 0; i < nu_; ++i) {
    b_in_[r + i] = tau_center_[off + i] - ctx_.u_max[i];
    b_in_[r + nu_ + i] = -ctx_.u_max[i] - tau_center_[off + i];
  }
  slack_0_.noalias() = A_in_ * lambda_;
  slack_0_ -= b_in_;
  // Cone rows; the upper torque rows J_a^T lambda(d) - tau_a(d); the lower ones are their
  // negatives (A_in's rows r + nu.. are minus rows r..), exactly.
  slack_d_.topRows(r + nu_).noalias() = A_in_.topRows(r + nu_).lazyProduct(lambda_d_);
  slack_d_.middleRows(r, nu_) -= T_.middleRows(off, nu_);
  slack_d_.middleRows(r + nu_, nu_) = -slack_d_.middleRows(r, nu_);
  // Margin: a share of the row's range over the box, plus the exact test's tolerance.
  const double tol = qp::QpSolverConfig().feasibility_tol;
  const double norm = lambda_.norm();
  prefilter_margin_.noalias() = slack_d_.cwiseAbs() * d_max_;
  prefilter_margin_ *= kPrefilterRangeShare;
  for (int j = 0; j < rows_; ++j)
    prefilter_margin_[j] += 2.0 * tol * (1.0 + std::abs(b_in_[j]) + row_norm_[j] * norm);
  prefilter_ = prefilter_margin_.allFinite() && slack_0_.allFinite();
}

bool BackwardStep::uniqueLambdaFeasible() {
  lambda_ = lu_b_.solve(b_eq_);
  // The QP's own acceptance test of an inequality row (dual_active_set_qp.h).
  const double tol = qp::QpSolverConfig().feasibility_tol;
  const double norm = lambda_.norm();
  slack_.noalias() = A_in_ * lambda_;
  slack_ -= b_in_;
  for (int j = 0; j < rows_; ++j)
    if (slack_[j] < -tol * (1.0 + std::abs(b_in_[j]) + row_norm_[j] * norm)) return false;
  return true;
}

}  // namespace reach_trajopt
