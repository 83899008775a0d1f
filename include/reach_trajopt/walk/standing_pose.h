#pragma once
/// \file standing_pose.h
/// A symmetric standing configuration: knees bent by `knee_bend`, the hip and ankle pitch
/// compensating so the soles are flat, the pelvis upright, and the base height chosen so both
/// soles rest on the ground z = 0. The starting state of every walking run.

#include <Eigen/Core>
#include <string>

#include "reach_trajopt/model/robot_model.h"

namespace reach_trajopt {

/// Names of the leg joints a standing pose sets, per side ("l_"/"r_" prefixes in our URDF).
struct LegJointNames {
  std::string hip_pitch = "hip_pitch", knee = "knee", ankle_pitch = "ankle_pitch";
  std::string left_prefix = "l_", right_prefix = "r_";
};

/// \param knee_bend  knee angle [rad] (> 0 bends); hip and ankle pitch take -knee_bend/2.
/// \param sole_frame a sole frame whose height sets the base height (the soles are level).
/// \throws ReachError when a joint or frame is unknown or the model has no floating base.
Eigen::VectorXd standingConfiguration(const RobotModel& model, double knee_bend,
                                      const std::string& sole_frame = "l_sole",
                                      const LegJointNames& names = {});

}  // namespace reach_trajopt
