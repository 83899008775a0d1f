#include "reach_trajopt/ros/node_setup.h"

#include <ros/package.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/step/footstep_planner_setup.h"
#include "reach_trajopt/walk/standing_pose.h"
#include "reach_trajopt/walk/walking_experiment.h"

namespace reach_trajopt {
namespace ros_bridge {

std::string robotDescription(const ros::NodeHandle& nh) {
  std::string urdf;
  if (!nh.getParam("robot_description", urdf) || urdf.empty())
    throw ConfigError("parameter 'robot_description' (URDF text) is not set");
  return urdf;
}

std::string configPath(const ros::NodeHandle& pnh) {
  std::string path;
  if (!pnh.getParam("config", path))
    path = ros::package::getPath("reach_trajopt") + "/config/biped.yaml";
  return path;
}

TempUrdf::TempUrdf(const std::string& xml) {
  char name[] = "/tmp/reach_trajopt_urdf_XXXXXX";
  const int fd = mkstemp(name);
  if (fd < 0) throw ReachError("cannot create a temporary URDF file");
  close(fd);
  path_ = name;
  std::ofstream out(path_);
  out << xml;
  if (!out) {
    std::remove(path_.c_str());
    throw ReachError("cannot write the temporary URDF file " + path_);
  }
}

TempUrdf::~TempUrdf() { std::remove(path_.c_str()); }

FootholdServiceSetup FootholdServiceSetup::load(const ros::NodeHandle& nh,
                                                const ros::NodeHandle& pnh) {
  const std::string urdf = robotDescription(nh);
  const std::string config_path = configPath(pnh);
  FootholdRequestLimits limits;
  pnh.getParam("ground_tolerance", limits.ground_tolerance);
  // A NaN tolerance would pass every foothold height (the comparison is false).
  if (!(limits.ground_tolerance >= 0.0) || !std::isfinite(limits.ground_tolerance))
    throw ConfigError("~ground_tolerance must be >= 0 m and finite");
  const YamlSection file = YamlSection::loadFile(config_path);
  // The services need these sections (throw naming the file when missing); the rest is the
  // planner setup every tool reads (contact: required).
  file.section("reach");
  file.section("kinematic_feasibility");
  const FootstepPlannerSetup setup = FootstepPlannerSetup::fromYaml(file);
  const RobotConfig& robot = setup.robot;
  const std::shared_ptr<const RobotModel> model =
      robot.modelFromUrdfString(urdf, "robot_description");
  const ContactConfig& contact = setup.contact;
  const WalkConfig walk =
      file.has("walk") ? WalkConfig::fromYaml(file.section("walk")) : WalkConfig{};
  FootholdServiceSetup s{file,   config_path, model, contact, setup.planner.reach,
                         limits, nullptr,     {}};
  s.planner = std::make_shared<FootstepTransitionPlanner>(model, contact, setup.planner);
  s.standing_q = standingConfiguration(*model, walk.knee_bend, contact.left_sole_frame, robot);
  return s;
}

}  // namespace ros_bridge
}  // namespace reach_trajopt
