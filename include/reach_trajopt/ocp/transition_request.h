#pragma once
/// \file transition_request.h
/// Input of the transition OCP (eq. 22-23): one contact transition from single support (SS-L
/// or SS-R) at x_0 to double support at x_f, the reachable-set slices that constrain the swing
/// sole, and an optional seed path (the reachability witness). These are small plain structs of
/// their own so the OCP does not depend on the reachability engine's headers.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <vector>

#include "reach_trajopt/contact/contact_mode.h"

namespace reach_trajopt {

/// One time slice of the swing sole's reachable output set: the 2-D convex hull
/// {y = (x, y) of the swing sole centre in the world [m] : A y <= b}.
struct ReachableSlice {
  double time = 0.0;   ///< since t_0 [s], in [0, horizon]
  Eigen::MatrixX2d A;  ///< m x 2 half-space normals (need not be normalized)
  Eigen::VectorXd b;   ///< m offsets [m times |row of A|]
};

/// A state path to warm-start from (e.g. the reachability witness x_0 -> x_f, one column per
/// 1 ms). Only q is used: its actuated part is least-squares fitted onto the spline basis.
struct SeedPath {
  Eigen::VectorXd time;  ///< N sample times since t_0 [s], within [0, horizon]
  Eigen::MatrixXd q;     ///< n_q x N configurations [m, rad]
  bool empty() const { return time.size() == 0; }
};

/// How to treat the final state.
enum class RelaxationMode {
  kStrict,   ///< x(t_f) = x_f and phi_2 = 0 (eq. 22-23 as written)
  kRelaxed,  ///< drop x(t_f) = x_f; phi_2 - eps = 0, eps = [eps_x, eps_y, 0, 0, 0, 0]
  kAuto,     ///< strict first; if it fails, relaxed
};

/// Upper bound of TransitionRequest::horizon [s] (docs/limits.md): a swing lasts well under a
/// second; the OCP's evaluations grow with the horizon, so longer ones could not keep their
/// time limit.
constexpr double kMaxTransitionHorizon = 5.0;

/// One transition OCP request (eq. 22-23).
struct TransitionRequest {
  Side stance = Side::kLeft;  ///< current mode SS-<stance>; new mode DS at t_f
  Eigen::Isometry3d stance_pose = Eigen::Isometry3d::Identity();   ///< planned stance sole a_k
  Eigen::Isometry3d swing_target = Eigen::Isometry3d::Identity();  ///< new contact a_{k+1}
  double horizon = 0.0;                                            ///< t_f - t_0 [s]
  Eigen::VectorXd q0, qd0;             ///< x_0, size n_q each [m, rad; m/s, rad/s]
  Eigen::VectorXd qf, qdf;             ///< x_f (e.g. KinematicFeasibility's q_f, qd_f = 0)
  std::vector<ReachableSlice> slices;  ///< optional; empty: no reachable-set constraint
  SeedPath seed;                       ///< optional; empty: cubic Hermite x_0 -> x_f
  RelaxationMode relaxation = RelaxationMode::kAuto;
  /// Relaxed landing: the base's height above the mean sole height [m] (e.g. the walking
  /// robot's predicted pelvis height); NaN: TransitionOcpConfig::terminal_pelvis_height.
  double terminal_pelvis_height = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace reach_trajopt
