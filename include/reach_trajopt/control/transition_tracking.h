#pragma once
/// \file transition_tracking.h
/// The swing references of the whole-body controller from an OCP trajectory (eq. 22-23): at
/// time t after the trajectory's start, the swing sole's pose, velocity and acceleration at
/// the nearest knot (from the trajectory's q, qd, qdd through the model) and the joint
/// trajectory as posture feed-forward. The sole's height reference is lowered by a
/// minimum-jerk blend to `touchdown_depth` below the trajectory's at its horizon (touchdown by
/// contact, as the interpolated swing's); past the horizon without touchdown the sole keeps
/// descending at kLateTouchdownDescentSpeed and the feed-forward stops.

#include "reach_trajopt/control/whole_body_controller.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/ocp/transition_result.h"

namespace reach_trajopt {

/// Fills the swing and feed-forward fields of `ref` from `trajectory` at `t` [s] after its
/// start, `touchdown_depth` [m] >= 0. \param swing  the swing sole's frame; `ws` a workspace of
/// `model` and `J` a 6 x n_q buffer, both overwritten (the caller keeps them: this runs at every
/// controller tick).
void trackTransition(const RobotModel& model, Workspace& ws, Matrix6Xd& J, FrameId swing,
                     const TransitionResult& trajectory, double t, double touchdown_depth,
                     WbcReference& ref);

}  // namespace reach_trajopt
