#pragma once
/// \file forward_step.h
/// One forward step of the reachable set, eq. (15)-(16): from a state x_j and a drawn torque u,
/// the QP
///   min |qdd|^2_Wqdd + |du|^2_Wu + sum_i |lambda_i|^2_Wl
///   s.t. M qdd + b = S^T (u + du) + J^T lambda          (eq. 1)
///        J_phi,i qdd = -Jdot_phi,i qd - beta (phi_i / dt^2 + 2 phidot_i / dt)   (eq. 5)
///        -u_max <= u + du <= u_max,   C_i R_i lambda_i >= 0   (eq. 7-8)
///        |qd + dt qdd| <= qd_max,     q_min <= q_{j+1} <= q_max
///        (bridge steps only) the swing sole above the ground one step ahead
/// then x_{j+1} = [q_j + dt qd_{j+1}; qd_j + dt qdd] (semi-implicit; or q_j + dt qd_j).
///
/// Solved in the reduced form: given u + du, the equality rows fix [qdd; lambda] uniquely
/// (K [qdd; lambda] = [S^T (u + du) - b; a_c] with K = [M, -J^T; J_phi, 0], invertible when
/// the contact Jacobian has full row rank), so [qdd; lambda] = P (u + du) + r0 and the QP is
/// over du alone (n_u variables, no equality rows). Everything that depends on the parent only
/// (M, b, J, the LU of K, P, the QP Hessian and its factorization, the inequality matrix) is
/// computed once in setParent() and shared by all its children; a child costs one QP solve,
/// warm-started from the previous child's active set. (Started cold, the forward stage was
/// 10-20 % faster, but the optimum's last digits, hence the samples, changed, and the proposed
/// forward walk fell in 3 of 8 seeds against none: bench/README.md, issue 16.)
///
/// The junction bridge of a witness path (junction_bridge.h) uses the same step to track a
/// target acceleration (trackChild), with the weights of a ForwardStepCost, the ground row,
/// and no rejection of children that leave the limits or the ground by rounding (the
/// certificate measures those).

#include <Eigen/Core>
#include <Eigen/LU>
#include <vector>

#include "reach_trajopt/contact/contact_constraint.h"
#include "reach_trajopt/qp/dual_active_set_qp.h"
#include "reach_trajopt/qp/hessian_factor.h"
#include "reach_trajopt/reach/reach_context.h"

namespace reach_trajopt {

/// Weights of the forward QP's cost (15) and the bridge mode.
struct ForwardStepCost {
  double w_qdd = 1e-4;     ///< on |qdd - qdd_target|^2 [per (rad/s^2)^2]
  double w_du = 1.0;       ///< on |du|^2 [per (N m)^2]
  double w_lambda = 1e-6;  ///< on |lambda|^2 [per N^2]
  /// Bridge step: the swing sole is kept above the ground by a QP row instead of rejecting
  /// the child, and children are not rejected for leaving the limits by rounding.
  bool bridge = false;
  /// The weights of ReachConfig (w_qdd, w_du, w_lambda): the sampling step (15).
  static ForwardStepCost sampling(const ReachConfig& config);
};

/// @brief Per-thread solver of the forward step (15)-(16). Sized once; no heap allocation in
/// setParent() / child().
class ForwardStep {
 public:
  /// The sampling step (15) with the weights of context.config.
  explicit ForwardStep(const ReachContext& context);
  ForwardStep(const ReachContext& context, const ForwardStepCost& cost);

  /// Evaluates the dynamics at the parent x_j = (q, qd). Returns false when no child can be
  /// feasible (explicit integrator with q + dt qd outside the limits, or a singular K).
  bool setParent(const Eigen::Ref<const Eigen::VectorXd>& q,
                 const Eigen::Ref<const Eigen::VectorXd>& qd);

