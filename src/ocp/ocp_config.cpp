#include "reach_trajopt/ocp/ocp_config.h"

#include <cmath>
#include <sstream>

#include "reach_trajopt/common/config_fields.h"
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
    throw ConfigError(os.str());
  }
}

}  // namespace

void TransitionOcpConfig::validate() const {
  if (segments < 2) {
    throw ConfigError("TransitionOcpConfig: segments must be >= 2, got " +
                      std::to_string(segments));
  }
  requirePositive("check_interval", check_interval);
  requirePositive("output_dt", output_dt);
  requireNonNegative("w_torque", w_torque);
  requireNonNegative("w_wrench", w_wrench);
  requireNonNegative("w_position", w_position);
  requireNonNegative("w_velocity", w_velocity);
  requirePositive("w_eps", w_eps);
  if (!std::isfinite(terminal_pelvis_height)) {
    throw ConfigError("TransitionOcpConfig: terminal_pelvis_height must be finite");
  }
  requireNonNegative("swing_clearance", swing_clearance);
  requireNonNegative("cone_margin", cone_margin);
  requireNonNegative("torque_margin", torque_margin);
  if (torque_margin >= 1.0) throw ConfigError("TransitionOcpConfig: torque_margin must be < 1");
  requirePositive("tolerance", tolerance);
  requirePositive("input_tolerance", input_tolerance);
  if (max_refinements < 0) throw ConfigError("TransitionOcpConfig: max_refinements must be >= 0");
  if (max_evaluations < 1) throw ConfigError("TransitionOcpConfig: max_evaluations must be >= 1");
  requirePositive("time_limit", time_limit);
  requirePositive("ftol_rel", ftol_rel);
  requirePositive("relaxed_ftol_rel", relaxed_ftol_rel);
  requirePositive("xtol_rel", xtol_rel);
  requirePositive("fd_step", fd_step);
  requireNonNegative("fit_regularization", fit_regularization);
  requireNonNegative("row_screening", row_screening);
  if (threads < 0)
    throw ConfigError("TransitionOcpConfig: threads must be >= 0 (0: OpenMP's default)");
}

const ConfigFields<TransitionOcpConfig>& TransitionOcpConfig::fields() {
  using C = TransitionOcpConfig;
  static const ConfigFields<C> f =
      ConfigFields<C>("TransitionOcpConfig", "ocp", "include/reach_trajopt/ocp/ocp_config.h",
                      "Transition OCP (eq. 22-23) on NLopt SLSQP; the header says what each knob "
                      "trades.")
          .add("segments", &C::segments, "",
               "cubic B-spline segments over the horizon, >= 2 (variables 12 (N - 1) + 6 strict)")
          .add("check_interval", &C::check_interval, "s",
               "NLP samples for cones, torque bounds, hulls, cost; smaller: more rows, slower")
          .add("output_dt", &C::output_dt, "s", "output and re-check sampling (controller rate)")
          .add("w_torque", &C::w_torque, "", "weight of |u / u_max|^2, >= 0")
          .add("w_wrench", &C::w_wrench, "", "weight of |lambda / (m g)|^2, >= 0")
          .add("w_position", &C::w_position, "1/rad^2, 1/m^2", "weight of |q - q_f|^2, >= 0")
          .add("w_velocity", &C::w_velocity, "s^2/rad^2", "weight of |qd - qd_f|^2, >= 0")
          .add("w_eps", &C::w_eps, "1/m^2", "weight of |eps|^2 of the relaxed problem, > 0")
          .add("cone_margin", &C::cone_margin, "m g",
               "NLP samples keep the cones this far inside, >= 0")
          .add("torque_margin", &C::torque_margin, "", "and |u| <= (1 - margin) u_max, in [0, 1)")
          .add("ground_clearance", &C::ground_clearance, "",
               "swing sole not below the target height at NLP samples")
          .add("swing_clearance", &C::swing_clearance, "m",
               "... and this much higher mid-horizon (no early touchdown), >= 0")
          .add("tolerance", &C::tolerance, "",
               "accepted violation per family (units: transition_result.h), > 0")
          .add("input_tolerance", &C::input_tolerance, "m, rad, m/s, rad/s",
               "x_0 (and x_f, strict) on their contacts, > 0")
          .add("max_refinements", &C::max_refinements, "",
               "re-solves with the violating samples added, >= 0")
          .add("max_evaluations", &C::max_evaluations, "", "NLopt maxeval per solve, >= 1")
          .add("time_limit", &C::time_limit, "s", "wall clock per request, > 0")
          .add("ftol_rel", &C::ftol_rel, "", "NLopt relative cost tolerance (strict problem)")
          .add("relaxed_ftol_rel", &C::relaxed_ftol_rel, "",
               "the relaxed problem's (its cost is dominated by w_eps |eps|^2)")
          .add("xtol_rel", &C::xtol_rel, "", "NLopt relative variable tolerance")
          .add("fd_step", &C::fd_step, "rad, m", "finite-difference step in q")
          .add("central_differences", &C::central_differences, "",
               "central instead of forward differences (2x the gradient cost, ~1e-10 error)")
          .add("fit_regularization", &C::fit_regularization, "",
               "seed fit: weight of the second differences, >= 0")
          .add("row_screening", &C::row_screening, "m g, u_max, m",
               "SLSQP sees the inequality rows within this of active, the rest checked "
               "after; 0: all rows")
          .add("threads", &C::threads, "",
               "OpenMP threads evaluating the NLP samples, 0: OpenMP's default (same bits)")
          .removed("terminal_pelvis_height",
                   "removed: the relaxed landing height is kinematic_feasibility.pelvis_height");
  return f;
}

TransitionOcpConfig TransitionOcpConfig::fromYaml(const YamlSection& s) { return fields().read(s); }

}  // namespace reach_trajopt
