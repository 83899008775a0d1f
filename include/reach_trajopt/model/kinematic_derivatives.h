#pragma once
/// \file kinematic_derivatives.h
/// Analytic first derivatives of a frame's kinematic terms in q and qd: its Jacobian J(q) (as
/// RobotModel::frameJacobian), its velocity J qd (frameVelocity) and its drift Jdot qd
/// (frameJdotQd), as directional derivatives along a change (dq, dqd) of the state.
///
/// Spatial vectors are world-frame Plucker coordinates at the world origin, [angular; linear]
/// (as in rnea_derivatives.h): S_j the motion subspace of joint j, V_j = sum_{k <= j} S_k qd_k
/// the velocity of body j and A_j = sum_{k < l <= j} qd_k qd_l S_k x S_l its velocity-product
/// acceleration (qdd = 0, no gravity), with k <= j meaning "k is j or one of its ancestors" and
/// x the motion cross product. Moving q_m turns the subtree of m about joint m:
///   d S_j / d q_m = S_m x S_j                                             (m < j), else 0,
/// (Pinocchio's kinematic Hessian, getJointKinematicHessian), so for a body b and m <= b:
///   d V_b / d q_m  = S_m x (V_b - V_m),                 d V_b / d qd_m = S_m,
///   d A_b / d q_m  = S_m x (A_b - A_m - V_m x (V_b - V_m)) + V_m x (S_m x (V_b - V_m)),
///   d A_b / d qd_m = S_m x (V_b - 2 V_m)
/// (the first from the Jacobi identity), and zero for m off b's support path. A frame at the
/// world point p of body b has, in RobotModel's convention (rows [linear; angular], linear
/// terms of the point p, world orientation):
///   J_j = [v_j + w_j x p; w_j] for S_j = [w_j; v_j],   velocity = [v + w x p; w] for V_b = [w; v],
///   drift = [a + alpha x p + w x (v + w x p); alpha]   for A_b = [alpha; a],
/// and dp = J_lin dq; the derivatives of these follow by the product rule. Along one direction
/// each costs O(d) for a frame at depth d (the dq-weighted sums of S_m over the support path
/// run once), so the derivatives along n directions cost O(n d) after one O(n_bodies) pass; the
/// same as matrices (one column per joint, frameMatrices) cost O(d), and the contraction
/// d(J^T lambda)/dq with a wrench lambda O(d^2):
///   d(J^T lambda)_j / d q_m = [m < j] (S_m x S_j) . F + w_j . (dp_m x f),
/// with lambda = [f; n] and F = [n + p x f; f] the wrench at the world origin.
/// Checked against central finite differences of RobotModel (test/unit/test_chain_derivatives.cpp).

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "reach_trajopt/model/robot_model.h"

namespace reach_trajopt {

/// Directional derivatives of a frame's J, J qd and Jdot qd (see file comment). Immutable after
/// construction; each thread passes its own Data.
class KinematicDerivatives {
 public:
  explicit KinematicDerivatives(std::shared_ptr<const RobotModel> model);

  /// Per-thread buffers: world-frame S, V, A and poses of every body, sized once.
  struct Data {
    explicit Data(const RobotModel& model);
    template <typename T>
    using Vec = std::vector<T, Eigen::aligned_allocator<T>>;
    Vec<Vector6d> S, V, A;
    Vec<Eigen::Matrix3d> R_world;
    Vec<Eigen::Vector3d> p_world;
    bool computed = false;
  };

  /// The forward pass at (q, qd): S_j, V_j, A_j of every body. Allocates nothing; throws
  /// ReachError on wrong sizes or non-finite entries.
  void compute(Data& d, const Eigen::Ref<const Eigen::VectorXd>& q,
               const Eigen::Ref<const Eigen::VectorXd>& qd) const;

  /// Along (dq, dqd) (size n_q each) at the state of the last compute():
  ///   dJ        = sum_m dq_m dJ/dq_m                  (6 x n_q; skipped when null),
  ///   dvelocity = d(J qd)    = dJ qd + J dqd          (skipped when null),
  ///   ddrift    = d(Jdot qd) = d/dq (Jdot qd) dq + d/dqd (Jdot qd) dqd   (skipped when null),
  /// rows [linear; angular] as RobotModel's frame terms. Allocates nothing.
  void frameDerivatives(const Data& d, FrameId frame, const Eigen::Ref<const Eigen::VectorXd>& dq,
                        const Eigen::Ref<const Eigen::VectorXd>& dqd, Matrix6Xd* dJ,
                        Vector6d* dvelocity, Vector6d* ddrift) const;

  /// A frame's derivatives as matrices, the columns the joints (non-zero only on the frame's
  /// support path), rows [linear; angular].
  struct FrameMatrices {
    explicit FrameMatrices(int nq);
    Matrix6Xd dJx_dq;              ///< d(J x)/dq at fixed x (the x given to frameMatrices)
    Matrix6Xd dvelocity_dq;        ///< d(J qd)/dq at fixed qd
    Matrix6Xd ddrift_dq;           ///< d(Jdot qd)/dq at fixed qd
    Matrix6Xd ddrift_dqd;          ///< d(Jdot qd)/dqd
    Eigen::MatrixXd dJTlambda_dq;  ///< n_q x n_q: d(J^T lambda)/dq at fixed lambda (if asked)
  };

  /// All of `out` at the state of the last compute(), for one x (size n_q) and, unless null,
  /// one lambda (a wrench [force; moment] on the frame: the rows of J^T lambda). Costs O(d) for
  /// the 6-row matrices and O(d^2) for dJTlambda_dq, d the frame's depth. Allocates nothing.
  void frameMatrices(const Data& d, FrameId frame, const Eigen::Ref<const Eigen::VectorXd>& x,
                     const Vector6d* lambda, FrameMatrices& out) const;

  const RobotModel& model() const { return *model_; }

 private:
  std::shared_ptr<const RobotModel> model_;
};

/// Directional derivative of the inverse left Jacobian of SO(3)
/// (ContactConstraint::inverseLeftJacobian): d/ds Jl^-1(e + s de) at s = 0, with
/// Jl^-1(e) = I - E/2 + c(theta) E^2, E = [e]x, theta = |e|, so
///   d Jl^-1 = -dE/2 + c'(theta) (e . de / theta) E^2 + c(theta) (dE E + E dE).
/// c as inverseLeftJacobian computes it; c'(theta) / theta by its series below theta = 1e-2,
/// where the closed form cancels.
Eigen::Matrix3d inverseLeftJacobianDerivative(const Eigen::Vector3d& e, const Eigen::Vector3d& de);

}  // namespace reach_trajopt