  /// Solves (15) for the drawn torque u (size n_u). On success fills the child's q, qd, its
  /// output y / rate, and the recorded u + du, lambda, and returns true; false when the QP is
  /// infeasible or the child leaves the state constraints.
  bool child(const Eigen::Ref<const Eigen::VectorXd>& u, Eigen::Ref<Eigen::VectorXd> q_child,
             Eigen::Ref<Eigen::VectorXd> qd_child, Eigen::Ref<Eigen::VectorXd> y,
             Eigen::Ref<Eigen::VectorXd> y_rate, Eigen::Ref<Eigen::VectorXd> u_out,
             Eigen::Ref<Eigen::VectorXd> lambda_out);

  /// d qdd / d u at the parent (n_q x n_u), valid after a successful setParent().
  Eigen::Ref<const Eigen::MatrixXd> accelerationMap() const { return P_.topRows(n_); }
  /// A bridge step: the same QP with the cost |qdd - qdd_target|^2_Wqdd + |du|^2_Wu +
  /// |lambda|^2_Wl (qdd_target of size n_q), u the nominal torque du corrects.
  bool trackChild(const Eigen::Ref<const Eigen::VectorXd>& u,
                  const Eigen::Ref<const Eigen::VectorXd>& qdd_target,
                  Eigen::Ref<Eigen::VectorXd> q_child, Eigen::Ref<Eigen::VectorXd> qd_child,
                  Eigen::Ref<Eigen::VectorXd> y, Eigen::Ref<Eigen::VectorXd> y_rate,
                  Eigen::Ref<Eigen::VectorXd> u_out, Eigen::Ref<Eigen::VectorXd> lambda_out);

  Workspace& workspace() { return ws_; }
  long qpCount() const { return qp_count_; }

 private:
  /// setParent's K = [M, -J^T; J_phi, 0] and the contact rows' right-hand side r0 (eq. 5 with
  /// the drift stabilization), and each held sole's cone in the world; after update, M, b.
  void fillDynamicsAndContactRows();
  /// setParent's inequality rows in u (torque bounds, cones, velocity and position limits, the
  /// bridge's ground row); after P = d[qdd; lambda]/du is known.
  void fillInequalityRows();
  /// child() and trackChild() (target: [qdd_target; 0], or null for zero).
  bool solveChild(const Eigen::Ref<const Eigen::VectorXd>& u, const Eigen::VectorXd* target,
                  Eigen::Ref<Eigen::VectorXd> q_child, Eigen::Ref<Eigen::VectorXd> qd_child,
                  Eigen::Ref<Eigen::VectorXd> y, Eigen::Ref<Eigen::VectorXd> y_rate,
                  Eigen::Ref<Eigen::VectorXd> u_out, Eigen::Ref<Eigen::VectorXd> lambda_out);

  const ReachContext& ctx_;
  ForwardStepCost cost_;
  Workspace ws_;
  int n_, nu_, m_, rows_;
  Eigen::VectorXd q_, qd_;
  Eigen::MatrixXd M_, K_, E_, P_, PtW_, G_, A_in_, J_;
  Eigen::VectorXd b_, r0_, s_, g_, b_in_, z_, w_, target_;
  Eigen::RowVectorXd swing_jz_;  ///< z row of the swing sole's Jacobian (the ground row)
  double ground_rhs_ = 0.0;      ///< J_z qdd >= this keeps the swing sole above the ground
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  ContactConstraintTerms terms_;
  ContactWrenchCone::Matrix cone_world_[2];
  qp::HessianFactor factor_;
  qp::DualActiveSetQp qp_;
  Eigen::MatrixXd empty_eq_;
  Eigen::VectorXd empty_beq_;
  std::vector<int> warm_;
  bool parent_ok_ = false;
  /// A parent's later children reuse the QP's check of its matrices (A_eq_, A_in_).
  qp::MatricesSinceRefill qp_matrices_;
  long qp_count_ = 0;
};

}  // namespace reach_trajopt
