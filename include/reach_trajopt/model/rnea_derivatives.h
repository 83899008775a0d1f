#pragma once
/// \file rnea_derivatives.h
/// Analytic partial derivatives of inverse dynamics, tau = ID(q, qd, qdd) = M(q) qdd + b(q, qd)
/// of eq. (1), with respect to q and qd: the derivatives of the recursive Newton-Euler algorithm
/// of Carpentier and Mansard ("Analytical derivatives of rigid body dynamics algorithms", RSS
/// 2018), written for RobotModel's tree of one-degree-of-freedom bodies (model_tree.h).
///
/// Everything is expressed in the world frame, as spatial vectors at the world origin
/// (Featherstone's Plucker coordinates, internally [angular; linear]): S_i the motion subspace of
/// joint i (revolute: [a; p x a], a the world axis through the point p; prismatic: [0; a]),
/// v_i, a_i the spatial velocity and acceleration of body i (a_0 = [0; -g], gravity as a base
/// acceleration), I_i its spatial inertia, f_i = I_i a_i + v_i x* I_i v_i the net force on it,
/// F_j = sum over the subtree of j of f_i, and tau_j = S_j^T F_j. With lambda(k) the parent of
/// body k, k <= j meaning "k is j or one of its ancestors", and
///   u_k = S_k x v_lambda(k),   c_k = -S_k x a_lambda(k) + u_k x v_lambda(k),
///   B_i = (v_i x*) I_i + (I_i v_i) xbar* - I_i (v_i x)     ((h xbar*) m := m x* h),
///   Isub_j, Bsub_j: the sums of I_i, B_i over the subtree of j,
/// moving q_k displaces the subtree of k rigidly about joint k, which gives (the terms
/// S_k x* F_j of dS_j/dq_k and dF_j/dq_k cancel in tau_j):
///   k <= j:  d tau_j / d q_k  = S_j^T (Isub_j c_k - Bsub_j u_k)
///   j < k:   d tau_j / d q_k  = S_j^T (S_k x* F_k + Isub_k c_k - Bsub_k u_k)
///   k <= j:  d tau_j / d qd_k = S_j^T (Bsub_j S_k - 2 Isub_j u_k)
///   j < k:   d tau_j / d qd_k = S_j^T (Bsub_k S_k - 2 Isub_k u_k)
/// and zero when j and k are on different branches. The cost is one forward pass, one backward
/// pass (composite Isub, Bsub, F) and two 6-vector dot products per pair (j, k) on one support
/// path: O(n d) for n bodies of depth d. d tau / d qdd = M(q) (RobotModel::massMatrix).
///
/// Coordinates and units are RobotModel's: q, qd, qdd of size n_q [m, rad; m/s, rad/s;
/// m/s^2, rad/s^2], tau [N, N m], floating-base coordinates x, y, z, yaw, pitch, roll treated as
/// the six one-dof joints they are. Checked against central finite differences of
/// RobotModel::inverseDynamics (test/unit/test_rnea_derivatives.cpp) and against Pinocchio's
/// computeRNEADerivatives on robots of example-robot-data (test/oracle/test_rnea_derivatives.py).

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "reach_trajopt/model/robot_model.h"

namespace reach_trajopt {

/// d tau / d q and d tau / d qd of inverse dynamics (see file comment). Immutable after
/// construction; each thread passes its own Data.
class RneaDerivatives {
 public:
  using Matrix6d = Eigen::Matrix<double, 6, 6>;

  explicit RneaDerivatives(std::shared_ptr<const RobotModel> model);

  /// Per-thread scratch: world-frame spatial quantities of every body, sized once.
  struct Data {
    explicit Data(const RobotModel& model);
    template <typename T>
    using Vec = std::vector<T, Eigen::aligned_allocator<T>>;
    Vec<Vector6d> S, v, a, F, u, c;
    Vec<Matrix6d> Isub, Bsub;
    Vec<Eigen::Matrix3d> R_world;
    Vec<Eigen::Vector3d> p_world;
  };

  /// Inverse dynamics and its derivatives at (q, qd, qdd). Allocates nothing.
  /// \param[out] tau      M qdd + b, size n_q (equal to RobotModel::inverseDynamics up to
  ///                      roundoff)
  /// \param[out] dtau_dq  n_q x n_q, column k = d tau / d q_k
  /// \param[out] dtau_dqd n_q x n_q, column k = d tau / d qd_k
  /// \throws ReachError on wrong sizes or non-finite inputs.
  void compute(Data& d, const Eigen::Ref<const Eigen::VectorXd>& q,
               const Eigen::Ref<const Eigen::VectorXd>& qd,
               const Eigen::Ref<const Eigen::VectorXd>& qdd, Eigen::Ref<Eigen::VectorXd> tau,
               Eigen::Ref<Eigen::MatrixXd> dtau_dq, Eigen::Ref<Eigen::MatrixXd> dtau_dqd) const;

  const RobotModel& model() const { return *model_; }

 private:
  std::shared_ptr<const RobotModel> model_;
};

}  // namespace reach_trajopt
