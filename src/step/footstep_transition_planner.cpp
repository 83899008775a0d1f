/// \file footstep_transition_planner.cpp
/// The per-step pipeline: contact-consistent x_0, kinematic check, reachability check, OCP,
/// fallback (see the header).

#include "reach_trajopt/step/footstep_transition_planner.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/stopwatch.h"
#include "reach_trajopt/planner/double_support_velocity.h"
#include "reach_trajopt/step/contact_consistent_state.h"
#include "reach_trajopt/step/reachable_set_constraint.h"

namespace reach_trajopt {
namespace {

/// The mean wall time of one of `step`'s check passes [s]: what a candidate's first pass needs
/// before the deadline (FootstepPlanRequest::hasTimeFor).
double meanPassSeconds(const FootstepTransition& step) {
  return step.check_time_s / std::max(1, step.check_passes);
}

/// The retreat's kinematic scan: points per candidate batch (a message to the workers carries
/// at most 360; retreat_kinematic_points may be up to 1000).
constexpr int kRetreatPointsPerBatch = 64;

StepVerdict verdictOf(const FootstepCheckResult& check, bool checked) {
  if (!check.kinematically_feasible) return StepVerdict::kKinematicallyInfeasible;
  if (!checked) return StepVerdict::kKinematicallyFeasible;  // the kinematic check only
  return check.reachable ? StepVerdict::kReachable : StepVerdict::kUnreachable;
}

RelaxationMode relaxationFor(OcpPolicy policy, bool reachable) {
  switch (policy) {
    case OcpPolicy::kStrict:
      return RelaxationMode::kStrict;
    case OcpPolicy::kAuto:
      return RelaxationMode::kAuto;
    case OcpPolicy::kByVerdict:
      break;
  }
  return reachable ? RelaxationMode::kStrict : RelaxationMode::kAuto;
}

/// A certified candidate standing in for the target of `r` (kNearestReachable): its request,
/// the target's verdict, its source; `where` (how far from the target, and how found) leads
/// its reason.
void standInForTarget(FootstepTransition& step, const FootstepPlanRequest& r,
                      const FootstepTransition& target, const char* where) {
  step.request = r;
  step.target_verdict = target.verdict;
  step.foothold_source = FootholdSource::kNearestReachable;
  step.reason = where + step.reason + "; the target: " + target.reason;
}

/// The witness path x_0 -> x_f as the OCP's initial guess.
void seedFromWitness(const ReachResult& reach, TransitionRequest& ocp) {
  if (!reach.witness.valid) return;
  const WitnessPath& w = reach.witness;
  ocp.seed.time =
      Eigen::Map<const Eigen::VectorXd>(w.time.data(), static_cast<Eigen::Index>(w.time.size()));
  ocp.seed.q = w.q;
}

}  // namespace

FootstepPlannerConfig FootstepPlannerConfig::fromYaml(const YamlSection& root) {
  FootstepPlannerConfig c;
  if (root.has("kinematic_feasibility"))
    c.kinematics = KinematicFeasibilityConfig::fromYaml(root.section("kinematic_feasibility"));
  if (root.has("reach")) c.reach = ReachConfig::fromYaml(root.section("reach"));
  if (root.has("ocp")) c.ocp = TransitionOcpConfig::fromYaml(root.section("ocp"));
  // The robot's pelvis height is written once: the relaxed OCP lands at the IK's height.
  c.ocp.terminal_pelvis_height = c.kinematics.pelvis_height;
  if (root.has("nearest_foothold"))
    c.nearest_foothold = NearestFootholdConfig::fromYaml(root.section("nearest_foothold"));
  return c;
}

FootstepTransitionPlanner::FootstepTransitionPlanner(std::shared_ptr<const RobotModel> model,
                                                     const ContactConfig& contact,
                                                     const FootstepPlannerConfig& config)
    : model_(model),
      contact_(contact),
      config_(config),
      kinematics_(std::make_shared<KinematicFeasibility>(model, config.kinematics, contact)),
      footsteps_(std::make_shared<ReachabilityAnalyzer>(model, contact, config.reach), kinematics_),
      nearest_(kinematics_, config.nearest_foothold),
      ocp_(model, config.ocp, contact) {}

FootstepTransition FootstepTransitionPlanner::plan(const FootstepPlanRequest& r,
                                                   const FootstepPlanProgress& progress) const {
  if (r.on_infeasible != InfeasibleFootholdPolicy::kNearestReachable)
    return planTarget(r, progress);
  if (r.check_reachability) return planNearestReachable(r, progress);
  FootstepPlanRequest kinematic = r;  // the nearest foothold that passes the kinematic check
  kinematic.on_infeasible = InfeasibleFootholdPolicy::kNearestFeasible;
  return planTarget(kinematic, progress);
}

FootstepTransition FootstepTransitionPlanner::planNearestReachable(
    const FootstepPlanRequest& r, const FootstepPlanProgress& progress) const {
  FootstepPlanRequest at = r;
  at.on_infeasible = InfeasibleFootholdPolicy::kNoFallback;
  // The target's relaxed OCP is solved only when its plan is the answer (deferred): a certified
  // candidate makes it useless (TALOS's demo walk: 0.8 of a step's 1.8 s of OCPs).
  std::optional<TransitionRequest> target_ocp;
  FootstepTransition target = planTarget(at, progress, RelaxedFallback::kNever, &target_ocp);
  if (target.reachable && hasStrictTrajectory(r, target)) return target;
  // A certified target whose strict OCP failed in every pass stays the foothold: its
  // certificate's witness is a path x_0 -> x_f checked at every 1 ms step, so the target is
  // reachable; a candidate would step elsewhere for a trajectory only (TALOS's demo walk: 0.5 s
  // of candidates for a step 2 cm away). The swing goes there without a trajectory.
  if (target.reachable) {
    solveDeferredRelaxed(r, target_ocp, progress, target);
    target.reason =
        "certified, no strict trajectory (the target kept, no candidate checked): " + target.reason;
    return target;
  }
  // The candidates together keep nearest_foothold.time_limit (or the request's earlier
  // deadline): each one's OCP would otherwise have its own (TALOS: 18 s for a step's candidates).
  const auto search_deadline =
      secondsAfter(SteadyClock::now(), config_.nearest_foothold.time_limit);
  if (!at.deadline || search_deadline < *at.deadline) at.deadline = search_deadline;
  PassTotals totals = PassTotals::of(target);
  auto carryTotals = [&](FootstepTransition& step, int checked) {
    totals.stampOn(step);
    step.candidates_checked = checked;
  };
  // The rings around the target, nearest first; each ring's kinematic checks as one batch.
  FootholdCandidates batch = candidateBatch(target.transition);
  std::optional<FootstepTransition> nearest_feasible;  // the first feasible candidate's plan
  int checked = 0;  // every candidate's check, the rings' and the retreat's
  // A target beyond the leg's reach (kinematically infeasible): its rings' points lie at the
  // edge of that reach, so the retreat toward the swing sole is tried first.
  const bool retreat_first = !target.kinematically_feasible;
  if (retreat_first) {
    if (std::optional<FootstepTransition> retreat =
            planRetreat(r, at, target, progress, totals, checked)) {
      carryTotals(*retreat, checked);
      return std::move(*retreat);
    }
  }
  const NearestFootholdConfig& rings = nearest_.config();
  int ring_checked = 0;
  const double pass_s = meanPassSeconds(target);
  for (int ring = 1;
       ring <= rings.rings && ring_checked < rings.max_checked && at.hasTimeFor(pass_s); ++ring) {
    batch.candidates = nearest_.ringCandidates(r.target, ring);
    const std::vector<CandidateOutcome> outcomes = checkCandidates(batch, false);
    for (std::size_t i = 0;
         i < outcomes.size() && ring_checked < rings.max_checked && at.hasTimeFor(pass_s); ++i) {
      if (!outcomes[i].feasible()) continue;
      FootstepPlanRequest candidate = at;
      candidate.target = batch.candidates[i];
      // Only a certified strict trajectory ends the search; a relaxed one is used only as the
      // first feasible candidate's, kept for a kinematically infeasible target (below).
      const bool may_be_kept = !target.kinematically_feasible && !nearest_feasible;
      FootstepTransition step =
          planTarget(candidate, progress,
                     may_be_kept ? RelaxedFallback::kAsRequested : RelaxedFallback::kNever);
      ++checked;
      ++ring_checked;
      totals.add(step);
      if (step.reachable && hasStrictTrajectory(r, step)) {
        carryTotals(step, checked);
        char where[96];
        std::snprintf(where, sizeof where, "nearest reachable foothold, %.3f m from the target: ",
                      ring * rings.ring_step);
        standInForTarget(step, r, target, where);
        return step;
      }
      if (!nearest_feasible) nearest_feasible = std::move(step);
    }
  }
  // None of the rings' candidates certified: points toward where the swing sole comes from.
  if (!retreat_first) {
    if (std::optional<FootstepTransition> retreat =
            planRetreat(r, at, target, progress, totals, checked)) {
      carryTotals(*retreat, checked);
      return std::move(*retreat);
    }
  }
  // None certified: the target's own plan when feasible (its relaxed OCP), else the nearest
  // feasible candidate's; both uncertified.
  const bool from_candidate = !target.kinematically_feasible && nearest_feasible;
  FootstepTransition kept = from_candidate ? std::move(*nearest_feasible) : std::move(target);
  // The target's own plan: within the request's deadline, not the candidates' search's.
  if (!from_candidate) totals.ocp_time_s += solveDeferredRelaxed(r, target_ocp, progress, kept);
  carryTotals(kept, checked);
  kept.request = r;
  if (from_candidate) {
    kept.target_verdict = target.verdict;
    if (kept.foothold_source == FootholdSource::kTarget)
      kept.foothold_source = FootholdSource::kNearestFeasible;
  }
  kept.reason = "no reachable foothold among the " + std::to_string(checked) +
                " nearest feasible candidates checked" +
                (at.hasTimeFor(pass_s) ? "" : " (deadline reached)") + ": " + kept.reason;
  return kept;
}

FootholdCandidates FootstepTransitionPlanner::candidateBatch(const ContactTransition& t) {
  FootholdCandidates batch;
  batch.stance = t.stance;
  batch.stance_contact = t.stance_contact;
  batch.q_init = t.q0;
  batch.pelvis_position = t.touchdown.pelvis_position;
  return batch;
}

std::vector<CandidateOutcome> FootstepTransitionPlanner::checkCandidates(
    const FootholdCandidates& batch, bool stop_at_first_decisive) const {
  return candidate_check_ ? candidate_check_(batch)
                          : checkFootholdCandidates(*kinematics_, batch, stop_at_first_decisive);
}

std::optional<FootstepTransition> FootstepTransitionPlanner::planRetreat(
    const FootstepPlanRequest& r, const FootstepPlanRequest& at, const FootstepTransition& target,
    const FootstepPlanProgress& progress, PassTotals& totals, int& checked) const {
  const int checks = config_.nearest_foothold.retreat_checks;
  const double pass_s = meanPassSeconds(target);
  if (checks <= 0 || !at.hasTimeFor(pass_s)) return std::nullopt;
  // The swing sole's position at x_0, at the target's height: the foot was standing there.
  const RobotModel& m = *model_;
  const ContactTransition& t = target.transition;
  Workspace ws(m);
  m.update(ws, t.q0, Eigen::VectorXd::Zero(m.nq()));
  Eigen::Vector3d from = m.framePose(ws, m.frameId(contact_.soleFrame(t.moving()))).translation();
  from.z() = r.target.position.z();
  auto pointAt = [&](double s) {
    FlatContact p = r.target;
    p.position = r.target.position + s * (from - r.target.position);
    return p;
  };
  // Bisection on the segment target -> from: s = 0 (the target) is not certified; the
  // certified point nearest it is kept.
  double lo = 0.0, hi = 1.0;
  std::optional<double> first_s;  // where the bisection starts, when not at the middle
  const int grid_points = config_.nearest_foothold.retreat_kinematic_points;
  if (!target.kinematically_feasible && grid_points > 0) {
    // A target beyond the kinematic check (Sec. III-B): so are the points of the segment nearer
    // it than the first one that passes, and the check decides them before drawing a sample.
    // The kinematic check alone (an IK each, milliseconds) finds that point among grid_points
    // points of the segment, nearest the target first; the reachability check starts there
    // (one check when it certifies that point), then bisects beyond it. The points not yet
    // decided go as one batch (one round trip to the workers), whose answer ends at its first
    // feasible or failed point (a point outside the workspace fails with an error); the next
    // batch starts after a failed one.
    FootholdCandidates batch = candidateBatch(t);
    int next = 1;  // the first point not decided yet
    while (next <= grid_points && !first_s && !at.pastDeadline()) {
      batch.candidates.clear();
      for (int i = next; i <= std::min(grid_points, next + kRetreatPointsPerBatch - 1); ++i)
        batch.candidates.push_back(pointAt(static_cast<double>(i) / grid_points));
      const std::vector<CandidateOutcome> outcomes = checkCandidates(batch, true);
      if (outcomes.empty()) ++next;  // nothing decided: that point counts as failed
      for (const CandidateOutcome& o : outcomes) {
        if (o.feasible()) {
          lo = static_cast<double>(next - 1) / grid_points;
          first_s = static_cast<double>(next) / grid_points;
          break;
        }
        ++next;
      }
    }
    if (!first_s) return std::nullopt;  // no point of the segment passes the kinematic check
  }
  std::optional<FootstepTransition> best;
  for (int k = 0; k < checks && at.hasTimeFor(pass_s); ++k) {
    const double s = k == 0 && first_s ? *first_s : 0.5 * (lo + hi);
    FootstepPlanRequest candidate = at;
    candidate.target = pointAt(s);
    // Only a certified strict trajectory is kept: no relaxed OCP for a retreat point.
    FootstepTransition step = planTarget(candidate, progress, RelaxedFallback::kNever);
    ++checked;
    totals.add(step);
    if (step.reachable && hasStrictTrajectory(r, step)) {
      hi = s;
      best = std::move(step);
      if (k == 0 && first_s) break;  // every point nearer the target failed the kinematic check
    } else {
      lo = s;
    }
  }
  if (!best) return std::nullopt;
  char where[128];
  std::snprintf(where, sizeof where,
                "nearest reachable foothold toward the swing sole, %.3f m from the target: ",
                (best->foothold - r.target.position).head<2>().norm());
  standInForTarget(*best, r, target, where);
  return best;
}

FootstepTransition FootstepTransitionPlanner::planTarget(
    const FootstepPlanRequest& r, const FootstepPlanProgress& progress,
    RelaxedFallback relaxed_fallback, std::optional<TransitionRequest>* full_pass_ocp) const {
  if (full_pass_ocp) full_pass_ocp->reset();
  const RobotModel& m = *model_;
  m.checkState(r.q0, r.qd0);
  requireFinite("FootstepTransitionPlanner: target", r.target.position);
  if (r.touchdown_com) {
    requireFinite("FootstepTransitionPlanner: touchdown CoM position", r.touchdown_com->p);
    requireFinite("FootstepTransitionPlanner: touchdown CoM velocity", r.touchdown_com->pd);
  }
  const ReachConfig& reach = r.reach ? *r.reach : config_.reach;
  // Which passes run, in which order, with which budget (sample_budget.h): the quick pass,
  // then, each only when the one before did not end the step, the wide hull retry, the hull
  // pass and the full pass; or the full pass alone.
  const PassSchedule schedule = PassSchedule::forStepPlanner(reach, r.check_reachability);
  const ScheduledPass& first = schedule.passes.front();
  if (progress.pass) progress.pass(1);
  if (first.kind != PassKind::kQuick)
    return planWith(r, reach, first.check, progress, relaxed_fallback, nullptr, full_pass_ocp);
  // The quick pass first. It is final when it certified the step and (when asked for) its
  // strict OCP converged: the sparser forward set's hulls (eq. 23) can leave a certified step
  // without a trajectory. A kinematically infeasible foothold is decided before any sample is
  // drawn: its quick pass is final too.
  bool keep_slices = false;  // for the wide hull retry only
  for (const ScheduledPass& p : schedule.passes) keep_slices |= p.kind == PassKind::kWideHullRetry;
  std::vector<ReachableSlice> quick_slices;
  // An uncertified quick pass is final only when its strict OCP converges (the local solve):
  // a relaxed trajectory of it would be replaced by the passes that follow.
  const RelaxedFallback quick_fallback = relaxed_fallback == RelaxedFallback::kNever
                                             ? RelaxedFallback::kNever
                                             : RelaxedFallback::kWhenCertified;
  FootstepTransition quick = planWith(r, reach, first.check, progress, quick_fallback,
                                      keep_slices ? &quick_slices : nullptr);
  if (!quick.kinematically_feasible || (quick.reachable && hasStrictTrajectory(r, quick)))
    return quick;
  // A later pass starts only with at least the quick pass's time left (hasTimeFor).
  const double pass_s = quick.check_time_s;
  if (!r.hasTimeFor(pass_s)) {
    quick.reason = "deadline reached after the quick pass: " + quick.reason;
    return quick;
  }
  PassTotals totals = PassTotals::of(quick);
  for (std::size_t i = 1; i + 1 < schedule.passes.size(); ++i) {
    std::optional<FootstepTransition> retried = retryQuickOcp(
        r, reach, schedule.passes[i], first.check, quick, quick_slices, progress, totals);
    if (retried) return std::move(*retried);
    if (!r.hasTimeFor(pass_s)) {
      totals.stampOn(quick);
      quick.reason = "deadline reached before the full pass: " + quick.reason;
      return quick;
    }
  }
  ++totals.passes;
  if (progress.pass) progress.pass(totals.passes);
  // The full budget alone: its check does not draw the quick budget again (and never gives up).
  FootstepTransition full = planWith(r, reach, schedule.passes.back().check, progress,
                                     relaxed_fallback, nullptr, full_pass_ocp);
  // A certificate is never given up: when only the quick pass found one, its plan stands.
  FootstepTransition& kept = quick.reachable && !full.reachable ? quick : full;
  if (&kept == &quick && full_pass_ocp) full_pass_ocp->reset();
  const char* why = quick.reachable ? "the quick pass's certified step has no strict trajectory"
                                    : "the quick pass certified nothing";
  totals.check_time_s += full.check_time_s;
  totals.ocp_time_s += full.ocp_time_s;
  totals.stampOn(kept);
  kept.reason =
      std::string(why) + (&kept == &full ? ", the full budget: " : ", kept: ") + kept.reason;
  return kept;
}

std::optional<FootstepTransition> FootstepTransitionPlanner::retryQuickOcp(
    const FootstepPlanRequest& r, const ReachConfig& reach, const ScheduledPass& pass,
    const CheckPass& quick_pass, const FootstepTransition& quick,
    std::vector<ReachableSlice>& quick_slices, const FootstepPlanProgress& progress,
    PassTotals& totals) const {
  // A retry of the quick pass's OCP ends the step when it gives a certified strict trajectory:
  // the step then carries the sums of every pass and says which retry solved it.
  auto endsStep = [&](FootstepTransition& retry, const std::string& how) {
    if (!retry.reachable || !hasStrictTrajectory(r, retry)) return false;
    totals.stampOn(retry);
    retry.reason =
        "the quick pass's strict OCP failed in its hulls, solved in " + how + ": " + retry.reason;
    return true;
  };
  if (pass.kind == PassKind::kWideHullRetry) {
    // The quick pass's strict OCP again, in its own hulls grown more (with or without a witness
    // to seed it: a slice of the quick window can be empty while its forward hulls hold the
    // OCP).
    if (!r.solve_ocp || quick_slices.empty()) return std::nullopt;
    ++totals.passes;
    if (progress.pass) progress.pass(totals.passes);
    const double extra_margin = pass.retry_margin - quick_pass.budget.constraint_margin;
    FootstepTransition wide =
        solveInGrownHulls(r, quick, std::move(quick_slices), extra_margin, progress);
    totals.ocp_time_s += wide.ocp_time_s;
    char margin[32];
    std::snprintf(margin, sizeof margin, "%g m", pass.retry_margin);
    if (endsStep(wide, std::string("them grown to ") + margin)) return wide;
  } else if (pass.kind == PassKind::kHull) {
    // The quick pass's OCP again, in the hulls of a denser forward set.
    if (!r.solve_ocp || !quick.check.reach.witness.valid) return std::nullopt;
    ++totals.passes;
    if (progress.pass) progress.pass(totals.passes);
    FootstepTransition hull = solveInFullHulls(r, reach, pass.check, quick, progress);
    totals.check_time_s += hull.check_time_s;
    totals.ocp_time_s += hull.ocp_time_s;
    if (endsStep(hull, "the hull pass's forward set's")) return hull;
  }
  return std::nullopt;
}

bool FootstepTransitionPlanner::hasStrictTrajectory(const FootstepPlanRequest& r,
                                                    const FootstepTransition& step) {
  return !r.solve_ocp ||
         (step.trajectory.status == OcpStatus::kConverged && !step.trajectory.relaxed);
}

FootstepTransition FootstepTransitionPlanner::solveInFullHulls(
    const FootstepPlanRequest& r, const ReachConfig& reach, const CheckPass& hull_pass,
    const FootstepTransition& quick, const FootstepPlanProgress& progress) const {
  FootstepTransition out;
  const Eigen::Isometry3d held = startPass(r, quick.transition.horizon, out);
  // A forward set alone drawn with the hull budget (reach.budgets.hull over the full one),
  // propagated up to the quick witness's junction only: slicesUpToJunction drops the rest.
  double check_time_s = 0.0;
  const WitnessPath& witness = quick.check.reach.witness;
  CheckPass forward_pass = hull_pass;
  forward_pass.forward_until_s = junctionTime(witness);
  FootstepCheckResult forward = runCheck(r, reach, forward_pass, progress.check, out, check_time_s);
  // The quick pass's check stands (verdict, IK, witness): only the OCP's hulls change, cut
  // where its witness leaves the sampled sets.
  recordCheck(quick.check, true, out);
  out.check_time_s = check_time_s;
  if (!forward.kinematically_feasible) return out;  // not the quick pass's IK: no retry
  solveTransition(r, held, slicesUpToJunction(std::move(forward.set_constraint), witness),
                  progress.ocp, out, RelaxedFallback::kNever);
  return out;
}

FootstepTransition FootstepTransitionPlanner::solveInGrownHulls(
    const FootstepPlanRequest& r, const FootstepTransition& quick,
    std::vector<ReachableSlice> quick_slices, double extra_margin,
    const FootstepPlanProgress& progress) const {
  FootstepTransition out;
  const Eigen::Isometry3d held = startPass(r, quick.transition.horizon, out);
  recordCheck(quick.check, true, out);  // the quick pass's check stands; no sample is drawn
  solveTransition(r, held, grownSlices(std::move(quick_slices), extra_margin), progress.ocp, out,
                  RelaxedFallback::kNever);
  return out;
}

FootstepTransition FootstepTransitionPlanner::planWith(
    const FootstepPlanRequest& r, const ReachConfig& reach, const CheckPass& pass,
    const FootstepPlanProgress& progress, RelaxedFallback relaxed_fallback,
    std::vector<ReachableSlice>* slices_used, std::optional<TransitionRequest>* solved_ocp) const {
  FootstepTransition out;
  const Eigen::Isometry3d held = startPass(r, r.horizon > 0.0 ? r.horizon : reach.horizon, out);
  std::vector<ReachableSlice> set_constraint = checkFoothold(r, reach, pass, progress.check, out);
  if (slices_used) *slices_used = set_constraint;
  solveTransition(r, held, std::move(set_constraint), progress.ocp, out, relaxed_fallback,
                  solved_ocp);
  return out;
}

Eigen::Isometry3d FootstepTransitionPlanner::startPass(const FootstepPlanRequest& r, double horizon,
                                                       FootstepTransition& out) const {
  out.request = r;
  ContactTransition& t = out.transition;
  t.stance = r.stance;
  t.horizon = horizon;
  const Eigen::Isometry3d held = initialState(r, t);
  t.touchdown = predictTouchdown(r, t);
  if (!r.touchdown_com) t.qdf = Eigen::VectorXd::Zero(model_->nq());  // x_f at rest
  return held;
}

Eigen::Isometry3d FootstepTransitionPlanner::initialState(const FootstepPlanRequest& r,
                                                          ContactTransition& t) const {
  const RobotModel& m = *model_;
  const FrameId stance_frame = m.frameId(contact_.soleFrame(r.stance));
  Eigen::Isometry3d held;
  if (r.make_contact_consistent) {
    ContactConsistentState x0 = contactConsistentState(m, stance_frame, r.q0, r.qd0);
    t.q0 = std::move(x0.q);
    t.qd0 = std::move(x0.qd);
    held = x0.stance_sole;
    t.stance_contact = FlatContact::fromPose(held);
  } else {
    t.q0 = r.q0;
    t.qd0 = r.qd0;
    Workspace ws(m);
    m.update(ws, t.q0, t.qd0);
    // held flat where the sole is
    t.stance_contact = FlatContact::fromPose(m.framePose(ws, stance_frame));
    held = t.stance_contact.pose();
  }
  t.target = r.target;
  return held;
}

TouchdownPrediction FootstepTransitionPlanner::predictTouchdown(const FootstepPlanRequest& r,
                                                                const ContactTransition& t) const {
  TouchdownPrediction td;
  if (!r.touchdown_com) return td;
  // x_f: where the CoM will have carried the pelvis by touchdown, at its current height.
  const RobotModel& m = *model_;
  Workspace ws(m);
  m.update(ws, t.q0, t.qd0);
  const Eigen::Vector3d com = m.centerOfMass(ws);
  const Eigen::Vector3d com_shift(r.touchdown_com->p.x() - com.x(),
                                  r.touchdown_com->p.y() - com.y(), 0.0);
  td.pelvis_position =
      m.framePose(ws, m.frameId(kinematics_->config().pelvis_frame)).translation() + com_shift;
  td.com_velocity = r.touchdown_com->pd;
  return td;
}

FootstepCheckResult FootstepTransitionPlanner::runCheck(
    const FootstepPlanRequest& r, const ReachConfig& reach, const CheckPass& pass,
    const ReachProgressCallback& progress, const FootstepTransition& out, double& time_s) const {
  const auto check_start = SteadyClock::now();
  if (footstep_check_) {
    FootstepCheckResult checked =
        footstep_check_(out.transition, reach, pass, r.check_reachability);
    time_s = secondsSince(check_start);
    return checked;
  }
  // A check inside the step: past the request's deadline it stops before its next slice, and
  // a check cut short shows nothing reachable (its kinematic stage stands).
  bool cut_short = false;
  ReachProgressCallback within_deadline = progress;
  if (r.deadline)
    within_deadline = [&](const ReachProgress& p) {
      if (r.pastDeadline()) {
        cut_short = true;
        return false;
      }
      return !progress || progress(p);
    };
  FootstepCheckResult checked;
  try {
    checked = checkFootstep(footsteps_, out.transition, reach, pass, r.check_reachability,
                            within_deadline);
  } catch (const ReachCancelled&) {
    if (!cut_short) throw;  // the caller's own cancellation
    checked = footsteps_.kinematicStage(out.transition);
    checked.reachable = false;
    if (checked.kinematically_feasible)
      checked.reason =
          "not shown reachable: the step's deadline came during the check (cut "
          "short after " +
          std::to_string(secondsSince(check_start)) + " s)";
  }
  time_s = secondsSince(check_start);
  return checked;
}

std::vector<ReachableSlice> FootstepTransitionPlanner::checkFoothold(
    const FootstepPlanRequest& r, const ReachConfig& reach, const CheckPass& pass,
    const ReachProgressCallback& progress, FootstepTransition& out) const {
  double time_s = 0.0;
  FootstepCheckResult checked = runCheck(r, reach, pass, progress, out, time_s);
  std::vector<ReachableSlice> set_constraint = std::move(checked.set_constraint);
  recordCheck(std::move(checked), r.check_reachability, out);
  out.check_time_s = time_s;
  return set_constraint;
}

void FootstepTransitionPlanner::recordCheck(FootstepCheckResult check, bool checked,
                                            FootstepTransition& out) {
  out.check = std::move(check);
  const FootstepCheckResult& c = out.check;
  out.kinematically_feasible = c.kinematically_feasible;
  out.reachable = c.reachable;
  out.verdict = verdictOf(c, checked);
  out.reason = c.reason;
  out.hausdorff_distance = -1.0;
  for (const SliceComparison& w : c.reach.window)
    out.hausdorff_distance = out.hausdorff_distance < 0.0
                                 ? w.distance.hausdorff
                                 : std::min(out.hausdorff_distance, w.distance.hausdorff);
}

void FootstepTransitionPlanner::solveTransition(
    const FootstepPlanRequest& r, const Eigen::Isometry3d& held,
    std::vector<ReachableSlice> set_constraint, const OcpProgressCallback& progress,
    FootstepTransition& out, RelaxedFallback relaxed_fallback,
    std::optional<TransitionRequest>* solved_ocp) const {
  const RobotModel& m = *model_;
  const FootstepCheckResult& check = out.check;
  const TouchdownPrediction& td = out.transition.touchdown;
  TransitionRequest ocp(out.transition);
  ocp.stance_pose = held;
  if (td.pelvis_position)  // a relaxed landing stands at the predicted pelvis height
    ocp.terminal_pelvis_height =
        td.pelvis_position->z() - 0.5 * (held.translation().z() + r.target.position.z());
  Eigen::Vector3d nearest_feasible = r.target.position;
  if (check.kinematically_feasible) {
    ocp.qf = check.kinematics.q_f;
    ocp.qdf = check.qdf;
    ocp.relaxation = relaxationFor(r.ocp_policy, check.reachable);
    const bool relaxed_allowed =
        relaxed_fallback == RelaxedFallback::kAsRequested ||
        (relaxed_fallback == RelaxedFallback::kWhenCertified && check.reachable);
    if (!relaxed_allowed) ocp.relaxation = RelaxationMode::kStrict;
    if (r.check_reachability) ocp.slices = std::move(set_constraint);
  } else if (r.on_infeasible == InfeasibleFootholdPolicy::kReject) {
    throw RequestError("kinematically infeasible foothold (" + check.kinematics.reason + ")");
  } else if (r.on_infeasible == InfeasibleFootholdPolicy::kNoFallback) {
    out.trajectory.status = OcpStatus::kFailed;
    out.trajectory.reason = "no OCP for an infeasible foothold (no fallback requested)";
    out.foothold = r.target.position;
    return;
  } else if (r.on_infeasible == InfeasibleFootholdPolicy::kRelaxTowardTarget) {
    ocp.qf = check.kinematics.q_f;
    ocp.qdf = check.kinematics.qd_f;
    ocp.relaxation = RelaxationMode::kRelaxed;  // land as close as the OCP can
  } else {
    const ContactTransition& t = out.transition;
    const std::optional<NearestFoothold> near = nearest_.find(
        t.stance, t.stance_contact, t.target, t.q0, td.pelvis_position, candidate_check_);
    if (!near) {
      out.reason += "; no kinematically feasible foothold within " +
                    std::to_string(nearest_.config().searchRadius()) + " m of the target";
      out.trajectory.status = OcpStatus::kFailed;
      out.trajectory.reason = "no kinematically feasible foothold near the target";
      out.foothold = r.target.position;
      return;
    }
    nearest_feasible = near->foothold.position;
    out.foothold_source = FootholdSource::kNearestFeasible;
    ocp.qf = near->kinematics.q_f;
    ocp.target.position = nearest_feasible;
    ocp.qdf = doubleSupportVelocity(m, ocp.qf, m.frameId(contact_.left_sole_frame),
                                    m.frameId(contact_.right_sole_frame),
                                    Eigen::Vector3d(td.com_velocity.x(), td.com_velocity.y(), 0.0));
    ocp.relaxation = RelaxationMode::kAuto;
  }
  if (!r.solve_ocp) {
    out.trajectory.status = OcpStatus::kFailed;
    out.trajectory.reason = "not solved (solve_ocp = false)";
    out.foothold = nearest_feasible;
    if (r.check_reachability && check.kinematically_feasible) certify(out);
    return;
  }
  seedFromWitness(check.reach, ocp);
  const auto ocp_start = SteadyClock::now();
  out.trajectory = ocp_.solve(ocp, progress, r.deadline.value_or(SteadyClock::time_point::max()));
  out.ocp_time_s = secondsSince(ocp_start);
  if (solved_ocp) *solved_ocp = std::move(ocp);
  finishTransition(r, nearest_feasible, out);
}

void FootstepTransitionPlanner::finishTransition(const FootstepPlanRequest& r,
                                                 const Eigen::Vector3d& fallback_foothold,
                                                 FootstepTransition& out) const {
  // Without a usable trajectory the swing still goes to the nearest kinematically feasible
  // foothold (the target itself when it is feasible).
  out.foothold = out.usable() ? out.trajectory.landing_position : fallback_foothold;
  if (out.usable() && out.trajectory.relaxed) out.foothold_source = FootholdSource::kRelaxed;
  if (!out.trajectory.reason.empty()) out.reason += "; OCP: " + out.trajectory.reason;
  if (r.check_reachability && out.check.kinematically_feasible) certify(out);
}

double FootstepTransitionPlanner::solveDeferredRelaxed(const FootstepPlanRequest& r,
                                                       const std::optional<TransitionRequest>& ocp,
                                                       const FootstepPlanProgress& progress,
                                                       FootstepTransition& step) const {
  if (!ocp || !r.solve_ocp || !step.check.kinematically_feasible ||
      step.trajectory.status != OcpStatus::kFailed ||
      relaxationFor(r.ocp_policy, step.check.reachable) != RelaxationMode::kAuto)
    return 0.0;
  // The pass's strict answer is replaced by the merged one: its reason's OCP part too.
  const std::string strict_part = "; OCP: " + step.trajectory.reason;
  if (step.reason.size() >= strict_part.size() &&
      step.reason.compare(step.reason.size() - strict_part.size(), strict_part.size(),
                          strict_part) == 0)
    step.reason.resize(step.reason.size() - strict_part.size());
  const auto ocp_start = SteadyClock::now();
  step.trajectory = ocp_.solveRelaxedAfter(*ocp, step.trajectory, progress.ocp,
                                           r.deadline.value_or(SteadyClock::time_point::max()));
  const double ocp_time_s = secondsSince(ocp_start);
  step.ocp_time_s += ocp_time_s;
  finishTransition(r, step.foothold, step);
  return ocp_time_s;
}

void FootstepTransitionPlanner::certify(FootstepTransition& out) const {
  const bool strict_converged =
      out.trajectory.status == OcpStatus::kConverged && !out.trajectory.relaxed;
  // The OCP reports the joint velocity limits but does not constrain them: a certificate
  // must respect them as the bridge's path does (TALOS's are tight enough to matter).
  const bool certifies = out.trajectory.reachesTargetWithinLimits(config_.ocp.tolerance);
  if (out.check.reachable) {
    out.certificate = Certificate::kBridge;
  } else if (strict_converged && !certifies) {
    out.reason += "; not a certificate: the strict OCP's path exceeds a joint velocity limit by " +
                  std::to_string(out.trajectory.violation.velocity_limits) + " (relative)";
  } else if (certifies) {
    out.certificate = Certificate::kLocalSolve;
    out.reason =
        "reachable: certified by the local solve, the strict OCP seeded with the "
        "check's closest bridged path (" +
        out.check.reason + ")";
  }
  out.reachable = out.certificate != Certificate::kNone;
  out.verdict = out.reachable ? StepVerdict::kReachable : StepVerdict::kUnreachable;
}

}  // namespace reach_trajopt
