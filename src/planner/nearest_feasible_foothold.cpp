/// \file nearest_feasible_foothold.cpp
/// Ring search for the closest kinematically feasible foothold (see the header).

#include "reach_trajopt/planner/nearest_feasible_foothold.h"

#include <cmath>

#include "reach_trajopt/common/config_fields.h"

namespace reach_trajopt {

void NearestFootholdConfig::validate() const {
  if (!(ring_step > 0.0) || !std::isfinite(ring_step))
    throw ConfigError("NearestFootholdConfig: ring_step must be > 0 m, got " +
                      std::to_string(ring_step));
  if (rings < 1 || rings > 1000)
    throw ConfigError("NearestFootholdConfig: rings must be in [1, 1000], got " +
                      std::to_string(rings));
  if (directions < 1 || directions > 360)
    throw ConfigError("NearestFootholdConfig: directions must be in [1, 360], got " +
                      std::to_string(directions));
}

const ConfigFields<NearestFootholdConfig>& NearestFootholdConfig::fields() {
  using C = NearestFootholdConfig;
  static const ConfigFields<C> f =
      ConfigFields<C>("NearestFootholdConfig", "nearest_foothold",
                      "include/reach_trajopt/planner/nearest_feasible_foothold.h",
                      "Ring search for the closest kinematically feasible foothold when the TVR "
                      "one fails the kinematic check (not in config/biped.yaml: the defaults).")
          .add("ring_step", &C::ring_step, "m", "radius increment between rings, > 0")
          .add("rings", &C::rings, "", "rings searched, in [1, 1000]")
          .add("directions", &C::directions, "", "points per ring, in [1, 360], first along +x");
  return f;
}

NearestFootholdConfig NearestFootholdConfig::fromYaml(const YamlSection& s) {
  return fields().read(s);
}

NearestFeasibleFoothold::NearestFeasibleFoothold(
    std::shared_ptr<const KinematicFeasibility> kinematics, const NearestFootholdConfig& config)
    : kinematics_(std::move(kinematics)), config_(config) {
  if (!kinematics_) throw ReachError("NearestFeasibleFoothold: null kinematic check");
  config_.validate();
}

std::optional<NearestFoothold> NearestFeasibleFoothold::find(
    Side stance, const FlatContact& stance_foothold, const FlatContact& target,
    const Eigen::VectorXd& q_init, const std::optional<Eigen::Vector3d>& pelvis_position) const {
  for (int ring = 1; ring <= config_.rings; ++ring) {
    for (int d = 0; d < config_.directions; ++d) {
      const double angle = 2.0 * M_PI * d / config_.directions;
      FlatContact p = target;
      p.position = target.position +
                   ring * config_.ring_step * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0);
      KinematicFeasibilityResult k =
          kinematics_->check(stance, stance_foothold, p, q_init, pelvis_position);
      if (k.feasible) return NearestFoothold{p, std::move(k)};
    }
  }
  return std::nullopt;
}

}  // namespace reach_trajopt
