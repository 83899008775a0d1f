#pragma once
/// \file kinematic_feasibility.h
/// The kinematic feasibility check of Sec. III-B: can the robot stand with the current contact
/// a_k and the planned contact a_{k+1}^d both held by eq. (5) (phi_i = 0), both soles flat,
/// the pelvis upright at a nominal height, and every joint within its position limits?
///
/// Method: joint-limited inverse kinematics. The 16 task rows (two 6-D sole errors of eq. (5),
/// pelvis height, pelvis orientation = upright with the soles' mean heading) are solved by
/// damped least squares Newton steps with their exact Jacobians; a joint whose update would
/// cross a limit is clamped to it and the step is re-solved for the other joints. The pelvis
/// x, y are free (or, optionally, the whole pelvis position is held). Before the IK, two geometric
/// checks reject placements where one foot would pass through the other (overlapping sole
/// rectangles, or the swing sole across the stance sole's centre line). Its solution is the final
/// configuration q_f of the transition (x_f with qd_f = 0), used by the backward reachable set and
/// the OCP.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>

#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/contact/contact_mode.h"
#include "reach_trajopt/contact/contact_transition.h"
#include "reach_trajopt/model/robot_model.h"

namespace reach_trajopt {

class YamlSection;
template <typename Config>
class ConfigFields;

/// Parameters of the kinematic feasibility check. Sole frames and sizes come from
/// ContactConfig. Tolerances trade accuracy for iterations (Newton: a few more per decade).
struct KinematicFeasibilityConfig {
  std::string pelvis_frame = "pelvis";  ///< frame held upright at the nominal height
  double pelvis_height = 1.05;          ///< pelvis origin above the mean sole height [m]
  double position_tolerance = 1e-6;     ///< max |sole / pelvis height error| to accept [m]
  double orientation_tolerance = 1e-6;  ///< max |orientation error| to accept [rad]
  int max_iterations = 100;             ///< Newton iterations
  double damping = 1e-8;                ///< DLS damping lambda^2 (> 0) [m^2]
  double max_joint_step = 0.3;          ///< largest joint update per iteration [rad or m]
  double sole_clearance = 0.03;         ///< minimal gap between the two sole rectangles [m]
  double min_lateral_offset = 0.0;      ///< swing sole centre towards the swing side of the
                                        ///< stance sole centre, at least this [m]
  double workspace_radius = 3.0;        ///< requests with soles farther apart horizontally
                                        ///< are errors, not steps [m]
  double workspace_height = 0.5;        ///< same for the sole height difference [m]

  /// Throws ConfigError naming the first bad value.
  void validate() const;
  /// The YAML keys of section `kinematic_feasibility:` (the member names), units and meaning.
  static const ConfigFields<KinematicFeasibilityConfig>& fields();
  /// Reads fields() from a YAML section, then validates.
  static KinematicFeasibilityConfig fromYaml(const YamlSection& section);
};

/// Outcome of one check.
struct KinematicFeasibilityResult {
  bool feasible = false;
  std::string reason;                 ///< why not (empty when feasible)
  double position_residual = 0.0;     ///< max |position error| over soles and pelvis height [m]
  double orientation_residual = 0.0;  ///< max |orientation error| of soles and pelvis [rad]
  int iterations = 0;
  Eigen::VectorXd q_f;   ///< final configuration, size n_q (last iterate when infeasible)
  Eigen::VectorXd qd_f;  ///< final velocity, zeros of size n_q
};

/// Sec. III-B kinematic feasibility of the next contact. Immutable; check() is thread-safe
/// (each call owns its Workspace).
class KinematicFeasibility {
 public:
  /// Throws ReachError on an invalid config, a model without a floating base, or an unknown
  /// frame (sole or pelvis).
  KinematicFeasibility(std::shared_ptr<const RobotModel> model,
                       const KinematicFeasibilityConfig& config = {},
                       const ContactConfig& contact = {});

  /// Checks the stance sole held at `current` and the swing sole at `planned`.
  /// \param q_init  starting configuration (size n_q); empty: a standing guess between the soles
  /// \param pelvis_position  world position of the pelvis origin to hold [m] (e.g. where the
  ///     walking robot's pelvis will be at touchdown); none: x, y free, z at the nominal height
  /// Throws ReachError on non-finite input, a wrong q_init size, or a step outside the
  /// workspace (soles more than workspace_radius apart horizontally or workspace_height
  /// vertically); an unreachable step within it is a result with feasible = false and a reason.
  KinematicFeasibilityResult check(
      Side stance, const FlatContact& current, const FlatContact& planned,
      const Eigen::VectorXd& q_init = Eigen::VectorXd(),
      const std::optional<Eigen::Vector3d>& pelvis_position = std::nullopt) const;

  const KinematicFeasibilityConfig& config() const { return config_; }
  const RobotModel& model() const { return *model_; }

 private:
  std::shared_ptr<const RobotModel> model_;
  KinematicFeasibilityConfig config_;
  ContactConfig contact_;
  FrameId left_sole_, right_sole_, pelvis_;
};

}  // namespace reach_trajopt
