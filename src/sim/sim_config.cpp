#include "reach_trajopt/sim/sim_config.h"

#include <cmath>
#include <sstream>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

namespace {
void requirePositive(const char* name, double v) { requirePositiveFinite("SimConfig", name, v); }
}  // namespace

void SimConfig::validate() const {
  requirePositive("time_step", time_step);
  requirePositive("mu", mu);
  requirePositive("max_coordinate_velocity", max_coordinate_velocity);
  if (!gravity.allFinite()) throw ReachError("SimConfig: gravity must be finite");
  if (solver_iterations < 1) {
    throw ReachError("SimConfig: solver_iterations must be >= 1, got " +
                     std::to_string(solver_iterations));
  }
  if (!std::isfinite(collision_margin) || collision_margin < 0.0) {
    std::ostringstream os;
    os << "SimConfig: collision_margin must be >= 0 and finite, got " << collision_margin;
    throw ReachError(os.str());
  }
  if (left_sole_frame.empty() || right_sole_frame.empty()) {
    throw ReachError("SimConfig: sole frame names must not be empty");
  }
  if (left_sole_frame == right_sole_frame) {
    throw ReachError("SimConfig: left and right sole frames are both '" + left_sole_frame + "'");
  }
}

SimConfig SimConfig::fromYaml(const YamlSection& s) {
  s.requireOnlyKeys({"time_step", "mu", "gravity", "contacts", "joint_limits", "clamp_torques",
                     "left_sole_frame", "right_sole_frame", "solver_iterations", "collision_margin",
                     "max_coordinate_velocity"});
  SimConfig c;
  s.read("time_step", c.time_step);
  s.read("mu", c.mu);
  Eigen::VectorXd g = c.gravity;
  if (s.read("gravity", Eigen::Ref<Eigen::VectorXd>(g))) c.gravity = g;
  s.read("contacts", c.contacts);
  s.read("joint_limits", c.joint_limits);
  s.read("clamp_torques", c.clamp_torques);
  s.read("left_sole_frame", c.left_sole_frame);
  s.read("right_sole_frame", c.right_sole_frame);
  s.read("solver_iterations", c.solver_iterations);
  s.read("collision_margin", c.collision_margin);
  s.read("max_coordinate_velocity", c.max_coordinate_velocity);
  return validatedIn(s, c);
}

}  // namespace reach_trajopt
