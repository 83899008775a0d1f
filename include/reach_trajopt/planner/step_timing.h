#pragma once
/// \file step_timing.h
/// Step-timing adaptation of the TVR step (eq. 11): the swing duration chosen at lift-off so
/// that the step eq. (11) asks for fits the foot offset bounds (Sec. IV-A) as far as timing
/// can make it fit. The idea is Khadiv, Herzog, Moosavian, Righetti, "Step timing adjustment:
/// a step toward generating robust gaits", Humanoids 2016 (and Khadiv et al., "Walking control
/// based on step timing adaptation", IEEE T-RO 2020): when the capture point runs away, a
/// shorter swing lands the foot before the step it needs grows past what the leg can take; when
/// the step would be too short (a lateral step that crosses the stance leg), a longer swing
/// lets the CoM carry on first. Here the foothold rule stays the TVR planner's: for a swing
/// duration T the CoM state is predicted to touchdown with the LIPM about the stance sole
/// (eq. 9-10) and eq. (11) gives the foothold a(T); T is the one in [T_min, T_max] (a grid of
/// `resolution`) whose a(T) lies closest to the bounds' rectangle (zero inside it); among equal
/// distances, the one nearest the nominal duration. A step that fits at the nominal duration
/// therefore keeps it: timing changes only steps the bounds would otherwise clip.

#include <Eigen/Core>

#include "reach_trajopt/contact/contact_mode.h"
#include "reach_trajopt/planner/lipm.h"

namespace reach_trajopt {

class TvrPlanner;

/// The swing-duration range of the adaptation [s].
struct StepTimingRange {
  double nominal = 0.22;      ///< the walk's single-support duration (> 0)
  double min = 0.22;          ///< shortest swing, <= nominal (> 0)
  double max = 0.22;          ///< longest swing, >= nominal
  double resolution = 0.005;  ///< grid of the search (> 0)
};

/// What the adaptation chose.
struct StepTiming {
  double swing_duration = 0.0;     ///< T [s]
  double bound_violation = 0.0;    ///< distance of a(T) to the bounds [m], 0: fits
  double nominal_violation = 0.0;  ///< the same at the nominal duration [m]
  Eigen::Vector2d foothold = Eigen::Vector2d::Zero();  ///< a(T), eq. (11) unbounded [m]
};

/// The adapted swing duration of one step (see the file comment), at lift-off: the measured
/// CoM state `com` at time `t` [s] of the run, the stance sole centre `stance` [m] (heading 0),
/// the sole that swings, and the walk's p_des of eq. (11) (x_start + forward_speed (t + T),
/// y_mid) [m, m/s]. The planner's bounds are used whatever TvrConfig::heuristic_bounds says.
/// \throws RequestError on a non-finite input or an invalid range.
StepTiming adaptStepTiming(const TvrPlanner& planner, const LipmState& com,
                           const Eigen::Vector2d& stance, Side swing, double t, double x_start,
                           double forward_speed, double y_mid, const StepTimingRange& range);

}  // namespace reach_trajopt
