/// \file walk_setup.cpp
/// A walking run's configs from one config file (see the header).

#include "reach_trajopt/walk/walk_setup.h"

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/step/footstep_planner_setup.h"

namespace reach_trajopt {

WalkSetup WalkSetup::fromYaml(const YamlSection& root) {
  WalkSetup s;
  // The robot, contact: and the step planner's sections as every tool reads them.
  const FootstepPlannerSetup planner = FootstepPlannerSetup::fromYaml(root);
  s.robot = planner.robot;
  s.contact = planner.contact;
  s.footsteps = planner.planner;
  if (root.has("walk")) s.walk = WalkConfig::fromYaml(root.section("walk"));
  s.tvr = TvrConfig::fromYaml(root.section("planner"));
  if (root.has("wbc")) s.wbc = WbcConfig::fromYaml(root.section("wbc"));
  if (root.has("sim")) s.sim = SimConfig::fromYaml(root.section("sim"));
  return s;
}

WalkSetup WalkSetup::fromYamlFile(const std::string& path) {
  return fromYaml(YamlSection::loadFile(path));
}

std::unique_ptr<WalkingExperiment> WalkSetup::experiment(const std::string& urdf_override) const {
  RobotConfig r = robot;
  if (!urdf_override.empty()) r.urdf = urdf_override;
  return std::make_unique<WalkingExperiment>(r, walk, tvr, contact, wbc, sim, &footsteps);
}

}  // namespace reach_trajopt
