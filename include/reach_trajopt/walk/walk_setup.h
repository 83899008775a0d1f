#pragma once
/// \file walk_setup.h
/// Every configuration of a walking run, read from one robot config file (config/biped.yaml):
/// its sections contact and planner (required), walk, wbc, sim (optional: defaults) and those
/// of the footstep pipeline (kinematic_feasibility, reach, ocp, nearest_foothold; optional).
/// The tools and nodes that walk read it here, once; the robot, contact and pipeline sections
/// through FootstepPlannerSetup (step/footstep_planner_setup.h), as the tools that plan a step.

#include <memory>
#include <string>

#include "reach_trajopt/walk/walking_experiment.h"

namespace reach_trajopt {

class YamlSection;

/// @brief The configs of one walking run and the experiment they build.
struct WalkSetup {
  RobotConfig robot;  ///< section robot: (optional: the biped)
  WalkConfig walk;
  TvrConfig tvr;
  ContactConfig contact;
  WbcConfig wbc;
  SimConfig sim;
  FootstepPlannerConfig footsteps;  ///< the check, the nearest foothold search and the OCP

  /// \throws ConfigError naming the file, section and key of a bad or missing value.
  static WalkSetup fromYaml(const YamlSection& root);
  static WalkSetup fromYamlFile(const std::string& path);
  /// The experiment on `robot`, or on the URDF `urdf_override` when not empty (a tool's
  /// --urdf; the locked joints and leg roles stay robot's). Validates every config.
  std::unique_ptr<WalkingExperiment> experiment(const std::string& urdf_override = "") const;
};

}  // namespace reach_trajopt
