/// \file reachability_analyzer.cpp
/// The bidirectional reachability check (see the header).

#include "reach_trajopt/reach/reachability_analyzer.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/common/format_number.h"
#include "reach_trajopt/common/stopwatch.h"
#include "reach_trajopt/reach/reach_context.h"
#include "reach_trajopt/reach/set_propagation.h"
#include "reach_trajopt/reach/witness_certificate.h"

namespace reach_trajopt {

namespace {

/// Throws ReachError when (q, qd) violates the limits or the held contacts.
void validateState(const ReachContext& ctx, const char* which, const Eigen::VectorXd& q,
                   const Eigen::VectorXd& qd, const std::vector<ContactConstraint>& contacts) {
  const RobotModel& model = *ctx.model;
  try {
    model.checkState(q, qd);
  } catch (const ReachError& e) {
    throw ReachError(std::string("reachability: ") + which + ": " + e.what());
  }
  const double tol = std::max(ctx.config.limit_tolerance, 1e-9);
  for (int i : ctx.finite_position)
    if (q[i] < ctx.q_min[i] - tol || q[i] > ctx.q_max[i] + tol)
      throw ReachError(std::string("reachability: ") + which + " violates the position limits of " +
                       model.joints()[i].name + " (q = " + formatNumber(q[i], 6) + ", limits [" +
                       formatNumber(ctx.q_min[i], 6) + ", " + formatNumber(ctx.q_max[i], 6) + "])");
  for (int i : ctx.finite_velocity)
    if (std::abs(qd[i]) > ctx.qd_max[i] + tol)
      throw ReachError(std::string("reachability: ") + which + " violates the velocity limit of " +
                       model.joints()[i].name + " (|qd| = " + formatNumber(std::abs(qd[i]), 6) +
                       " > " + formatNumber(ctx.qd_max[i], 6) + ")");
  Workspace ws(model);
  model.update(ws, q, qd);
  ContactConstraintTerms t(model.nq());
  for (const ContactConstraint& c : contacts) {
    c.evaluate(model, ws, t);
    const std::string frame = model.frameNames()[c.frame()];
    if (t.phi.cwiseAbs().maxCoeff() > ctx.config.contact_tolerance)
      throw ReachError(std::string("reachability: ") + which + " violates the contact of " + frame +
                       " (|phi| = " + formatNumber(t.phi.cwiseAbs().maxCoeff()) +
                       " > contact_tolerance " + formatNumber(ctx.config.contact_tolerance) + ")");
    if (t.phidot.cwiseAbs().maxCoeff() > ctx.config.contact_velocity_tolerance)
      throw ReachError(std::string("reachability: ") + which + " moves the held sole " + frame +
                       " (|J qd| = " + formatNumber(t.phidot.cwiseAbs().maxCoeff()) +
                       " > contact_velocity_tolerance " +
                       formatNumber(ctx.config.contact_velocity_tolerance) + ")");
  }
}

/// The sentence explaining the verdict: the certificate, then what the sets showed.
std::string verdictReason(const SamplingBudget& budget, const std::vector<SliceComparison>& window,
                          int best, bool sets_meet, const WitnessPath& w) {
  std::ostringstream os;
  if (w.certified) {
    os << "reachable: certified path x_0 -> x_f, the forward sample at t = "
       << formatNumber(w.time[w.bridge_start]) << " s bridged to x_f (largest violation "
       << formatNumber(w.violation.max()) << ", x(t_f) - x_f "
       << formatNumber(w.terminal_position_gap) << " / " << formatNumber(w.terminal_velocity_gap)
       << ", pair " << w.candidates_tried << " of " << budget.certificate_candidates << ")";
    return os.str();
  }
  os << "unreachable (not shown reachable): ";
  if (best < 0) {
    os << "a forward or backward slice of the window is empty (every draw was rejected)";
    return os.str();
  }
  const SliceComparison& c = window[best];
  if (!w.valid)
    os << "no junction pair to bridge (the window must end at least 2 dt before t_f)";
  else if (std::isinf(w.terminal_position_gap))
    os << "no bridge of the " << w.candidates_tried << " best junction pairs reached t_f";
  else
    os << "no bridge of the " << w.candidates_tried << " best junction pairs ended on x_f "
       << "(closest: x(t_f) - x_f " << formatNumber(w.terminal_position_gap) << " / "
       << formatNumber(w.terminal_velocity_gap) << ", swing sole "
       << formatNumber(w.terminal_output_gap) << " m from the target, largest violation "
       << formatNumber(w.violation.max()) << ")";
  os << "; the output sets " << (sets_meet ? "meet" : "stay apart") << " (closest approach "
     << formatNumber(c.distance.closest) << " m at t = " << formatNumber(c.time) << " s, d_H "
     << formatNumber(c.distance.hausdorff) << " m)";
  return os.str();
}

/// Adds each of `members` of `from` to the same member of `to` (the counts or times of two
/// sample budgets).
template <class Struct, class Value, std::size_t N>
void addMembers(Struct& to, const Struct& from, Value Struct::*const (&members)[N]) {
  for (Value Struct::*m : members) to.*m += from.*m;
}

}  // namespace

void ReachCounts::add(const ReachCounts& o) {
  using C = ReachCounts;
  static constexpr long C::*kSummed[] = {
      &C::forward_samples,  &C::backward_samples,  &C::forward_qps,         &C::backward_qps,
      &C::forward_rejected, &C::backward_rejected, &C::backward_prefiltered};
  addMembers(*this, o, kSummed);
}

void ReachTimings::add(const ReachTimings& o) {
  using T = ReachTimings;
  static constexpr double T::*kSummed[] = {&T::forward,   &T::backward, &T::boundary,
                                           &T::hausdorff, &T::witness,  &T::total};
  addMembers(*this, o, kSummed);
}

ReachabilityAnalyzer::ReachabilityAnalyzer(std::shared_ptr<const RobotModel> model,
                                           const ContactConfig& contact, const ReachConfig& config)
    : model_(std::move(model)), contact_(contact), config_(config) {
  if (!model_) throw ReachError("ReachabilityAnalyzer: null model");
  contact_.validate();
  config_.validate();
}

ReachResult ReachabilityAnalyzer::check(const ReachProblem& problem) const {
  return check(problem, config_);
}

Eigen::VectorXd ReachabilityAnalyzer::sampleConfiguration(const ReachResult& result, bool forward,
                                                          int slice, int index) const {
  return sampleConfigurationOf(
      forward ? result.forward : result.backward,
      forward ? PropagationDirection::kForward : PropagationDirection::kBackward, result.dt,
      result.semi_implicit, slice, index);
}

ReachResult ReachabilityAnalyzer::check(const ReachProblem& pb, const ReachConfig& config,
                                        const ReachProgressCallback& progress) const {
  const PassSchedule schedule = PassSchedule::forCheck(config);
  const CheckPass& first_pass = schedule.passes.front().check;
  if (schedule.passes.size() == 1) return checkPass(pb, config, first_pass, progress);
  config.validate();  // names a bad key of the whole configuration, not of the quick budget's
  ReachResult quick = checkPass(pb, config, first_pass, progress);
  if (quick.reachable) return quick;
  const double gap = terminalGapInTolerances(config, quick.witness);
  if (schedule.give_up_gap > 0.0 && std::isfinite(gap) && gap > schedule.give_up_gap) {
    quick.gave_up = true;
    quick.reason = "the quick budget's closest attempt ended " + formatNumber(gap) +
                   " terminal tolerances from x_f (give_up_gap " +
                   formatNumber(schedule.give_up_gap) +
                   "), the full budget not drawn: " + quick.reason;
    return quick;
  }
  const ReachCounts quick_counts = quick.counts;
  const ReachTimings quick_timings = quick.timings;
  quick = ReachResult();  // its sets are not returned: freed before the full budget's
  ReachResult full = checkPass(pb, config, schedule.passes.back().check, progress);
  full.budgets = 2;
  full.counts.add(quick_counts);
  full.timings.add(quick_timings);
  full.reason = "the quick budget certified nothing (closest attempt " + formatNumber(gap) +
                " terminal tolerances from x_f), the full budget: " + full.reason;
  return full;
}

ReachResult ReachabilityAnalyzer::checkPass(const ReachProblem& pb, const ReachConfig& config_in,
                                            const CheckPass& pass,
                                            const ReachProgressCallback& progress) const {
  const auto t_start = SteadyClock::now();
  ReachConfig config = config_in;
  if (pass.forwardOnly() && pass.forward_until_s >= 0.0 &&
      pass.forward_until_s < config.window_end) {
    // The forward set up to the first step at or after forward_until_s, on the grid.
    config.window_end =
        std::max(1.0, std::ceil(pass.forward_until_s / config.dt - 1e-6)) * config.dt;
    config.window_start = std::min(config.window_start, config.window_end);  // no backward set
  }
  config.validate();
  pass.budget.validate("budget");
  config.requireResourcesWithinLimits(model_->nq(), pass.budget);  // before any sample is drawn
  ReachContext ctx(model_, contact_, config, pass.budget, pb.mode, pb.footholds, pb.target);
  ctx.startAt(pb.q0);
  const RobotModel& model = *model_;
  // ---- input checks ---------------------------------------------------------------------
  validateState(ctx, "x_0", pb.q0, pb.qd0, ctx.contacts);
  std::vector<ContactConstraint> final_contacts = ctx.contacts;
  if (pb.target) {
    if (!pb.mode.isSingleSupport())
      throw ReachError("reachability: a target foothold needs a single-support mode, got " +
                       pb.mode.name());
    final_contacts.emplace_back(model, contact_.soleFrame(pb.mode.swing()), *pb.target);
  }
  validateState(ctx, "x_f", pb.qf, pb.qdf, final_contacts);

  const double dt = config.dt;
  const int i_t = static_cast<int>(std::lround(config.horizon / dt));
  const int i_1 = static_cast<int>(std::lround(config.window_end / dt));
  const int i_2 = static_cast<int>(std::lround(config.window_start / dt));
  const int n_fwd = i_1;        // forward steps
  const int n_bwd = i_t - i_2;  // backward steps

  ReachResult res;
  res.dt = dt;
  res.semi_implicit = config.semiImplicit();
  for (const JointInfo& j : model.joints()) res.joint_names.push_back(j.name);
  const int threads = config.threads > 0 ? config.threads : omp_get_max_threads();
  res.counts.threads = threads;

  // ---- forward set (15)-(16) and backward set (17)-(20), side by side --------------------
  DirectionSet fwd{{PropagationDirection::kForward, 0, pb.q0, pb.qd0, n_fwd}, {}, {}};
  DirectionSet bwd{{PropagationDirection::kBackward, i_t, pb.qf, pb.qdf, n_bwd}, {}, {}};
  std::vector<DirectionSet*> sets{&fwd};
  if (!pass.forwardOnly()) sets.push_back(&bwd);  // the hull pass: the forward set alone
  propagateSets(ctx, sets, threads, progress);
  res.forward = std::move(fwd.slices);
  res.backward = std::move(bwd.slices);
  res.counts.forward_samples = fwd.stats.samples;
  res.counts.forward_rejected = fwd.stats.rejected;
  res.counts.forward_qps = fwd.stats.qps;
  res.counts.backward_samples = bwd.stats.samples;
  res.counts.backward_rejected = bwd.stats.rejected;
  res.counts.backward_qps = bwd.stats.qps;
  res.counts.backward_prefiltered = bwd.stats.prefiltered;
  res.timings.forward = fwd.stats.propagation_time;
  res.timings.backward = bwd.stats.propagation_time;
  res.timings.boundary = fwd.stats.boundary_time + bwd.stats.boundary_time;
  if (pass.forwardOnly()) {
    res.reason = "not checked: the forward set only (PassSets::kForwardOnly, the hull pass)";
  } else {
    // ---- the test (14) on the overlap window ----------------------------------------------
    const auto th = SteadyClock::now();
    res.window = compareWindow(config, res.forward, res.backward, i_2, i_1, i_t);
    res.timings.hausdorff = secondsSince(th);
    // ---- verdict and witness --------------------------------------------------------------
    const auto tw = SteadyClock::now();
    res.best = decidingSlice(res.window, res.sets_meet);
    res.witness = certifyWitness(ctx, res.forward, res.backward, res.window, res.semi_implicit);
    res.reachable = res.witness.certified;
    res.reason = verdictReason(pass.budget, res.window, res.best, res.sets_meet, res.witness);
    res.timings.witness = secondsSince(tw);
  }
  res.timings.total = secondsSince(t_start);
  return res;
}

}  // namespace reach_trajopt
