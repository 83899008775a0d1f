#pragma once
/// \file transition_tracking.h
/// The swing references of the whole-body controller from an OCP trajectory (eq. 22-23): at
/// time t after the trajectory's start, the swing sole's pose, velocity and acceleration at
/// the nearest knot (from the trajectory's q, qd, qdd through the model) and the joint
/// trajectory as posture feed-forward. Past the horizon without touchdown the sole keeps
/// descending at 0.2 m/s and the feed-forward stops.

#include "reach_trajopt/control/whole_body_controller.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/ocp/transition_result.h"

namespace reach_trajopt {

/// Fills the swing and feed-forward fields of `ref` from `trajectory` at `t` [s] after its
/// start. \param swing  the swing sole's frame; `ws` a workspace of `model` and `J` a 6 x n_q
/// buffer, both overwritten (the caller keeps them: this runs at every controller tick).
void trackTransition(const RobotModel& model, Workspace& ws, Matrix6Xd& J, FrameId swing,
                     const TransitionResult& trajectory, double t, WbcReference& ref);

}  // namespace reach_trajopt
