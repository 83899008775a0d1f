#pragma once
/// \file standing_pose.h
/// A symmetric standing configuration: knees bent by `knee_bend`, the hip and ankle pitch
/// compensating so the soles are flat, hip yaw/roll and ankle roll at 0, every other joint at
/// 0 (or the nearest limit), the pelvis upright, and the base height chosen so the soles rest
/// on the ground z = 0. The starting state of every walking run.

#include <Eigen/Core>
#include <string>

#include "reach_trajopt/model/robot_config.h"
#include "reach_trajopt/model/robot_model.h"

namespace reach_trajopt {

/// \param knee_bend  knee angle [rad] (> 0 bends); hip and ankle pitch take -knee_bend/2.
/// \param sole_frame a sole frame whose height sets the base height (the soles are level).
/// \param robot      the leg joints by role (robot.left_knee, ...).
/// \throws ReachError when a joint or frame is unknown or the model has no floating base.
Eigen::VectorXd standingConfiguration(const RobotModel& model, double knee_bend,
                                      const std::string& sole_frame, const RobotConfig& robot);

}  // namespace reach_trajopt
