/// \file robot_config.cpp
/// The `robot:` section (see the header).

#include "reach_trajopt/model/robot_config.h"

#include <cmath>
#include <cstdlib>
#include <map>

#include "reach_trajopt/common/config_fields.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/model/robot_model.h"

namespace reach_trajopt {

namespace {

/// Each role: its YAML key (the member name) and its joint name.
std::vector<std::pair<const char*, const std::string*>> roles(const RobotConfig& c) {
  return {{"left_hip_yaw", &c.left_hip_yaw},           {"left_hip_roll", &c.left_hip_roll},
          {"left_hip_pitch", &c.left_hip_pitch},       {"left_knee", &c.left_knee},
          {"left_ankle_pitch", &c.left_ankle_pitch},   {"left_ankle_roll", &c.left_ankle_roll},
          {"right_hip_yaw", &c.right_hip_yaw},         {"right_hip_roll", &c.right_hip_roll},
          {"right_hip_pitch", &c.right_hip_pitch},     {"right_knee", &c.right_knee},
          {"right_ankle_pitch", &c.right_ankle_pitch}, {"right_ankle_roll", &c.right_ankle_roll}};
}

bool requiredRole(const std::string& key) {
  return key.find("pitch") != std::string::npos || key.find("knee") != std::string::npos;
}

ModelOptions modelOptions(const RobotConfig& c) {
  ModelOptions options;
  options.locked_joints = c.locked_joints;
  return options;
}

}  // namespace

LegJoints RobotConfig::leg(Side side) const {
  if (side == Side::kLeft)
    return {left_hip_yaw, left_hip_roll,    left_hip_pitch,
            left_knee,    left_ankle_pitch, left_ankle_roll};
  return {right_hip_yaw, right_hip_roll,    right_hip_pitch,
          right_knee,    right_ankle_pitch, right_ankle_roll};
}

std::string RobotConfig::urdfPath() const {
  std::string out;
  for (std::size_t i = 0; i < urdf.size(); ++i) {
    if (urdf.compare(i, 2, "${") != 0) {
      out += urdf[i];
      continue;
    }
    const std::size_t end = urdf.find('}', i + 2);
    if (end == std::string::npos)
      throw ConfigError("robot.urdf: '${' without a closing '}' in '" + urdf + "'");
    const std::string name = urdf.substr(i + 2, end - i - 2);
    const char* value = std::getenv(name.c_str());
    if (!value || !*value)
      throw ConfigError("robot.urdf: the environment variable " + name + " of '" + urdf +
                        "' is not set (scripts/env.sh sets EXAMPLE_ROBOT_DATA)");
    out += value;
    i = end;
  }
  return out;
}

void RobotConfig::checkJoints(const RobotModel& model) const {
  for (const auto& [key, joint] : roles(*this)) {
    if (joint->empty()) continue;
    bool found = false;
    for (const JointInfo& j : model.joints()) found = found || (!j.is_virtual && j.name == *joint);
    if (!found)
      throw ConfigError("robot." + std::string(key) + ": '" + *joint +
                        "' is not a moving joint of " + model.source());
  }
}

std::shared_ptr<const RobotModel> RobotConfig::loadModel(const std::string& urdf_override) const {
  return RobotModel::fromUrdfFile(urdf_override.empty() ? urdfPath() : urdf_override,
                                  modelOptions(*this));
}

std::shared_ptr<const RobotModel> RobotConfig::modelFromUrdfString(
    const std::string& xml, const std::string& source) const {
  return RobotModel::fromUrdfString(xml, modelOptions(*this), source);
}

void RobotConfig::validate() const {
  if (urdf.empty()) throw ConfigError("RobotConfig: urdf: empty path");
  std::map<std::string, const char*> role_of;  // joint -> the first key naming it
  for (const auto& [key, joint] : roles(*this)) {
    if (joint->empty()) continue;
    const auto [it, fresh] = role_of.emplace(*joint, key);
    if (!fresh)
      throw ConfigError("RobotConfig: robot." + std::string(it->second) + " and robot." +
                        std::string(key) + " both name joint '" + *joint +
                        "' (a joint holds one leg role)");
  }
  for (const auto& [key, joint] : roles(*this)) {
    if (joint->empty() && requiredRole(key))
      throw ConfigError("RobotConfig: " + std::string(key) + ": the leg needs this joint");
    if (!joint->empty() && locked_joints.count(*joint))
      throw ConfigError("RobotConfig: " + std::string(key) + ": '" + *joint +
                        "' is also in locked_joints");
  }
  for (const auto& [name, position] : locked_joints)
    if (!std::isfinite(position))
      throw ConfigError("RobotConfig: locked_joints." + name + ": not a finite number");
  requirePositiveFinite("RobotConfig", "sim_sole_box_height", sim_sole_box_height);
}

const ConfigFields<RobotConfig>& RobotConfig::fields() {
  using C = RobotConfig;
  auto f = ConfigFields<C>(
      "RobotConfig", "robot", "include/reach_trajopt/model/robot_config.h",
      "The robot: URDF, locked joints, leg joints by role, simulator sole boxes (the soles are "
      "contact:'s, the pelvis kinematic_feasibility.pelvis_frame).");
  f.add("urdf", &C::urdf, "",
        "URDF file; ${NAME} is the environment variable NAME, relative paths from the working "
        "directory");
  f.custom(
      "locked_joints", "mapping joint: position",
      [](const YamlSection& s, const std::string& k, C& c) {
        const YamlSection joints = s.section(k);
        c.locked_joints.clear();
        for (const std::string& name : joints.keys()) {
          double position = 0.0;
          joints.read(name, position);
          c.locked_joints[name] = position;
        }
      },
      [](const C& c) {
        std::string text = "{";
        for (const auto& [name, position] : c.locked_joints)
          text += (text.size() > 1 ? ", " : "") + name + ": " + parameterText(position);
        return text + "}";
      },
      "rad or m", "joints held at these positions and removed from the model (buildReducedModel)");
  // The roles, in the order of roles(): each a string member of C.
  using Member = std::string C::*;
  static const Member kMembers[12] = {
      &C::left_hip_yaw,     &C::left_hip_roll,   &C::left_hip_pitch,    &C::left_knee,
      &C::left_ankle_pitch, &C::left_ankle_roll, &C::right_hip_yaw,     &C::right_hip_roll,
      &C::right_hip_pitch,  &C::right_knee,      &C::right_ankle_pitch, &C::right_ankle_roll};
  static const char* const kRoleText[6] = {
      "hip yaw joint (\"\": none)",   "hip roll joint (\"\": none)",
      "hip pitch joint (required)",   "knee joint, positive angles bend it (required)",
      "ankle pitch joint (required)", "ankle roll joint (\"\": none)"};
  const auto keys = roles(C{});
  for (int i = 0; i < 12; ++i)
    f.add(keys[i].first, kMembers[i], "",
          std::string(i < 6 ? "left " : "right ") + kRoleText[i % 6]);
  f.add("sim_sole_boxes", &C::sim_sole_boxes, "",
        "the simulator adds a contact box of the sole rectangle under each sole frame (for "
        "URDFs whose feet are meshes)");
  f.add("sim_sole_box_height", &C::sim_sole_box_height, "m", "thickness of those boxes, > 0");
  static const ConfigFields<C> fields = f;
  return fields;
}

RobotConfig RobotConfig::fromYaml(const YamlSection& s) { return fields().read(s); }

RobotConfig RobotConfig::fromConfigFile(const YamlSection& root) {
  return root.has("robot") ? fromYaml(root.section("robot")) : RobotConfig{};
}

}  // namespace reach_trajopt
