#pragma once
/// \file footstep_planner_setup.h
/// The configs of the step planner read from one config file (config/biped.yaml), the same way
/// for every tool and node that plans or checks a step (plan_transition, check_transition,
/// reach_check, verdict_grid, the foothold services, the walk's WalkSetup): section robot:
/// (optional: the biped), contact: (required: a robot's soles are not guessed), and the
/// pipeline's kinematic_feasibility:, reach:, ocp:, nearest_foothold: (each optional: defaults).

#include <memory>
#include <string>

#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/model/robot_config.h"
#include "reach_trajopt/step/footstep_transition_planner.h"

namespace reach_trajopt {

class RobotModel;
class YamlSection;

/// @brief The robot, its contacts and the step planner's stage configs of one config file.
struct FootstepPlannerSetup {
  RobotConfig robot;
  ContactConfig contact;
  FootstepPlannerConfig planner;

  /// \throws ConfigError naming the file and key of a bad value, or "<file>: contact: missing
  /// section" when the file has no contact: section.
  static FootstepPlannerSetup fromYaml(const YamlSection& root);
  /// The same from a file. \throws ReachError naming the file when it cannot be read.
  static FootstepPlannerSetup fromYamlFile(const std::string& path);
  /// The robot's model (robot.urdf, or `urdf_override` when not empty: a tool's --urdf; the
  /// locked joints stay the robot section's).
  std::shared_ptr<const RobotModel> loadModel(const std::string& urdf_override = "") const;
};

}  // namespace reach_trajopt
