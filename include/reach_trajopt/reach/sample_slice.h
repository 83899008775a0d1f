#pragma once
/// \file sample_slice.h
/// The samples of one time slice of a forward (16) or backward (20) reachable set, stored
/// column-wise. To bound memory, a sample keeps its velocity, output and recorded (u, lambda)
/// but not its configuration: q is exact from its parent's (q_s = q_p + dt qd_s forward with
/// the semi-implicit step, q_p + dt qd_p with the explicit one, q_p - dt qd_p backward), and
/// only the kept samples (the boundary samples (21) plus a few interior ones), the parents of
/// the next slice, keep q.
///
/// What (u, lambda) mean: for a forward sample s with parent p they act at x_p during the
/// step p -> s, with qdd = (qd_s - qd_p) / dt; for a backward sample s with parent p (one step
/// later in time) they act at x_s during the step s -> p, with qdd = (qd_p - qd_s) / dt. Either
/// way M qdd + b = S^T u + sum_i J_i^T lambda_i (eq. 1) at the evaluation state, lambda_i in
/// world orientation at the sole centre, contacts in the order left, right of the mode.

#include <Eigen/Core>
#include <vector>

namespace reach_trajopt {

/// Samples of one slice of a reachable set.
struct SampleSlice {
  double time = 0.0;  ///< t - t_0 [s]
  int size() const { return static_cast<int>(parent.size()); }
  std::vector<int> parent;      ///< sample index in the previous slice (-1 for x_0 / x_f)
  Eigen::MatrixXd output;       ///< y of each sample (n_y x size) [m]
  Eigen::MatrixXd output_rate;  ///< dy/dt (n_y x size) [m/s]
  Eigen::MatrixXd qd;           ///< velocities (n_q x size)
  Eigen::MatrixXd u;            ///< recorded torques (n_u x size; zeros for the root)
  Eigen::MatrixXd lambda;       ///< recorded contact wrenches (6 n_c x size; zeros for the root)
  std::vector<int> boundary;    ///< samples on the boundary by rule (21), ascending
  /// Samples propagated to the next slice: the boundary plus `interior_samples` evenly spread
  /// interior ones (they fill the later slices' interiors), ascending.
  std::vector<int> kept;
  Eigen::MatrixXd q_kept;  ///< configuration of each kept sample (n_q x kept.size())
  /// Column of q_kept holding a sample's q, or -1 (size() entries).
  std::vector<int> kept_column;
};

/// q of a forward child (16): q_p + dt qd_s (semi-implicit) or q_p + dt qd_p (explicit).
/// One function for the step and for the reconstruction, so both give the same bits.
inline void forwardConfiguration(const Eigen::Ref<const Eigen::VectorXd>& q_p,
                                 const Eigen::Ref<const Eigen::VectorXd>& qd_p,
                                 const Eigen::Ref<const Eigen::VectorXd>& qd_s, double dt,
                                 bool semi_implicit, Eigen::Ref<Eigen::VectorXd> q_s) {
  if (semi_implicit)
    q_s = q_p + dt * qd_s;
  else
    q_s = q_p + dt * qd_p;
}

/// q of a backward child (20): q_p - dt qd_p.
inline void backwardConfiguration(const Eigen::Ref<const Eigen::VectorXd>& q_p,
                                  const Eigen::Ref<const Eigen::VectorXd>& qd_p, double dt,
                                  Eigen::Ref<Eigen::VectorXd> q_s) {
  q_s = q_p - dt * qd_p;
}

}  // namespace reach_trajopt
