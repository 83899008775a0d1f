#pragma once
/// \file nearest_feasible_foothold.h
/// The fallback of a foothold that fails the kinematic check of Sec. III-B (e.g. a TVR step
/// that puts one sole through the other): the closest kinematically feasible foothold, searched
/// on rings of growing radius around the target (`rings` rings `ring_step` apart, `directions`
/// points per ring, the first direction along +x, counter-clockwise). The first feasible point
/// found is returned with its IK posture; none within rings * ring_step is a result, not an
/// error. Not in the paper (its planner never proposes such steps); see docs/method.md.

#include <Eigen/Core>
#include <memory>
#include <optional>

#include "reach_trajopt/planner/kinematic_feasibility.h"

namespace reach_trajopt {

class YamlSection;
template <typename Config>
class ConfigFields;

/// Parameters of the ring search. Defaults: 15 rings of 2 cm (0.3 m), 12 directions.
struct NearestFootholdConfig {
  double ring_step = 0.02;  ///< radius increment between rings [m]
  int rings = 15;           ///< rings searched
  int directions = 12;      ///< points per ring
  /// \throws ConfigError naming the first bad field.
  void validate() const;
  /// The YAML keys of section `nearest_foothold:` (the member names), units and meaning.
  static const ConfigFields<NearestFootholdConfig>& fields();
  /// Reads fields() from a YAML section, then validates.
  static NearestFootholdConfig fromYaml(const YamlSection& section);
  double searchRadius() const { return rings * ring_step; }  ///< [m]
};

/// A feasible foothold found near the target.
struct NearestFoothold {
  FlatContact foothold;                   ///< the feasible foothold [m, rad]
  KinematicFeasibilityResult kinematics;  ///< its IK posture q_f
};

/// @brief Ring search for the closest kinematically feasible foothold to a target.
class NearestFeasibleFoothold {
 public:
  NearestFeasibleFoothold(std::shared_ptr<const KinematicFeasibility> kinematics,
                          const NearestFootholdConfig& config);
  /// \param stance, stance_foothold  the held sole
  /// \param target     the infeasible foothold (its yaw is kept)
  /// \param q_init     IK start (size n_q)
  /// \param pelvis_position  passed to KinematicFeasibility::check
  /// \return the first feasible ring point, or none.
  std::optional<NearestFoothold> find(Side stance, const FlatContact& stance_foothold,
                                      const FlatContact& target, const Eigen::VectorXd& q_init,
                                      const std::optional<Eigen::Vector3d>& pelvis_position) const;
  const NearestFootholdConfig& config() const { return config_; }

 private:
  std::shared_ptr<const KinematicFeasibility> kinematics_;
  NearestFootholdConfig config_;
};

}  // namespace reach_trajopt
