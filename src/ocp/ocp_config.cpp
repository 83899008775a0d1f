#include "reach_trajopt/ocp/ocp_config.h"

#include <cmath>
#include <sstream>
#include <string>

#include "reach_trajopt/common/cli_args.h"
#include "reach_trajopt/common/config_fields.h"
#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

void TransitionOcpConfig::validate() const {
  fields().checkRanges(*this);
  if (!std::isfinite(terminal_pelvis_height)) {
    throw ConfigError("TransitionOcpConfig: terminal_pelvis_height must be finite");
  }
  if (const std::string why = threadsBeyondHardware(threads); !why.empty())
    throw ConfigError("TransitionOcpConfig: threads " + why);
}

const ConfigFields<TransitionOcpConfig>& TransitionOcpConfig::fields() {
  using C = TransitionOcpConfig;
  static const ConfigFields<C> f =
      ConfigFields<C>("TransitionOcpConfig", "ocp", "include/reach_trajopt/ocp/ocp_config.h",
                      "Transition OCP (eq. 22-23) on NLopt SLSQP; the header says what each knob "
                      "trades.")
          .add("segments", &C::segments, "", Range::between(2, 200),
               "cubic B-spline segments over the horizon (variables 12 (N - 1) + 6 strict; "
               "SLSQP's dense matrices grow as their square)")
          .add("check_interval", &C::check_interval, "s", Range::atLeast(1e-3),
               "NLP samples for cones, torque bounds, hulls, cost; smaller: more rows, slower "
               "(at least 1 ms: the 5 s longest horizon then has 5000)")
          .add("output_dt", &C::output_dt, "s", Range::atLeast(1e-4),
               "output and re-check sampling (controller rate; at least 0.1 ms: the 5 s "
               "longest horizon then has 50000 samples)")
          .add("w_torque", &C::w_torque, "", Range::nonNegative(), "weight of |u / u_max|^2")
          .add("w_wrench", &C::w_wrench, "", Range::nonNegative(), "weight of |lambda / (m g)|^2")
          .add("w_position", &C::w_position, "1/rad^2, 1/m^2", Range::nonNegative(),
               "weight of |q - q_f|^2")
          .add("w_velocity", &C::w_velocity, "s^2/rad^2", Range::nonNegative(),
               "weight of |qd - qd_f|^2")
          .add("w_eps", &C::w_eps, "1/m^2", Range::positive(),
               "weight of |eps|^2 of the relaxed problem")
          .add("cone_margin", &C::cone_margin, "m g", Range::nonNegative(),
               "NLP samples keep the cones this far inside")
          .add("torque_margin", &C::torque_margin, "", Range::below(0.0, 1.0),
               "and |u| <= (1 - margin) u_max")
          .add("ground_clearance", &C::ground_clearance, "",
               "swing sole not below the target height at NLP samples")
          .add("swing_clearance", &C::swing_clearance, "m", Range::nonNegative(),
               "... and this much higher mid-horizon (no early touchdown)")
          .add("tolerance", &C::tolerance, "", Range::positive(),
               "accepted violation per family (units: transition_result.h)")
          .add("input_tolerance", &C::input_tolerance, "m, rad, m/s, rad/s", Range::positive(),
               "x_0 (and x_f, strict) on their contacts")
          .add("max_refinements", &C::max_refinements, "", Range::nonNegative(),
               "re-solves with the violating samples added")
          .add("max_evaluations", &C::max_evaluations, "", Range::atLeast(1),
               "NLopt maxeval per solve")
          .add("time_limit", &C::time_limit, "s", Range::positive(), "wall clock per request")
          .add("ftol_rel", &C::ftol_rel, "", Range::positive(),
               "NLopt relative cost tolerance (strict problem)")
          .add("relaxed_ftol_rel", &C::relaxed_ftol_rel, "", Range::positive(),
               "the relaxed problem's (its cost is dominated by w_eps |eps|^2)")
          .add("xtol_rel", &C::xtol_rel, "", Range::positive(), "NLopt relative variable tolerance")
          .choice("chain_derivatives", &C::chain_derivatives,
                  {{"analytic", ChainDerivatives::kAnalytic},
                   {"finite_differences", ChainDerivatives::kFiniteDifferences}},
                  "Jacobian of the kinematic chain: exact, or differences (fd_step, "
                  "central_differences) to compare")
          .add("fd_step", &C::fd_step, "rad, m", Range::positive(), "finite_differences: step in q")
          .add("central_differences", &C::central_differences, "",
               "finite_differences: central instead of forward (2x the gradient cost, ~1e-10 "
               "error)")
          .add("fit_regularization", &C::fit_regularization, "", Range::nonNegative(),
               "seed fit: weight of the second differences")
          .add("row_screening", &C::row_screening, "m g, u_max, m", Range::nonNegative(),
               "SLSQP sees the inequality rows within this of active, the rest checked "
               "after; 0: all rows")
          .add("threads", &C::threads, "", Range::nonNegative(),
               "OpenMP threads evaluating the NLP samples, 0: OpenMP's default (same bits)")
          .removed("terminal_pelvis_height",
                   "removed: the relaxed landing height is kinematic_feasibility.pelvis_height");
  return f;
}

TransitionOcpConfig TransitionOcpConfig::fromYaml(const YamlSection& s) { return fields().read(s); }

}  // namespace reach_trajopt
