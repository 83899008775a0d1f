/// \file reach_config.cpp
/// Validation and YAML reading of ReachConfig.

#include "reach_trajopt/reach/reach_config.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "reach_trajopt/common/cli_args.h"
#include "reach_trajopt/common/config_fields.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"

namespace reach_trajopt {
namespace {

[[noreturn]] void bad(const std::string& field, const std::string& why) {
  throw ConfigError("ReachConfig: " + field + " " + why);
}

void requireAtMost(const char* field, long long v, long long limit) {
  if (v > limit)
    bad(field,
        "must be <= " + std::to_string(limit) + " (docs/limits.md), got " + std::to_string(v));
}

/// True when t is an integer multiple of dt (to 1e-9 of a step).
bool onGrid(double t, double dt) { return std::abs(t / dt - std::round(t / dt)) < 1e-6; }

}  // namespace

void ReachConfig::validate() const {
  fields().checkRanges(*this);
  if (window_start > window_end + 1e-12 || window_end > horizon + 1e-12) {
    std::ostringstream os;
    os << "needs 0 <= window_start <= window_end <= horizon (the overlap window [t_2, t_1] "
          "must lie in [t_0, t_f]), got window_start "
       << window_start << ", window_end " << window_end << ", horizon " << horizon;
    bad("window", os.str() + ": empty window");
  }
  if (!onGrid(horizon, dt) || !onGrid(window_start, dt) || !onGrid(window_end, dt))
    bad("horizon/window_start/window_end", "must be multiples of dt");
  if (horizon < dt * (1.0 - 1e-9))
    bad("horizon", "must be at least one time step dt = " + std::to_string(dt) + " s, got " +
                       std::to_string(horizon));
  using L = ReachLimits;
  if (horizon / dt > L::kMaxSteps + 0.5)
    bad("horizon", "/ dt = " + std::to_string(horizon / dt) + " steps is over the limit of " +
                       std::to_string(L::kMaxSteps));
  budgets.full.validate("budgets.full");
  if (quick_pass) budgets.quick.validate("budgets.quick");
  budgets.hullBudget().validate("budgets.hull");
  requireAtMost("angular_bins", angular_bins, L::kMaxAngularBins);
  if (boundary_lookahead.empty()) bad("boundary_lookahead", "must hold at least one value");
  requireAtMost("boundary_lookahead (entries)", static_cast<long long>(boundary_lookahead.size()),
                L::kMaxLookahead);
  requireAtMost("redraw_rounds", redraw_rounds, L::kMaxRedrawRounds);
  if (const std::string why = threadsBeyondHardware(threads); !why.empty()) bad("threads", why);
  if (forward_integrator != "semi_implicit" && forward_integrator != "explicit")
    bad("forward_integrator",
        "must be 'semi_implicit' or 'explicit', got '" + forward_integrator + "'");
  if (output_axes.empty() || output_axes.size() > 3) bad("output_axes", "must hold 1-3 axes");
  for (std::size_t i = 0; i < output_axes.size(); ++i) {
    const char c = output_axes[i];
    if (c != 'x' && c != 'y' && c != 'z') bad("output_axes", "may only hold x, y, z");
    if (output_axes.find(c) != i) bad("output_axes", "repeats an axis");
  }
  if (std::isnan(swing_ground_margin) || swing_ground_margin == HUGE_VAL)
    bad("swing_ground_margin", "must be a number (-inf disables)");
  if (!(give_up_gap >= 0.0)) bad("give_up_gap", "must be >= 0 (0: never give up)");
}

double ReachConfig::estimatedQps(const SamplingBudget& budget) const {
  const double steps = std::ceil(window_end / dt) + std::ceil((horizon - window_start) / dt);
  const double parents = static_cast<double>(budget.max_boundary) + budget.interior_samples;
  const double per_slice =
      parents * std::max(budget.children_per_parent, budget.backward_children_per_parent);
  return 2.0 * budget.initial_samples + steps * per_slice;
}

double ReachConfig::estimatedQps() const {
  double qps = estimatedQps(budgets.full);
  if (quick_pass) qps = std::max(qps, estimatedQps(budgets.quick));
  if (quick_pass && hull_pass) qps = std::max(qps, estimatedQps(budgets.hullBudget()));
  return qps;
}

double ReachConfig::estimatedMemoryBytes(int nq, const SamplingBudget& budget) const {
  // output + rate (3 each), qd, u, lambda (12), kept q: doubles; parent index; QP scratch.
  const double per_sample = 8.0 * (6 + 3.0 * nq + 12) + 16;
  return per_sample * estimatedQps(budget);
}

double ReachConfig::estimatedMemoryBytes(int nq) const {
  const double per_sample = 8.0 * (6 + 3.0 * nq + 12) + 16;
  return per_sample * estimatedQps();
}

void ReachConfig::requireResourcesWithinLimits(int nq) const {
  requireResourcesWithinLimits(nq, budgets.full);
  if (quick_pass) requireResourcesWithinLimits(nq, budgets.quick);
  if (quick_pass && hull_pass) requireResourcesWithinLimits(nq, budgets.hullBudget());
}

void ReachConfig::requireResourcesWithinLimits(int nq, const SamplingBudget& b) const {
  const double qps = estimatedQps(b);
  if (qps > ReachLimits::kMaxQps) {
    std::ostringstream os;
    os << "ReachConfig: the check would solve about " << qps << " QPs (initial_samples "
       << b.initial_samples << ", max_boundary " << b.max_boundary << ", interior_samples "
       << b.interior_samples << ", horizon " << horizon << " s at dt " << dt
       << " s), over the limit of " << ReachLimits::kMaxQps << " (minutes of wall time)";
    throw ConfigError(os.str());
  }
  const double bytes = estimatedMemoryBytes(nq, b);
  if (bytes > ReachLimits::kMaxMemoryBytes) {
    std::ostringstream os;
    os << "ReachConfig: the check would need about " << std::lround(bytes / (1024 * 1024))
       << " MiB (initial_samples " << b.initial_samples << ", max_boundary " << b.max_boundary
       << ", children_per_parent " << b.children_per_parent << ", horizon " << horizon
       << " s at dt " << dt << " s), over the limit of "
       << std::lround(ReachLimits::kMaxMemoryBytes / (1024 * 1024)) << " MiB";
    throw ConfigError(os.str());
  }
}

namespace {

/// The keys that moved into reach.budgets, and the check's internal mode that left the file:
/// each an error naming its new place.
ConfigFields<ReachConfig>& addRemovedKeys(ConfigFields<ReachConfig>& f) {
  const auto moved = [](const std::string& key, const std::string& budget) {
    return "removed: now reach.budgets." + budget + "." + key +
           " (reach.budgets: {full, quick, hull}, docs/parameters.md)";
  };
  const char* budget_keys[] = {
      "initial_samples",  "children_per_parent", "backward_children_per_parent",
      "max_boundary",     "interior_samples",    "certificate_candidates",
      "constraint_margin"};
  for (const char* key : budget_keys) f.removed(key, moved(key, "full"));
  for (const char* key : budget_keys) f.removed(std::string("quick_") + key, moved(key, "quick"));
  f.removed("hull_initial_samples", moved("initial_samples", "hull"));
  f.removed("hull_children_per_parent", moved("children_per_parent", "hull"));
  f.removed("forward_set_only",
            "removed: the forward set alone is how the step planner's hull pass runs one check "
            "(CheckPass::sets, reach/sample_budget.h), not a setting of the file");
  return f;
}

}  // namespace

const ConfigFields<ReachConfig>& ReachConfig::fields() {
  using C = ReachConfig;
  static const ConfigFields<C> f = addRemovedKeys(
      ConfigFields<C>("ReachConfig", "reach", "include/reach_trajopt/reach/reach_config.h",
                      "The reachability check (eq. 13-21) and its certificate (docs/method.md "
                      "Sec. 4); the walk replaces `horizon` by walk.check_horizon.")
          .add("dt", &C::dt, "s", Range::positive(), "time step of (16) and (20) (paper: 1 ms)")
          .add("horizon", &C::horizon, "s", Range::positive(), "t_f - t_0, a multiple of dt")
          .add("window_start", &C::window_start, "s", Range::nonNegative(),
               "t_2: the backward set reaches back to here")
          .add("window_end", &C::window_end, "s", Range::nonNegative(),
               "t_1: the forward set reaches up to here; window_start <= window_end <= horizon")
          .nested("budgets", &C::budgets, ReachBudgets::fields())
          .add("angular_bins", &C::angular_bins, "", Range::nonNegative(),
               "bins per output plane (keeps concave parts)")
          .add("boundary_lookahead", &C::boundary_lookahead, "s", Range::nonNegative(),
               "tau of y + tau ydot in the boundary rule (each)")
          .add("vertex_fraction", &C::vertex_fraction, "", Range::between(0, 1),
               "share of bang-bang draws (antithetic pairs)")
          .add("redraw_rounds", &C::redraw_rounds, "", Range::nonNegative(),
               "extra rounds of draws at a step whose slice came out thin (0: fixed draws)")
          .add("redraw_below", &C::redraw_below, "", Range::between(0, 1),
               "share of max_boundary + interior_samples under which a slice is thin")
          .add("seed", &C::seed, "", "random stream (same results for any thread count)")
          .add("threads", &C::threads, "", Range::nonNegative(),
               "OpenMP threads, 0: OpenMP's default")
          .add("forward_integrator", &C::forward_integrator, "",
               "semi_implicit (the inverse of (20)) or explicit (eq. 16 as printed)")
          .add("w_qdd", &C::w_qdd, "1/(rad/s^2)^2", Range::positive(),
               "W_qdd of the forward QP (15)")
          .add("w_du", &C::w_du, "1/(N m)^2", Range::positive(), "W_u of (15)")
          .add("w_lambda", &C::w_lambda, "1/N^2", Range::positive(), "W_lambda of (15)")
          .add("contact_stabilization", &C::contact_stabilization, "", Range::between(0, 1),
               "beta of the drift stabilization (0: eq. 5 as printed)")
          .add("backward_joint_accel", &C::backward_joint_accel, "rad/s^2", Range::positive(),
               "a_max of the backward draws (17), actuated joints")
          .add("backward_base_accel", &C::backward_base_accel, "m/s^2 or rad/s^2",
               Range::positive(), "same for the floating-base coordinates")
          .add("backward_prefilter", &C::backward_prefilter, "",
               "reject single-support backward draws that the linearized (19) rejects by far, "
               "before their dynamics (same children)")
          .add("delta", &C::delta, "m", Range::nonNegative(),
               "Prop. 2 threshold (paper 1e-5), reported only")
          .add("overlap_gap_max", &C::overlap_gap_max, "m", Range::nonNegative(),
               "output sets meet when a pair is closer than min(K, this); reported only")
          .add("certificate_tolerance", &C::certificate_tolerance, "N, N m, m, rad",
               Range::positive(),
               "largest violation on a certified path of eq. (1), (8), the limits, the ground")
          .add("certificate_contact_velocity_tolerance", &C::certificate_contact_velocity_tolerance,
               "m/s, rad/s", Range::positive(), "|J qd| of the held soles on a certified path")
          .add("terminal_position_tolerance", &C::terminal_position_tolerance, "m, rad",
               Range::positive(), "|q(t_f) - q_f| of a certified path")
          .add("terminal_velocity_tolerance", &C::terminal_velocity_tolerance, "m/s, rad/s",
               Range::positive(), "|qd(t_f) - qd_f| of a certified path")
          .add("output_frame", &C::output_frame, "", "frame of y; empty: the swing sole")
          .add("output_axes", &C::output_axes, "", "world axes of the frame origin in y")
          .add("swing_ground_margin", &C::swing_ground_margin, "m",
               "the swing sole may not go below the target foothold minus this")
          .add("contact_tolerance", &C::contact_tolerance, "m, rad", Range::positive(),
               "|phi| allowed at x_0, x_f and along a certified path")
          .add("contact_velocity_tolerance", &C::contact_velocity_tolerance, "m/s, rad/s",
               Range::positive(), "|J qd| allowed at x_0 and x_f")
          .add("limit_tolerance", &C::limit_tolerance, "", Range::nonNegative(),
               "slack on the position / velocity / torque limits")
          .add("quick_pass", &C::quick_pass, "",
               "budgets.quick first, budgets.full only when it does not end the step (the step "
               "planner's passes) or the check (see give_up_gap); false: budgets.full alone")
          .add("give_up_gap", &C::give_up_gap, "terminal tolerances",
               "a check on its own stops after an uncertified quick budget whose closest "
               "attempt ends farther than this from x_f (0: never)")
          .add("quick_retry_constraint_margin", &C::quick_retry_constraint_margin, "m",
               Range::nonNegative(),
               "when the quick pass's strict OCP fails, solve it again in its hulls grown to "
               "this margin before the hull pass (0: no retry)")
          .add("hull_pass", &C::hull_pass, "",
               "when the quick pass's strict OCP fails, solve it again in the hulls of a forward "
               "set alone drawn with budgets.hull before the full pass"));
  return f;
}

ReachConfig ReachConfig::fromYaml(const YamlSection& s, const ReachConfig& base) {
  return fields().read(s, base);
}

ReachConfig ReachConfig::fromYaml(const YamlSection& s) { return fromYaml(s, ReachConfig()); }

}  // namespace reach_trajopt
