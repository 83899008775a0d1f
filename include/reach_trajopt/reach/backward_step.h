#pragma once
/// \file backward_step.h
/// One backward step of the reachable set, eq. (17)-(20), in the corrected reading of
/// docs/method.md Sec. 4. From x_j = (q_j, qd_j):
///   q_{j-1} = q_j - dt qd_j;
///   draw d ~ U(-dt a_max, dt a_max) per coordinate, v = N d + Jbar e, with N = I - Jbar J_phi,
///   Jbar = M^-1 J_phi^T (J_phi M^-1 J_phi^T)^-1 (eq. 17) and e = J_phi qd_j - beta phi / dt
///   (beta = contact_stabilization), all at q_{j-1}, so J_phi qd_{j-1} = beta phi / dt: the
///   held soles keep zero contact velocity (eq. 18), with the Euler drift removed;
///   qd_{j-1} = qd_j - v (v stands for dt qdd);
///   check the state limits at x_{j-1}; then with qdd = v / dt at x_{j-1} (not x_j as printed)
///   solve the feasibility QP (19): min |lambda|^2 s.t. the six floating-base rows
///   M_b qdd + b_b = J_b^T lambda, the cone C_i R_i lambda_i >= 0 and the torque bounds on
///   u = M_a qdd + b_a - J_a^T lambda. A feasible child is kept with its (u, lambda).
/// The step x_{j-1} -> x_j is then the semi-implicit Euler step of eq. (1).
/// M (Cholesky), J, Jbar, the cone rows and the QP matrices depend on q_{j-1} only and are shared
/// by all children of a parent (setParent()); a child costs a velocity-only kinematics pass, one
/// bias evaluation and a tiny QP. With one held sole the six base rows determine lambda
/// (J_b^T is square): then (19) has one feasible point, lambda = J_b^-T (M_b qdd + b_b), and
/// the "QP" is that solve (LU per parent) and the QP's own test of the inequality rows.
///
/// Prefilter (ReachConfig::backward_prefilter, one held sole): (19) rejects about 85 % of the
/// draws, each after a velocity pass and a bias evaluation. Per parent, the slack of every
/// inequality row of (19) is affine in d once the bias b(q_{j-1}, qd_{j-1}) is frozen at the
/// draw d = 0: tau(d) = M (N d + w) / dt + b_0, lambda = J_b^-T tau_b. A draw whose
/// linearized slack is below minus a tenth of that row's range over the draw box (plus the
/// QP's tolerance) is rejected before its dynamics. The bias moves with d only through the
/// Coriolis terms, by O(|qd| dt) of the range (under 1e-2 of it in the walks measured), so
/// such a draw fails the exact test too: the children are the same as without the prefilter,
/// which test_reach_biped checks draw by draw.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>

#include "reach_trajopt/contact/contact_constraint.h"
#include "reach_trajopt/qp/dual_active_set_qp.h"
#include "reach_trajopt/qp/hessian_factor.h"
#include "reach_trajopt/reach/reach_context.h"

namespace reach_trajopt {

/// @brief Per-thread solver of the backward step (17)-(20). Sized once; no heap allocation in
/// setParent() / child().
class BackwardStep {
 public:
  explicit BackwardStep(const ReachContext& context);

  /// Prepares the children of x_j = (q, qd). False when none can be feasible (q_{j-1} outside
  /// the position limits, or a rank-deficient contact Jacobian).
  bool setParent(const Eigen::Ref<const Eigen::VectorXd>& q,
                 const Eigen::Ref<const Eigen::VectorXd>& qd);

  /// Per-coordinate bound dt a_max of the draws d (size n_q).
  const Eigen::VectorXd& drawBound() const { return d_max_; }

  /// Builds the child for the draw d (size n_q, |d_i| <= dt a_max_i). On success fills
  /// x_{j-1} = (q_prev, qd_prev), its output, and the recorded (u, lambda); false when the
  /// state limits, the ground or (19) reject it.
  bool child(const Eigen::Ref<const Eigen::VectorXd>& d, Eigen::Ref<Eigen::VectorXd> q_prev,
             Eigen::Ref<Eigen::VectorXd> qd_prev, Eigen::Ref<Eigen::VectorXd> y,
             Eigen::Ref<Eigen::VectorXd> y_rate, Eigen::Ref<Eigen::VectorXd> u_out,
             Eigen::Ref<Eigen::VectorXd> lambda_out);

  long qpCount() const { return qp_count_; }
  /// Draws rejected by the prefilter, before their dynamics (not counted in qpCount()).
  long prefilterRejects() const { return prefilter_rejects_; }

 private:
  /// (19) when lambda is unique: true when it passes the cone and torque rows.
  bool uniqueLambdaFeasible();
  /// The affine slack model of the prefilter at the current parent (unique lambda only).
  void buildPrefilter();

  const ReachContext& ctx_;
  Workspace ws_;
  int n_, nu_, m_, m_eq_, rows_;
  Eigen::VectorXd q_prev_, qd_j_, b_, qdd_, v_, w_, d_max_, e_, jphi_d_;
  Eigen::MatrixXd M_, Jc_, Jphi_, MinvJt_, Lambda_, Jbar_, J_, A_eq_, A_in_;
  Eigen::VectorXd b_eq_, b_in_, g_, tau_;
  Eigen::LLT<Eigen::MatrixXd> llt_m_;  ///< of M (symmetric positive definite)
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_c_, lu_b_;
  Eigen::VectorXd lambda_, slack_, row_norm_;
  bool unique_lambda_ = false;  ///< the base rows fix lambda at this parent
  ContactConstraintTerms terms_;
  ContactWrenchCone::Matrix cone_world_[2];
  qp::HessianFactor factor_;
  qp::DualActiveSetQp qp_;
  std::vector<int> warm_;
  bool parent_ok_ = false;
  /// A parent's later children reuse the QP's check of its matrices (A_eq_, A_in_).
  qp::MatricesSinceRefill qp_matrices_;
  long qp_count_ = 0;
  // Prefilter: slack(d) ~ slack_0 + slack_d d; rejected below -prefilter_margin.
  bool prefilter_ = false;  ///< the model is valid at this parent
  Eigen::MatrixXd T_, lambda_d_, slack_d_;
  Eigen::MatrixXd lambda_inv_jphi_;  ///< Lambda^-1 J_phi (m x n)
  Eigen::VectorXd qd_center_, tau_center_, slack_0_, prefilter_margin_, slack_lin_;
  long prefilter_rejects_ = 0;
};

}  // namespace reach_trajopt
