#pragma once
/// \file witness_path.h
/// The witness of a reachability check: a state path from x_0 with the torques and wrenches of
/// every 1 ms step and the largest violation of eq. (1), (5), (8), the limits and the ground
/// along it. The reachability check's witness (witness_certificate.h) is x_0 -> a through the
/// forward set, then the QP-controlled segment of junction_bridge.h from a to x(t_f), for a
/// forward / backward pair (a, b) of one slice: no jump, x(t_f) within its terminal gaps of
/// x_f. A path may also hold a jump (junction >= 0, e.g. x_0 -> a | b -> x_f through the two
/// sets' chains), which measurePath skips and which is never certified.

#include <Eigen/Core>
#include <utility>
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
  double ground = 0.0;            ///< max depth of the swing sole below the ground [m]
  double leg_clearance = 0.0;     ///< max of leg_margin - the legs' distance [m]
  double max() const;
  /// Largest of the families that have no tolerance of their own (all but contact and
  /// contact_velocity).
  double maxWithoutContact() const;
};

/// A state path from x_0 through a forward/backward pair (a, b) (see the file comment).
struct WitnessPath {
  bool valid = false;
  /// Bridged, every step within the certificate's tolerances, x(t_f) within the terminal
  /// gaps of x_f: a checked path x_0 -> x_f (ReachResult::reachable rests on this alone).
  bool certified = false;
  std::vector<double> time;  ///< t - t_0 of each state [s] (a and b share a time)
  Eigen::MatrixXd q, qd;     ///< n_q x L
  /// Step k (state k -> k+1): torques and wrenches (n_u x (L-1), 6 n_c x (L-1)); the junction
  /// step a -> b (index `junction`) has none (zeros).
  Eigen::MatrixXd u, lambda;
  /// Step k evaluates eq. (1) at state k with qdd = (qd_{k+1} - qd_k) / dt; forward steps use
  /// the configured forward integrator, backward ones the semi-implicit step.
  std::vector<char> semi_implicit_step;
  /// Unbridged: index of a (the last forward state), b is junction + 1, and the step a -> b
  /// is a jump. Bridged: -1 (every step is a step of the dynamics).
  int junction = -1;
  int bridge_start = -1;      ///< bridged: index of a, the bridge's states follow; else -1
  Eigen::MatrixXd output;     ///< n_y x L swing sole outputs [m]
  double output_gap = 0.0;    ///< |y(a) - y(b)| of the pair [m]
  double position_gap = 0.0;  ///< |q_a - q_b|_inf of the pair [m, rad]
  double velocity_gap = 0.0;  ///< |qd_a - qd_b|_inf of the pair [m/s, rad/s]
  /// Where the path ends against x_f: |q(t_f) - q_f|_inf [m, rad], |qd(t_f) - qd_f|_inf
  /// [m/s, rad/s] and |y(t_f) - y(x_f)| [m], the distance by which the swing sole missed the
  /// target (0 for an unbridged path, which ends on x_f; inf for a bridge that stopped early).
  double terminal_position_gap = 0.0, terminal_velocity_gap = 0.0, terminal_output_gap = 0.0;
  int candidates_tried = 0;  ///< junction pairs bridged before this one was kept
  PathViolation violation;   ///< over every state and every step except an unbridged junction
};

/// (slice, sample) from sample `index` of slice `slice` through its parents to the root
/// (slice 0): for a forward set the path backwards in time, for a backward set forwards.
std::vector<std::pair<int, int>> chainToRoot(const std::vector<SampleSlice>& slices, int slice,
                                             int index);

/// Largest violations of a path's states and steps (see PathViolation), into w.violation.
void measurePath(const ReachContext& ctx, WitnessPath& w);

}  // namespace reach_trajopt
