#pragma once
/// \file transition_result.h
/// Output of the transition OCP (eq. 22-23): the trajectory sampled at the controller rate,
/// the largest constraint violation per family (re-evaluated at every output sample) and the
/// solver status mapped to converged / relaxed / failed with a reason.

#include <Eigen/Core>
#include <string>

#include "reach_trajopt/common/enum_names.h"

namespace reach_trajopt {

/// Outcome of a transition OCP.
enum class OcpStatus {
  kConverged,  ///< strict problem solved: ends at x_f, all constraints within tolerance
  kRelaxed,    ///< relaxed problem solved: lands at swing_target + eps, flagged
  kFailed,     ///< no acceptable trajectory; `reason` says why (the trajectory is diagnostic)
};
/// "converged", "relaxed", "failed" (names at the edges: messages, JSON, CSV).
const EnumNames<OcpStatus>& ocpStatusNames();
inline const char* ocpStatusName(OcpStatus s) { return nameOf(ocpStatusNames(), s); }

/// Largest violation per constraint family over all output samples (0 when satisfied).
/// Units: dynamics residual of eq. (1) divided by the effort limit (actuated rows) or by the
/// robot weight m g (floating-base rows), dimensionless; contacts in m and rad (phi), m/s and
/// rad/s (phidot), m/s^2 and rad/s^2 (phiddot); cones as min(C lambda) / (m g), dimensionless;
/// torque bounds as (|u| - u_max) / u_max; joint limits in rad (or m); hulls in m; boundary
/// states as max |x - x_ref| (mixed m, rad, m/s, rad/s).
struct ConstraintViolations {
  double dynamics = 0.0;         ///< eq. (1)
  double stance_contact = 0.0;   ///< eq. (5) for the stance sole: max of |phi|, |phidot|, |phiddot|
  double stance_cone = 0.0;      ///< eq. (8), stance sole, every sample
  double new_contact = 0.0;      ///< phi_2 (or phi_2 - eps), phidot_2, phiddot_2 at t_f
  double new_cone = 0.0;         ///< eq. (8), new contact at t_f
  double torque = 0.0;           ///< |u| <= u_max
  double joint_limits = 0.0;     ///< q within its position limits
  double velocity_limits = 0.0;  ///< (|qd| - qd_max) / qd_max, reported (not constrained)
  double reachable_set = 0.0;    ///< A y - b of each slice at its time [m]
  double leg_clearance = 0.0;    ///< margin - the legs' capsules' distance (leg_clearance.h) [m]
  double initial_state = 0.0;    ///< |x(t_0) - x_0|
  double final_state = 0.0;      ///< |x(t_f) - x_f| (strict only; 0 when relaxed)
  /// Largest of the families that must hold (all but velocity_limits).
  double max() const;
};

/// The transition trajectory and its diagnostics.
struct TransitionResult {
  OcpStatus status = OcpStatus::kFailed;
  std::string reason;        ///< why failed (or notes); empty when converged cleanly
  std::string nlopt_status;  ///< NLopt's last return code, e.g. "FTOL_REACHED"
  bool relaxed = false;      ///< the relaxed problem produced this trajectory
  Eigen::Vector2d eps = Eigen::Vector2d::Zero();  ///< landing offset (eps_x, eps_y) [m]
  Eigen::Vector3d landing_position = Eigen::Vector3d::Zero();  ///< swing sole at t_f [m]

  double dt = 0.001;           ///< sample spacing [s]
  Eigen::VectorXd time;        ///< N sample times since t_0 [s] (last = horizon)
  Eigen::MatrixXd q, qd, qdd;  ///< n_q x N [m, rad], [m/s, rad/s], [m/s^2, rad/s^2]
  Eigen::MatrixXd u;           ///< n_u x N joint torques [N m]
  Eigen::MatrixXd lambda;      ///< 12 x N contact wrenches [f; tau] world, [left; right] [N, N m]

  ConstraintViolations violation;  ///< re-evaluated at every sample
  double cost = 0.0;               ///< eq. (22) at the solution (the OCP's scaled form)
  int iterations = 0;              ///< objective evaluations over all solves
  int solves = 0;                  ///< SLSQP runs (refinements, strict + relaxed)
  int variables = 0;               ///< size of the last NLP
  int constraints = 0;             ///< rows of the last NLP (equalities + inequalities)
  double solve_time = 0.0;         ///< wall time [s]

  /// A path x_0 -> x_f that shows the target reachable: the strict problem converged and the
  /// joint velocities, reported but not constrained by the OCP, stay within their limits
  /// (relative excess <= `tolerance`).
  bool reachesTargetWithinLimits(double tolerance) const {
    return status == OcpStatus::kConverged && !relaxed && violation.velocity_limits <= tolerance;
  }
};

}  // namespace reach_trajopt
