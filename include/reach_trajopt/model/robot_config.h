#pragma once
/// \file robot_config.h
/// The robot of a config file (section `robot:`): which URDF, which of its joints are locked
/// (held and removed from the model, joint_locking.h), which joints play which role in a leg
/// (the standing posture of walk/standing_pose.h sets them), and whether the simulator puts
/// contact boxes under the soles. Together with the sole frames and rectangles of `contact:`
/// and the pelvis frame of `kinematic_feasibility:`, this is everything the code knows about a
/// robot: no robot or joint name is written in code (README, "Add your robot").

#include <memory>
#include <string>

#include "reach_trajopt/common/side.h"
#include "reach_trajopt/model/joint_locking.h"

namespace reach_trajopt {

class RobotModel;
class YamlSection;
template <typename Config>
class ConfigFields;

/// The joints of one leg by role (URDF joint names). The pitch joints and the knee are
/// required; a role the leg does not have is "" (it is then left at 0 by the standing pose).
struct LegJoints {
  std::string hip_yaw, hip_roll, hip_pitch, knee, ankle_pitch, ankle_roll;
};

/// @brief One robot: URDF, locked joints, leg joint roles, simulator sole boxes.
/// Defaults are the biped of urdf/biped.urdf.
struct RobotConfig {
  /// URDF file. `${NAME}` is replaced by the environment variable NAME (scripts/env.sh sets
  /// EXAMPLE_ROBOT_DATA to the project venv's example-robot-data robots/ directory); a
  /// relative path is relative to the working directory (the tools run from the repository).
  std::string urdf = "urdf/biped.urdf";
  /// Joint -> held position [rad or m], e.g. TALOS's arms at half_sitting.
  LockedJoints locked_joints;
  std::string left_hip_yaw = "l_hip_yaw", left_hip_roll = "l_hip_roll",
              left_hip_pitch = "l_hip_pitch", left_knee = "l_knee",
              left_ankle_pitch = "l_ankle_pitch", left_ankle_roll = "l_ankle_roll";
  std::string right_hip_yaw = "r_hip_yaw", right_hip_roll = "r_hip_roll",
              right_hip_pitch = "r_hip_pitch", right_knee = "r_knee",
              right_ankle_pitch = "r_ankle_pitch", right_ankle_roll = "r_ankle_roll";
  /// The simulator adds a box the size of the contact rectangle (contact.half_length,
  /// half_width) under each sole frame, its bottom face on the sole; for URDFs whose feet
  /// collide through meshes, which the simulator ignores.
  bool sim_sole_boxes = false;
  double sim_sole_box_height = 0.02;  ///< thickness of those boxes [m]

  /// The leg joints of `side`.
  LegJoints leg(Side side) const;
  /// `urdf` with ${NAME} expanded. \throws ConfigError naming robot.urdf and NAME when the
  /// variable is not set or the brace is not closed.
  std::string urdfPath() const;
  /// Loads urdfPath() with the locked joints. The leg roles are checked where they are used
  /// (checkJoints, by the standing pose): a model without legs loads too.
  /// \param urdf_override a URDF path to use instead (a tool's --urdf), "" for none
  /// \throws ReachError naming the file, or the locked joint that does not exist.
  std::shared_ptr<const RobotModel> loadModel(const std::string& urdf_override = "") const;
  /// The same from URDF text (a node's robot_description); `source` names it in errors.
  std::shared_ptr<const RobotModel> modelFromUrdfString(const std::string& xml,
                                                        const std::string& source) const;
  /// Throws ConfigError naming robot.<key> when a role's joint is not a joint of `model`.
  void checkJoints(const RobotModel& model) const;

  /// Throws ConfigError for an empty URDF path or pitch/knee role, non-finite locked
  /// positions, a joint both locked and given a role, or a non-positive box height.
  void validate() const;
  /// The YAML keys of section `robot:`.
  static const ConfigFields<RobotConfig>& fields();
  /// Reads fields() (missing keys keep the defaults, unknown keys throw), validates.
  static RobotConfig fromYaml(const YamlSection& section);
  /// The `robot:` section of a config file, or the defaults when the file has none.
  static RobotConfig fromConfigFile(const YamlSection& root);
};

}  // namespace reach_trajopt
