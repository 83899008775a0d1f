#pragma once
/// \file transition_tracking.h
/// The swing references of the whole-body controller from an OCP trajectory (eq. 22-23): at
/// time t after the trajectory's start, the swing sole's pose, velocity and acceleration at
/// the nearest knot (from the trajectory's q, qd, qdd through the model) and the joint
/// trajectory as posture feed-forward. Over the trajectory's last TouchdownAim::blend seconds
/// the sole's reference sinks (minimum jerk) to TouchdownAim::depth below the trajectory's
/// landing, so that the sole lands by contact on time as the interpolated swing's does (the
/// OCP lands the sole on the ground with the tracking lag left over: late). Past the horizon
/// without touchdown the sole keeps descending at 0.2 m/s and the feed-forward stops.

#include "reach_trajopt/control/whole_body_controller.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/ocp/transition_result.h"

namespace reach_trajopt {

/// Where a tracked OCP swing aims its sole at the end (WalkConfig::touchdown_depth,
/// WalkConfig::ocp_touchdown_blend).
struct TouchdownAim {
  double depth = 0.0;  ///< below the trajectory's landing at its end [m], >= 0
  double blend = 0.0;  ///< the last part of the trajectory that lowers the sole [s]; 0: none
};

/// Fills the swing and feed-forward fields of `ref` from `trajectory` at `t` [s] after its
/// start. \param swing  the swing sole's frame; `ws` a workspace of `model` and `J` a 6 x n_q
/// buffer, both overwritten (the caller keeps them: this runs at every controller tick).
void trackTransition(const RobotModel& model, Workspace& ws, Matrix6Xd& J, FrameId swing,
                     const TransitionResult& trajectory, double t, const TouchdownAim& aim,
                     WbcReference& ref);

}  // namespace reach_trajopt
