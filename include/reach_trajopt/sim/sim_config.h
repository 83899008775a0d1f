#pragma once
/// \file sim_config.h
/// Parameters of the Bullet multibody world that stands in for the robot (paper Sec. IV uses
/// DART; we use Bullet's btMultiBody, double precision). Read from the `sim:` section of
/// config/sim.yaml.

#include <Eigen/Core>
#include <string>

namespace reach_trajopt {

class YamlSection;
template <typename Config>
class ConfigFields;

/// Simulation parameters. Speed versus accuracy: `solver_iterations` (contact and joint-limit
/// impulses: more iterations, stiffer and more accurate contacts, slower steps).
struct SimConfig {
  double time_step = 1e-3;  ///< fixed step [s] (1 kHz; 0.1 to 10 ms)
  double mu = 0.7;          ///< Coulomb friction sole/link-ground (same default as ContactConfig)
  Eigen::Vector3d gravity = Eigen::Vector3d(0.0, 0.0, -9.81);  ///< world frame [m/s^2]
  bool contacts = true;       ///< false: no ground (free fall, for checks against the model)
  bool joint_limits = true;   ///< unilateral joint-limit constraints from the URDF limits
  bool clamp_torques = true;  ///< saturate u at the URDF effort limits, as actuators do
  /// The two legs collide with each other (the links below the root on the path to each sole,
  /// and their subtrees); a leg-leg contact is reported by BulletWorld::legContacts().
  bool leg_self_collision = true;
  /// Sole-centre frames where wrenches are reported. Not YAML keys: the robot's sole frames
  /// are ContactConfig's (section `contact:`), which WalkingExperiment copies here.
  std::string left_sole_frame = "l_sole";
  std::string right_sole_frame = "r_sole";
  /// Full sizes [m] of a contact box added under each sole frame (its bottom face on the
  /// sole); zero: none, the URDF's collision shapes only. Not a YAML key: robot.sim_sole_boxes
  /// and the contact rectangle, which WalkingExperiment copies here.
  Eigen::Vector3d sole_box_size = Eigen::Vector3d::Zero();
  int solver_iterations = 20;      ///< Bullet constraint-solver iterations per step (<= 1000)
  double collision_margin = 1e-3;  ///< Bullet convex margin [m] (rounds box corners)
  /// Bullet clamps every velocity coordinate to this [m/s, rad/s]; kept out of reach.
  double max_coordinate_velocity = 1e3;

  /// Throws ConfigError naming the offending value (non-positive step, mu, iterations,
  /// negative margin, non-finite gravity, empty or equal sole frames).
  void validate() const;
  /// The YAML keys of section `sim:` (the member names but the sole frames), units, meaning.
  static const ConfigFields<SimConfig>& fields();
  /// Reads fields() (missing keys keep the defaults, unknown keys throw), validates.
  static SimConfig fromYaml(const YamlSection& section);
};

}  // namespace reach_trajopt
