#include "reach_trajopt/ocp/ocp_config.h"

#include <cmath>
#include <sstream>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

namespace {

void requirePositive(const char* name, double v) {
  requirePositiveFinite("TransitionOcpConfig", name, v);
}

void requireNonNegative(const char* name, double v) {
  if (!std::isfinite(v) || v < 0.0) {
    std::ostringstream os;
    os << "TransitionOcpConfig: " << name << " must be >= 0 and finite, got " << v;
    throw ReachError(os.str());
  }
}

}  // namespace

void TransitionOcpConfig::validate() const {
  if (segments < 2) {
    throw ReachError("TransitionOcpConfig: segments must be >= 2, got " + std::to_string(segments));
  }
  requirePositive("check_interval", check_interval);
  requirePositive("output_dt", output_dt);
  requireNonNegative("w_torque", w_torque);
  requireNonNegative("w_wrench", w_wrench);
  requireNonNegative("w_position", w_position);
  requireNonNegative("w_velocity", w_velocity);
  requirePositive("w_eps", w_eps);
  if (!std::isfinite(terminal_pelvis_height)) {
    throw ReachError("TransitionOcpConfig: terminal_pelvis_height must be finite");
  }
  requireNonNegative("swing_clearance", swing_clearance);
  requireNonNegative("cone_margin", cone_margin);
  requireNonNegative("torque_margin", torque_margin);
  if (torque_margin >= 1.0) throw ReachError("TransitionOcpConfig: torque_margin must be < 1");
  requirePositive("tolerance", tolerance);
  requirePositive("input_tolerance", input_tolerance);
  if (max_refinements < 0) throw ReachError("TransitionOcpConfig: max_refinements must be >= 0");
  if (max_evaluations < 1) throw ReachError("TransitionOcpConfig: max_evaluations must be >= 1");
  requirePositive("time_limit", time_limit);
  requirePositive("ftol_rel", ftol_rel);
  requirePositive("relaxed_ftol_rel", relaxed_ftol_rel);
  requirePositive("xtol_rel", xtol_rel);
  requirePositive("fd_step", fd_step);
  requireNonNegative("fit_regularization", fit_regularization);
}

TransitionOcpConfig TransitionOcpConfig::fromYaml(const YamlSection& s) {
  s.requireOnlyKeys({"segments",
                     "check_interval",
                     "output_dt",
                     "w_torque",
                     "w_wrench",
                     "w_position",
                     "w_velocity",
                     "w_eps",
                     "terminal_pelvis_height",
                     "cone_margin",
                     "torque_margin",
                     "ground_clearance",
                     "swing_clearance",
                     "tolerance",
                     "input_tolerance",
                     "max_refinements",
                     "max_evaluations",
                     "time_limit",
                     "ftol_rel",
                     "relaxed_ftol_rel",
                     "xtol_rel",
                     "fd_step",
                     "central_differences",
                     "fit_regularization"});
  TransitionOcpConfig c;
  s.read("segments", c.segments);
  s.read("check_interval", c.check_interval);
  s.read("output_dt", c.output_dt);
  s.read("w_torque", c.w_torque);
  s.read("w_wrench", c.w_wrench);
  s.read("w_position", c.w_position);
  s.read("w_velocity", c.w_velocity);
  s.read("w_eps", c.w_eps);
  s.read("terminal_pelvis_height", c.terminal_pelvis_height);
  s.read("cone_margin", c.cone_margin);
  s.read("torque_margin", c.torque_margin);
  s.read("ground_clearance", c.ground_clearance);
  s.read("swing_clearance", c.swing_clearance);
  s.read("tolerance", c.tolerance);
  s.read("input_tolerance", c.input_tolerance);
  s.read("max_refinements", c.max_refinements);
  s.read("max_evaluations", c.max_evaluations);
  s.read("time_limit", c.time_limit);
  s.read("ftol_rel", c.ftol_rel);
  s.read("relaxed_ftol_rel", c.relaxed_ftol_rel);
  s.read("xtol_rel", c.xtol_rel);
  s.read("fd_step", c.fd_step);
  s.read("central_differences", c.central_differences);
  s.read("fit_regularization", c.fit_regularization);
  return validatedIn(s, c);
}

}  // namespace reach_trajopt
