#include "reach_trajopt/sim/sim_config.h"

#include <cmath>
#include <sstream>

#include "reach_trajopt/common/config_fields.h"
#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

void SimConfig::validate() const {
  fields().checkRanges(*this);
  if (!gravity.allFinite()) throw ConfigError("SimConfig: gravity must be finite");
  if (left_sole_frame.empty() || right_sole_frame.empty()) {
    throw ConfigError("SimConfig: sole frame names must not be empty");
  }
  if (left_sole_frame == right_sole_frame) {
    throw ConfigError("SimConfig: left and right sole frames are both '" + left_sole_frame + "'");
  }
}

const ConfigFields<SimConfig>& SimConfig::fields() {
  using C = SimConfig;
  const std::string frames =
      "removed: the sole frames are contact.left_sole_frame and contact.right_sole_frame of the "
      "robot's config (config/biped.yaml)";
  static const ConfigFields<C> f =
      ConfigFields<C>("SimConfig", "sim", "include/reach_trajopt/sim/sim_config.h",
                      "Bullet multibody world (config/sim.yaml); its sole frames are those of "
                      "`contact:`.")
          .add("time_step", &C::time_step, "s", Range::between(1e-4, 0.01),
               "fixed step (1 kHz; 0.1 to 10 ms)")
          .add("mu", &C::mu, "", Range::positive(), "Coulomb friction with the ground")
          .add("gravity", &C::gravity, "m/s^2", "world frame, finite")
          .add("contacts", &C::contacts, "", "false removes the ground (free-fall checks)")
          .add("joint_limits", &C::joint_limits, "",
               "URDF position limits as unilateral constraints")
          .add("clamp_torques", &C::clamp_torques, "", "saturate torques at the URDF effort limits")
          .add("leg_self_collision", &C::leg_self_collision, "",
               "the two legs' collision shapes collide with each other (a walk ends as a fall "
               "when they touch)")
          .add("solver_iterations", &C::solver_iterations, "", Range::between(1, 1000),
               "Bullet constraint-solver iterations per step: more, stiffer and more "
               "accurate contacts; slower steps (at most 1000)")
          .add("collision_margin", &C::collision_margin, "m", Range::nonNegative(),
               "Bullet convex margin (rounds box corners)")
          .add("max_coordinate_velocity", &C::max_coordinate_velocity, "m/s, rad/s",
               Range::positive(), "Bullet's velocity clamp, kept out of reach")
          .removed("left_sole_frame", frames)
          .removed("right_sole_frame", frames);
  return f;
}

SimConfig SimConfig::fromYaml(const YamlSection& s) { return fields().read(s); }

}  // namespace reach_trajopt
