#pragma once
/// \file sample_budget.h
/// How many samples one pass of the reachability check draws and keeps (docs/method.md Sec. 4.2,
/// 4.6), and the schedule of passes that the step planner and the check on its own run.
///
/// A budget is data: ReachConfig::budgets holds three of them (YAML `reach: budgets: {full:
/// {...}, quick: {...}, hull: {...}}`), and a PassSchedule says which of them runs when:
///   - the check on its own (ReachabilityAnalyzer::check: the check service, reach_check,
///     bench/reach): quick, then full unless the quick budget certified the step or gave up
///     (give_up_gap);
///   - the step planner (FootstepTransitionPlanner::plan): quick, then [the wide hull retry],
///     the hull pass and the full pass, each only when the one before did not end the step.

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace reach_trajopt {

template <typename Config>
class ConfigFields;
struct ReachConfig;

/// The sample budget of one pass of the check (eq. 15-21 and the certificate).
/// Cost ~ QPs solved: initial_samples per direction at the first step, then per later step
/// (max_boundary + interior_samples) x children_per_parent (backward:
/// backward_children_per_parent).
struct SamplingBudget {
  int initial_samples = 10000;  ///< draws at the first step of each direction (paper: 1e4)
  int children_per_parent = 8;  ///< forward draws per kept sample at the later steps
  /// Backward draws per kept sample at the later steps: (19) rejects most draws of (17), so
  /// the backward direction draws more than the forward one (whose QP repairs its draws).
  int backward_children_per_parent = 24;
  int max_boundary = 96;  ///< boundary samples (21) kept per slice and propagated
  /// Interior samples kept and propagated besides the boundary ones (evenly spread over the
  /// slice): without them the later slices are thin shells around their sets.
  int interior_samples = 32;
  /// Junction pairs (a, b) bridged at most, lowest bridge effort first
  /// (witness_certificate.h); the verdict is "reachable" only when one gives a certified path.
  int certificate_candidates = 8;
  /// Eq. (23): the swing sole hulls of this pass's forward set handed to the OCP grow by this
  /// [m] (step/reachable_set_constraint.h); sparser budgets keep smaller hulls, so grow more.
  double constraint_margin = 0.01;

  /// Throws ConfigError "ReachConfig: <name>.<key> ..." for a value out of range (also over
  /// ReachLimits).
  void validate(const std::string& name = "budgets.full") const;
  /// Its YAML keys (one budget under `reach: budgets:`).
  static const ConfigFields<SamplingBudget>& fields();
};

/// A budget whose unset keys take another's: the hull pass's, over the full budget.
struct PartialSamplingBudget {
  std::optional<int> initial_samples, children_per_parent, backward_children_per_parent,
      max_boundary, interior_samples, certificate_candidates;
  std::optional<double> constraint_margin;
  /// `base` with the keys set here replaced.
  SamplingBudget over(const SamplingBudget& base) const;
  /// Its YAML keys (each optional: unset takes the full budget's).
  static const ConfigFields<PartialSamplingBudget>& fields();
};

/// The three budgets of ReachConfig (YAML `reach: budgets:`).
struct ReachBudgets {
  /// The full budget: the check's only one without the quick pass, its second one with it, and
  /// the step planner's last pass. The defaults are the paper's 1e4 first draws and ours.
  SamplingBudget full;
  /// The quick budget, drawn first (ReachConfig::quick_pass): about a tenth of the full one's
  /// QPs; its hulls keep 32 samples per slice against 128, so they grow more.
  SamplingBudget quick{1000, 4, 8, 24, 8, 4, 0.02};
  /// The hull pass's forward set (ReachConfig::hull_pass): the full budget with fewer first
  /// draws (its first step keeps only max_boundary + interior_samples of them as parents) and
  /// half the children per parent. Unset keys take the full budget's.
  PartialSamplingBudget hull{2500, 4, {}, {}, {}, {}, {}};
  /// The hull pass's budget: `hull` over `full`.
  SamplingBudget hullBudget() const { return hull.over(full); }
  /// Its YAML keys: the sections full, quick and hull.
  static const ConfigFields<ReachBudgets>& fields();
};

/// Which sets one pass of the check propagates.
enum class PassSets {
  kBoth,         ///< the forward and the backward set, the window test and the certificate
  kForwardOnly,  ///< the forward set alone (no verdict: "not shown reachable"): its hulls only
};

/// One pass of the check: its budget and its sets.
struct CheckPass {
  SamplingBudget budget;
  PassSets sets = PassSets::kBoth;
  /// With kForwardOnly: the forward set stops at the first step at or after this [s after
  /// t_0] when that is before window_end. Each draw is keyed by its step, so the slices it has
  /// are those of the whole window's, bit for bit.
  double forward_until_s = HUGE_VAL;
  bool forwardOnly() const { return sets == PassSets::kForwardOnly; }
};

/// The passes of the schedule (see the file comment).
enum class PassKind {
  kQuick,          ///< the quick budget's check (and, in the planner, its OCP)
  kWideHullRetry,  ///< the quick pass's strict OCP again in its own hulls grown (no sampling)
  kHull,           ///< the quick pass's strict OCP again in the hulls of the hull budget's
                   ///< forward set
  kFull,           ///< the full budget's check (and OCP)
};

/// One entry of a PassSchedule.
struct ScheduledPass {
  PassKind kind = PassKind::kFull;
  CheckPass check;  ///< the check it runs (kWideHullRetry: the quick one's, not run again)
  /// kWideHullRetry: the margin the quick hulls grow to [m] (more than the quick budget's).
  double retry_margin = 0.0;
};

/// Which passes run, in which order, with which budget; built from a ReachConfig by
/// forCheck() or forStepPlanner(), the one place that reads its pass switches.
struct PassSchedule {
  std::vector<ScheduledPass> passes;  ///< in order; the first always runs
  /// The check on its own stops after an uncertified first pass whose closest attempt ends
  /// more than this many terminal tolerances from x_f; 0: never (the step planner's).
  double give_up_gap = 0.0;
  /// ReachabilityAnalyzer::check: [quick ->] full, with give-up.
  static PassSchedule forCheck(const ReachConfig& config);
  /// FootstepTransitionPlanner::plan: quick -> [wide hull retry] -> [hull] -> full, or full
  /// alone without the quick pass (or without a reachability check).
  static PassSchedule forStepPlanner(const ReachConfig& config, bool check_reachability = true);
};

}  // namespace reach_trajopt
