/// \file sample_budget.cpp
/// Sample budgets, their YAML keys and the pass schedule (see the header).

#include "reach_trajopt/reach/sample_budget.h"

#include "reach_trajopt/common/config_fields.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/reach/reach_config.h"

namespace reach_trajopt {
namespace {

void requireInRange(const std::string& name, const char* key, long long v, long long min,
                    long long max, const char* why_min) {
  const std::string field = "ReachConfig: " + name + "." + key;
  if (v < min) throw ConfigError(field + " must be >= " + std::to_string(min) + why_min);
  if (v > max)
    throw ConfigError(field + " must be <= " + std::to_string(max) + " (docs/limits.md), got " +
                      std::to_string(v));
}

}  // namespace

void SamplingBudget::validate(const std::string& name) const {
  using L = ReachLimits;
  const char* zero = " (zero samples)";
  requireInRange(name, "initial_samples", initial_samples, 1, L::kMaxInitialSamples, zero);
  requireInRange(name, "children_per_parent", children_per_parent, 1, L::kMaxChildrenPerParent,
                 zero);
  requireInRange(name, "backward_children_per_parent", backward_children_per_parent, 1,
                 L::kMaxChildrenPerParent, zero);
  requireInRange(name, "max_boundary", max_boundary, 1, L::kMaxBoundary, "");
  requireInRange(name, "interior_samples", interior_samples, 0, L::kMaxBoundary, "");
  requireInRange(name, "certificate_candidates", certificate_candidates, 1,
                 L::kMaxCertificateCandidates, "");
  if (!std::isfinite(constraint_margin) || constraint_margin < 0.0)
    throw ConfigError("ReachConfig: " + name + ".constraint_margin must be >= 0 and finite, got " +
                      std::to_string(constraint_margin));
}

const ConfigFields<SamplingBudget>& SamplingBudget::fields() {
  using B = SamplingBudget;
  static const ConfigFields<B> f =
      ConfigFields<B>("SamplingBudget", "budget", "include/reach_trajopt/reach/sample_budget.h",
                      "One pass's sample budget.")
          .add("initial_samples", &B::initial_samples, "",
               "draws at the first step of each direction (paper: 1e4); one QP each")
          .add("children_per_parent", &B::children_per_parent, "",
               "forward draws per kept sample at later steps")
          .add("backward_children_per_parent", &B::backward_children_per_parent, "",
               "backward draws per kept sample (most are rejected by (19))")
          .add("max_boundary", &B::max_boundary, "", "boundary samples (21) kept per slice")
          .add("interior_samples", &B::interior_samples, "", "interior samples kept besides them")
          .add("certificate_candidates", &B::certificate_candidates, "",
               "junction pairs bridged at most (witness_certificate.h), >= 1")
          .add("constraint_margin", &B::constraint_margin, "m",
               "eq. (23): the pass's swing sole hulls handed to the OCP grow by this, >= 0");
  return f;
}

SamplingBudget PartialSamplingBudget::over(const SamplingBudget& base) const {
  SamplingBudget b = base;
  if (initial_samples) b.initial_samples = *initial_samples;
  if (children_per_parent) b.children_per_parent = *children_per_parent;
  if (backward_children_per_parent) b.backward_children_per_parent = *backward_children_per_parent;
  if (max_boundary) b.max_boundary = *max_boundary;
  if (interior_samples) b.interior_samples = *interior_samples;
  if (certificate_candidates) b.certificate_candidates = *certificate_candidates;
  if (constraint_margin) b.constraint_margin = *constraint_margin;
  return b;
}

const ConfigFields<PartialSamplingBudget>& PartialSamplingBudget::fields() {
  using B = PartialSamplingBudget;
  const char* unset = " (unset: the full budget's)";
  static const ConfigFields<B> f =
      ConfigFields<B>("PartialSamplingBudget", "budget",
                      "include/reach_trajopt/reach/sample_budget.h",
                      "A sample budget whose unset keys take the full budget's.")
          .add("initial_samples", &B::initial_samples, "",
               std::string("draws at the first step of its forward set") + unset)
          .add("children_per_parent", &B::children_per_parent, "",
               std::string("forward draws per kept sample at later steps") + unset)
          .add("backward_children_per_parent", &B::backward_children_per_parent, "",
               std::string("backward draws per kept sample") + unset)
          .add("max_boundary", &B::max_boundary, "",
               std::string("boundary samples (21) kept per slice") + unset)
          .add("interior_samples", &B::interior_samples, "",
               std::string("interior samples kept besides them") + unset)
          .add("certificate_candidates", &B::certificate_candidates, "",
               std::string("junction pairs bridged at most") + unset)
          .add("constraint_margin", &B::constraint_margin, "m",
               std::string("eq. (23): its hulls grow by this") + unset);
  return f;
}

const ConfigFields<ReachBudgets>& ReachBudgets::fields() {
  using B = ReachBudgets;
  static const ConfigFields<B> f =
      ConfigFields<B>("ReachBudgets", "budgets", "include/reach_trajopt/reach/sample_budget.h",
                      "The sample budgets of the check's passes.")
          .nested("full", &B::full, SamplingBudget::fields())
          .nested("quick", &B::quick, SamplingBudget::fields())
          .nested("hull", &B::hull, PartialSamplingBudget::fields());
  return f;
}

PassSchedule PassSchedule::forCheck(const ReachConfig& config) {
  PassSchedule s;
  if (config.quick_pass) {
    s.passes.push_back({PassKind::kQuick, {config.budgets.quick}, 0.0});
    s.give_up_gap = config.give_up_gap;
  }
  s.passes.push_back({PassKind::kFull, {config.budgets.full}, 0.0});
  return s;
}

PassSchedule PassSchedule::forStepPlanner(const ReachConfig& config, bool check_reachability) {
  PassSchedule s;
  if (!check_reachability || !config.quick_pass) {
    s.passes.push_back({PassKind::kFull, {config.budgets.full}, 0.0});
    return s;
  }
  const SamplingBudget& quick = config.budgets.quick;
  s.passes.push_back({PassKind::kQuick, {quick}, 0.0});
  if (config.quick_retry_constraint_margin > quick.constraint_margin)
    s.passes.push_back({PassKind::kWideHullRetry, {quick}, config.quick_retry_constraint_margin});
  if (config.hull_pass)
    s.passes.push_back(
        {PassKind::kHull, {config.budgets.hullBudget(), PassSets::kForwardOnly}, 0.0});
  s.passes.push_back({PassKind::kFull, {config.budgets.full}, 0.0});
  return s;
}

}  // namespace reach_trajopt
