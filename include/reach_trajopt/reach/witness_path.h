#pragma once
/// \file witness_path.h
/// The witness of a reachability check: the state path x_0 -> a | b -> x_f through the closest
/// forward / backward pair (a, b) of the deciding slice, traced through parent indices, with
/// the torques and wrenches of every step, the gaps at the junction a | b and the largest
/// violation of eq. (1), (5), (8) and the limits along it.

#include <Eigen/Core>
#include <vector>

#include "reach_trajopt/reach/reach_context.h"
#include "reach_trajopt/reach/sample_slice.h"
#include "reach_trajopt/reach/window_comparison.h"

namespace reach_trajopt {

/// Largest constraint violations along a path (all >= 0; 0 = satisfied).
struct PathViolation {
  double dynamics = 0.0;          ///< |M qdd + b - S^T u - J^T lambda|_inf of eq. (1) [N, Nm]
  double cone = 0.0;              ///< max(0, -min C R lambda) of eq. (8) [N]
  double torque = 0.0;            ///< max(0, |u| - u_max) [Nm]
  double position_limit = 0.0;    ///< [m, rad]
  double velocity_limit = 0.0;    ///< [m/s, rad/s]
  double contact = 0.0;           ///< max |phi| of the held soles (eq. 5) [m, rad]
  double contact_velocity = 0.0;  ///< max |J_phi qd| [m/s, rad/s]
  double integration = 0.0;       ///< max |q_{k+1} - (q_k + dt qd)| of the Euler steps [m, rad]
  double max() const;
};

/// A state path x_0 -> a | b -> x_f through the closest forward/backward pair (a, b).
struct WitnessPath {
  bool valid = false;
  std::vector<double> time;  ///< t - t_0 of each state [s] (a and b share a time)
  Eigen::MatrixXd q, qd;     ///< n_q x L
  /// Step k (state k -> k+1): torques and wrenches (n_u x (L-1), 6 n_c x (L-1)); the junction
  /// step a -> b (index `junction`) has none (zeros).
  Eigen::MatrixXd u, lambda;
  /// Step k evaluates eq. (1) at state k with qdd = (qd_{k+1} - qd_k) / dt; forward steps use
  /// the configured forward integrator, backward ones the semi-implicit step.
  std::vector<char> semi_implicit_step;
  int junction = -1;          ///< index of a (the last forward state); b is junction + 1
  Eigen::MatrixXd output;     ///< n_y x L swing sole outputs [m]
  double output_gap = 0.0;    ///< |y(a) - y(b)| [m]
  double position_gap = 0.0;  ///< |q_a - q_b|_inf [m, rad]
  double velocity_gap = 0.0;  ///< |qd_a - qd_b|_inf [m/s, rad/s]
  PathViolation violation;    ///< over every state and every step except the junction
};

/// Traces the witness of `comparison` (its closest pair) through the two sets and measures it.
/// \param semi_implicit  the forward integrator of the forward set
WitnessPath buildWitnessPath(const ReachContext& ctx, const std::vector<SampleSlice>& forward,
                             const std::vector<SampleSlice>& backward,
                             const SliceComparison& comparison, bool semi_implicit);

/// Largest violations of a path's states and steps (see PathViolation), into w.violation.
void measurePath(const ReachContext& ctx, WitnessPath& w);

}  // namespace reach_trajopt
