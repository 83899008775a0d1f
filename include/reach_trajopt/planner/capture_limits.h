#pragma once
/// \file capture_limits.h
/// The capture limits of the linear inverted pendulum (eq. 9) with a finite foot, minimum step
/// time and maximum step length (Koolen, de Boer, Rebula, Goswami, Pratt, "Capturability-based
/// analysis and control of legged locomotion, Part 1", IJRR 2012, Sec. 5): the largest CoM
/// speed [m/s] a push may give the robot, standing with its CoM above a sole, that it can still
/// stop with no step, one step, or any number of steps. They bound what any stepping strategy
/// can recover and are the yardstick of the push envelope (walk/push_envelope.h).
///
/// With omega = sqrt(g / h), the instantaneous capture point offset r = v / omega from the sole
/// centre. The CoP held on the sole's edge d_0 toward r during a swing of T_s, then a step of
/// at most l_max toward r: r is N-step capturable iff r <= d_N with
///   d_0 = the sole's extent toward r,   d_N = (d_{N-1} + l_max - d_0) e^{-omega T_s} + d_0,
///   d_inf = (d_0 + (l_max - d_0) e^{-omega T_s}) / (1 - e^{-omega T_s}),
/// and the speed limits v_N = omega d_N. In a direction theta (from +x, counter-clockwise; +y
/// the left), d_0 is the support function of the sole's rectangle, l_max that of the step
/// bounds (the TVR planner's heuristic bounds, planner/tvr_planner.h) with the leg on the side
/// of the push stepping, and the standing robot's 0-step limit adds the soles' lateral
/// separation to d_0 (both soles on the ground).

#include <vector>

namespace reach_trajopt {

struct TvrConfig;
struct ContactConfig;

/// The robot as the capture analysis sees it. Lengths [m], times [s].
struct CaptureModel {
  double com_height = 1.0;              ///< h of the LIPM (> 0)
  double gravity = 9.81;                ///< g (> 0)
  double min_swing_time = 0.22;         ///< T_s: the shortest swing (>= 0)
  double sole_half_length = 0.135;      ///< sole extent along its x (>= 0)
  double sole_half_width = 0.08;        ///< along its y (>= 0)
  double stance_half_separation = 0.0;  ///< each sole centre's lateral distance from the CoM
                                        ///< standing (0: one sole; >= 0)
  double step_forward_max = 0.42;       ///< largest step along +x from the stance sole (>= 0)
  double step_backward_max = 0.42;      ///< largest step along -x (>= 0)
  double step_lateral_max = 0.65;       ///< largest step toward the swing side (>= 0)

  /// \throws RequestError naming the bad field (non-finite, or out of the ranges above).
  void validate() const;
  /// From the LIPM and heuristic bounds of `tvr`, the sole of `contact` and the walk's swing
  /// time; stance_half_separation stays 0 (one sole).
  static CaptureModel fromConfigs(const TvrConfig& tvr, const ContactConfig& contact,
                                  double swing_time);
  double omega() const;  ///< sqrt(g / h) [1/s]
};

/// The capture limits in one direction [m/s].
struct CaptureLimits {
  double direction = 0.0;  ///< theta [rad] from +x
  double zero_step = 0.0;  ///< no step: the CoP alone (both soles when standing)
  double one_step = 0.0;   ///< one step
  double n_step = 0.0;     ///< any number of steps (the limit of N -> infinity)
};

/// d_N of the file comment [m]: the largest capture point offset from the stance sole centre
/// that `steps` steps can capture in direction `theta` [rad] (steps >= 0; one sole).
double captureRegionRadius(const CaptureModel& model, double theta, int steps);
/// The limits of direction `theta` [rad]. \throws RequestError for an invalid model.
CaptureLimits captureLimits(const CaptureModel& model, double theta);

}  // namespace reach_trajopt
