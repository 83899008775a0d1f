/// \file footstep_planner_setup.cpp
/// The step planner's configs from one config file (see the header).

#include "reach_trajopt/step/footstep_planner_setup.h"

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/model/robot_model.h"

namespace reach_trajopt {

FootstepPlannerSetup FootstepPlannerSetup::fromYaml(const YamlSection& root) {
  FootstepPlannerSetup s;
  s.robot = RobotConfig::fromConfigFile(root);
  s.contact = ContactConfig::fromYaml(root.section("contact"));
  s.planner = FootstepPlannerConfig::fromYaml(root);
  return s;
}

FootstepPlannerSetup FootstepPlannerSetup::fromYamlFile(const std::string& path) {
  return fromYaml(YamlSection::loadFile(path));
}

std::shared_ptr<const RobotModel> FootstepPlannerSetup::loadModel(
    const std::string& urdf_override) const {
  return robot.loadModel(urdf_override);
}

}  // namespace reach_trajopt
