// The sets choose the foothold (InfeasibleFootholdPolicy::kNearestReachable,
// step/footstep_transition_planner.h) on footsteps of the demo's pushed walk
// (test/fixtures/pushed_walk_requests.jsonl, its steps 1, 2 and 5) and on bench/reach's case:
// a target the check certifies is kept, with or without a strict trajectory; one it does not is
// replaced by a ring point that it certifies, whose strict trajectory this test re-checks at every
// 1 ms sample with the model (eq. 1 with both soles' wrenches, the held sole, x(t_f) on the ring
// point's IK posture), no nearer than the nearest kinematically feasible ring point found by the
// kinematic search alone; a target beyond the leg's reach is replaced by a certified point of the
// segment toward the swing sole (the retreat, tried before the rings for such a target); when none
// of the candidates is certified the answer says so and carries no certificate.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "reach_trajopt/step/footstep_plan_request_json.h"
#include "reach_trajopt/step/footstep_transition_planner.h"
#include "reach_trajopt/testing/reference_cases.h"
#include "reach_trajopt/testing/transition_recheck.h"

using namespace reach_trajopt;

namespace {

const std::string kRepo = REACH_TRAJOPT_SOURCE_DIR;

const ShippedPipeline& pipeline() { return shippedPipeline(kRepo); }

std::vector<FootstepPlanRequest> walkRequests() {
  return pipeline().requests("pushed_walk_requests.jsonl");
}

/// The shipped planner with a candidate search that a loaded machine does not cut short (its
/// shipped 120 s wall-clock limit, nearest_foothold.time_limit, is a safety net of the walk).
FootstepPlannerConfig unhurriedConfig() {
  FootstepPlannerConfig config = pipeline().config;
  config.nearest_foothold.time_limit = 600.0;
  return config;
}

const FootstepTransitionPlanner& unhurriedPlanner() {
  static const FootstepTransitionPlanner planner(pipeline().model, pipeline().contact,
                                                 unhurriedConfig());
  return planner;
}

FootstepTransition planNearestReachable(FootstepPlanRequest r,
                                        const FootstepTransitionPlanner* planner = nullptr) {
  r.on_infeasible = InfeasibleFootholdPolicy::kNearestReachable;
  r.ocp_policy = OcpPolicy::kByVerdict;
  return (planner ? *planner : *pipeline().planner).plan(r);
}

/// The step's strict trajectory, re-checked at every 1 ms sample with the model: eq. (1) with
/// both soles' wrenches, the held sole, x(t_f) on the chosen foothold's IK posture, the landing.
void expectStrictTrajectoryRechecked(const FootstepTransition& step) {
  ASSERT_EQ(step.trajectory.status, OcpStatus::kConverged) << step.trajectory.reason;
  EXPECT_FALSE(step.trajectory.relaxed);
  const TransitionRecheck c = recheckTransition(*pipeline().model, pipeline().contact, step);
  std::cout << "eq. (1) " << c.dynamics << " N, held sole " << c.held_sole << " m, q(t_f) - q_f "
            << c.end_q << ", landing " << c.landing << " m\n";
  EXPECT_LE(c.dynamics, 1e-6);
  EXPECT_LE(c.held_sole, 1e-3);
  EXPECT_LE(c.end_q, 1e-3);
  EXPECT_LE(c.landing, 1e-3);
}

/// `step` replaced its kinematically infeasible target by a foothold of the nearest-reachable
/// search that the check certified; its reason says where that foothold came from (`where`).
void expectCertifiedStandInForInfeasibleTarget(const FootstepTransition& step,
                                               const std::string& where) {
  ASSERT_TRUE(step.target_verdict.has_value());
  EXPECT_EQ(*step.target_verdict, StepVerdict::kKinematicallyInfeasible);
  ASSERT_EQ(step.foothold_source, FootholdSource::kNearestReachable) << step.reason;
  EXPECT_NE(step.reason.find(where), std::string::npos) << step.reason;
  EXPECT_EQ(step.verdict, StepVerdict::kReachable);
  EXPECT_NE(step.certificate, Certificate::kNone);
}

/// The swing sole's position at the request's x_0 (where the retreat's segment ends) [m].
Eigen::Vector2d swingSoleAtStart(const FootstepPlanRequest& r) {
  const ShippedPipeline& p = pipeline();
  Workspace ws(*p.model);
  p.model->update(ws, r.q0, Eigen::VectorXd::Zero(p.model->nq()));
  return p.model->framePose(ws, p.model->frameId(p.contact.soleFrame(opposite(r.stance))))
      .translation()
      .head<2>();
}

/// Where `chosen` lies on the segment from `target` (s = 0) to `from` (s = 1); `off_line_m` is
/// its distance from the segment's line [m].
double segmentParameter(const Eigen::Vector2d& target, const Eigen::Vector2d& from,
                        const Eigen::Vector2d& chosen, double& off_line_m) {
  const Eigen::Vector2d d = from - target;
  const double s = (chosen - target).dot(d) / d.squaredNorm();
  off_line_m = (chosen - target - s * d).norm();
  return s;
}

}  // namespace

TEST(NearestReachable, ACertifiedTargetIsKept) {
  const FootstepTransition step = planNearestReachable(walkRequests()[2]);  // the walk's step 5
  EXPECT_EQ(step.verdict, StepVerdict::kReachable) << step.reason;
  EXPECT_EQ(step.foothold_source, FootholdSource::kTarget);
  EXPECT_EQ(step.candidates_checked, 0);
  EXPECT_FALSE(step.target_verdict.has_value());
  EXPECT_LT((step.foothold - step.request.target.position).head<2>().norm(), 0.01);
}

TEST(NearestReachable, ACertifiedTargetWithoutAStrictTrajectoryIsKept) {
  // The OCP stopped after one evaluation cannot converge: the certified target (the walk's
  // step 5, certified by the bridge) has no strict trajectory in any pass. Its certificate
  // stands, so it stays the foothold, no candidate checked; the swing goes there without a
  // trajectory.
  FootstepPlannerConfig config = unhurriedConfig();
  config.ocp.max_evaluations = 1;
  const FootstepTransitionPlanner planner(pipeline().model, pipeline().contact, config);
  const FootstepTransition step = planNearestReachable(walkRequests()[2], &planner);
  std::cout << step.reason << "\n";
  EXPECT_EQ(step.verdict, StepVerdict::kReachable) << step.reason;
  EXPECT_EQ(step.certificate, Certificate::kBridge);
  EXPECT_TRUE(step.check.reach.witness.certified);
  EXPECT_EQ(step.trajectory.status, OcpStatus::kFailed) << step.trajectory.reason;
  EXPECT_EQ(step.foothold_source, FootholdSource::kTarget);
  EXPECT_EQ(step.candidates_checked, 0);
  EXPECT_FALSE(step.target_verdict.has_value());
  EXPECT_LT((step.foothold - step.request.target.position).head<2>().norm(), 1e-9);
  EXPECT_NE(step.reason.find("certified, no strict trajectory"), std::string::npos);
}

TEST(NearestReachable, AFootThroughTheOtherIsReplacedByACertifiedRingPoint) {
  // Step 1, TVR's step through the stance sole, with the rings alone (no retreat).
  const ShippedPipeline& p = pipeline();
  FootstepPlannerConfig rings_only = p.config;
  rings_only.nearest_foothold.retreat_checks = 0;
  const FootstepTransitionPlanner planner(p.model, p.contact, rings_only);
  const FootstepPlanRequest r = walkRequests()[0];
  const FootstepTransition step = planNearestReachable(r, &planner);
  std::cout << step.reason << "\n";
  expectCertifiedStandInForInfeasibleTarget(step, "nearest reachable foothold, ");
  EXPECT_GE(step.candidates_checked, 1);
  EXPECT_LE(step.candidates_checked, p.config.nearest_foothold.max_checked);
  expectStrictTrajectoryRechecked(step);
  // A ring point: no nearer than the nearest kinematically feasible one, within the search.
  const NearestFeasibleFoothold rings(
      std::make_shared<KinematicFeasibility>(p.model, p.config.kinematics, p.contact),
      p.config.nearest_foothold);
  const std::optional<NearestFoothold> feasible =
      rings.find(step.transition.stance, step.transition.stance_contact, r.target,
                 step.transition.q0, step.transition.touchdown.pelvis_position);
  ASSERT_TRUE(feasible.has_value());
  const double nearest_feasible_m =
      (feasible->foothold.position - r.target.position).head<2>().norm();
  const double chosen_m = (step.foothold - r.target.position).head<2>().norm();
  std::cout << "nearest feasible " << nearest_feasible_m << " m, chosen " << chosen_m << " m\n";
  EXPECT_GE(chosen_m, nearest_feasible_m - 1e-3);
  EXPECT_LE(chosen_m, p.config.nearest_foothold.searchRadius() + 1e-3);
}

TEST(NearestReachable, TheRetreatStartsAtTheFirstPointThatPassesTheKinematicCheck) {
  // Step 1 again, with the shipped search: the retreat, tried first for a kinematically
  // infeasible target, checks the first of its evenly spaced points toward the swing sole that
  // passes the kinematic check; certified, it is the step (one reachability check). Nothing
  // nearer on the segment passes the kinematic check: the point one spacing nearer the target
  // fails it here, checked by a KinematicFeasibility of this test's own.
  const ShippedPipeline& p = pipeline();
  const FootstepPlanRequest r = walkRequests()[0];
  const FootstepTransition step = planNearestReachable(r, &unhurriedPlanner());
  std::cout << step.reason << "\n";
  expectCertifiedStandInForInfeasibleTarget(step, "toward the swing sole");
  EXPECT_EQ(step.candidates_checked, 1);
  expectStrictTrajectoryRechecked(step);
  const Eigen::Vector2d target = r.target.position.head<2>(), from = swingSoleAtStart(r);
  double off_line_m = 0.0;
  const double s = segmentParameter(target, from, step.foothold.head<2>(), off_line_m);
  EXPECT_LT(off_line_m, 1e-6);
  const int n = p.config.nearest_foothold.retreat_kinematic_points;
  ASSERT_GT(n, 0);
  const double spacing = 1.0 / n;
  EXPECT_NEAR(s * n, std::round(s * n), 1e-3) << "a point of the evenly spaced ones";
  ASSERT_GT(s, spacing / 2) << "the target itself fails the kinematic check";
  const KinematicFeasibility kinematics(p.model, p.config.kinematics, p.contact);
  FlatContact nearer = r.target;
  nearer.position.head<2>() = target + (s - spacing) * (from - target);
  const KinematicFeasibilityResult before =
      kinematics.check(step.transition.stance, step.transition.stance_contact, nearer,
                       step.transition.q0, step.transition.touchdown.pelvis_position);
  EXPECT_FALSE(before.feasible) << "s = " << s - spacing << " passes the kinematic check";
  FlatContact chosen = r.target;
  chosen.position = step.foothold;
  EXPECT_TRUE(kinematics
                  .check(step.transition.stance, step.transition.stance_contact, chosen,
                         step.transition.q0, step.transition.touchdown.pelvis_position)
                  .feasible);
}

TEST(NearestReachable, NoCertifiedCandidateSaysSoAndCertifiesNothing) {
  // bench/reach's case: the sole 80 ms before touchdown, too fast to stop on its target.
  // One candidate checked (each costs the target's passes again).
  const ShippedPipeline& p = pipeline();
  FootstepPlannerConfig one_candidate = p.config;
  one_candidate.nearest_foothold.max_checked = 1;
  one_candidate.nearest_foothold.retreat_checks = 0;
  const FootstepTransitionPlanner planner(p.model, p.contact, one_candidate);
  FootstepPlanRequest r = benchSwingCase(p.model, p.config, p.contact);
  r.on_infeasible = InfeasibleFootholdPolicy::kNearestReachable;
  const FootstepTransition step = planner.plan(r);
  std::cout << step.reason << "\n";
  EXPECT_EQ(step.certificate, Certificate::kNone);
  EXPECT_NE(step.verdict, StepVerdict::kReachable);
  EXPECT_NE(step.foothold_source, FootholdSource::kNearestReachable);
  EXPECT_EQ(step.candidates_checked, 1);
  EXPECT_NE(step.reason.find("no reachable foothold among the"), std::string::npos) << step.reason;
}

TEST(NearestReachable, OnlyTheTargetSolvesARelaxedOcpAfterTheSearch) {
  // bench/reach's case (a kinematically feasible target the check does not certify), one ring
  // candidate and one retreat point: only a certified strict trajectory ends the search, and the
  // answer without one is the target's own plan with its relaxed OCP (eq. 23). That relaxed
  // problem is solved once, for the target, after the search (a certified candidate would make
  // it useless), never for a candidate: in the stream of progress events (each plan of the
  // search starts with pass 1, each OCP evaluation says strict or relaxed) the relaxed
  // evaluations form one block at the very end.
  const ShippedPipeline& p = pipeline();
  FootstepPlannerConfig two_candidates = unhurriedConfig();
  two_candidates.nearest_foothold.max_checked = 1;
  two_candidates.nearest_foothold.retreat_checks = 1;
  const FootstepTransitionPlanner planner(p.model, p.contact, two_candidates);
  FootstepPlanRequest r = benchSwingCase(p.model, p.config, p.contact);
  r.on_infeasible = InfeasibleFootholdPolicy::kNearestReachable;
  r.ocp_policy = OcpPolicy::kByVerdict;
  enum class Event { kPlanStart, kPass, kStrict, kRelaxed };
  std::vector<Event> events;
  FootstepPlanProgress progress;
  progress.pass = [&](int pass) { events.push_back(pass == 1 ? Event::kPlanStart : Event::kPass); };
  progress.ocp = [&](const OcpProgress& o) {
    events.push_back(o.relaxed ? Event::kRelaxed : Event::kStrict);
    return true;
  };
  const FootstepTransition step = planner.plan(r, progress);
  std::cout << step.reason << "\n";
  ASSERT_NE(step.verdict, StepVerdict::kReachable) << "the case's target must not be certified";
  ASSERT_TRUE(step.foothold_source == FootholdSource::kTarget ||
              step.foothold_source == FootholdSource::kRelaxed)
      << "the target's own plan is the answer: " << step.reason;
  ASSERT_GE(step.candidates_checked, 1);
  EXPECT_EQ(std::count(events.begin(), events.end(), Event::kPlanStart),
            1 + step.candidates_checked);
  const auto first_relaxed = std::find(events.begin(), events.end(), Event::kRelaxed);
  ASSERT_NE(first_relaxed, events.end()) << "the target's relaxed OCP was not solved";
  EXPECT_TRUE(std::all_of(first_relaxed, events.end(), [](Event e) {
    return e == Event::kRelaxed;
  })) << "a plan, a pass or a strict solve came after a relaxed one";
  EXPECT_NE(step.reason.find("strict problem failed ("), std::string::npos) << step.reason;
}

TEST(NearestReachable, TheRetreatsKinematicScanAsksTheCandidateCheckInBatches) {
  // Step 1 planned with a candidate check plugged in (what the workers do): the same foothold
  // as in this process, the scan's points sent together, one batch answering up to the first
  // point that passes or fails with an error, not one batch per point.
  const ShippedPipeline& p = pipeline();
  FootstepTransitionPlanner plugged(p.model, p.contact, unhurriedConfig());
  const KinematicFeasibility kinematics(p.model, p.config.kinematics, p.contact);
  int batches = 0;
  std::size_t points = 0;
  plugged.setCandidateCheck([&](const FootholdCandidates& batch) {
    ++batches;
    points += batch.candidates.size();
    return checkFootholdCandidates(kinematics, batch, true);
  });
  const FootstepPlanRequest r = walkRequests()[0];
  const FootstepTransition in_process = planNearestReachable(r, &unhurriedPlanner());
  const FootstepTransition step = planNearestReachable(r, &plugged);
  std::cout << batches << " batches, " << points << " points sent\n";
  expectCertifiedStandInForInfeasibleTarget(step, "toward the swing sole");
  EXPECT_TRUE(step.foothold.isApprox(in_process.foothold, 1e-12))
      << step.foothold.transpose() << " vs " << in_process.foothold.transpose();
  // The retreat's first point is certified (TheRetreatStarts...): the scan is every batch.
  double off_line_m = 0.0;
  const double s = segmentParameter(r.target.position.head<2>(), swingSoleAtStart(r),
                                    step.foothold.head<2>(), off_line_m);
  ASSERT_GT(std::lround(s * p.config.nearest_foothold.retreat_kinematic_points), 1)
      << "the first point passes: one batch either way";
  EXPECT_EQ(batches, 1);
}

TEST(NearestReachable, ATargetBeyondReachIsReplacedByACertifiedPointTowardTheSwingSole) {
  // The walk's step 5 (certified as planned) with its target moved 0.35 m further out, away
  // from the stance sole: beyond the leg's reach. The retreat's bisection on the segment
  // target -> swing sole at x_0 gives a point of that segment that the check certifies, with a
  // strict trajectory re-checked here at every 1 ms sample.
  const ShippedPipeline& p = pipeline();
  FootstepPlanRequest r = walkRequests()[2];
  const Eigen::Vector2d from = swingSoleAtStart(r);
  const double outward = r.target.position.y() > r.stance_contact.position.y() ? 1.0 : -1.0;
  r.target.position.y() += 0.35 * outward;
  const FootstepTransition step = planNearestReachable(r, &unhurriedPlanner());
  std::cout << step.reason << "\n";
  expectCertifiedStandInForInfeasibleTarget(step, "toward the swing sole");
  EXPECT_LE(step.candidates_checked, p.config.nearest_foothold.retreat_checks);
  expectStrictTrajectoryRechecked(step);
  // On the segment, strictly between its ends: off the line by nothing, s in (0, 1).
  double off_line_m = 0.0;
  const double s =
      segmentParameter(r.target.position.head<2>(), from, step.foothold.head<2>(), off_line_m);
  EXPECT_LT(off_line_m, 1e-6);
  EXPECT_GT(s, 0.0);
  EXPECT_LT(s, 1.0);
}

TEST(NearestReachable, WithoutAReachabilityCheckItIsTheKinematicSearch) {
  FootstepPlanRequest r = walkRequests()[0];
  r.check_reachability = false;
  const FootstepTransition step = planNearestReachable(r);
  EXPECT_EQ(step.verdict, StepVerdict::kKinematicallyInfeasible);
  EXPECT_EQ(step.foothold_source, FootholdSource::kNearestFeasible);
  EXPECT_EQ(step.certificate, Certificate::kNone);
}

TEST(NearestReachable, TheCandidatesKeepTheSearchTimeLimit) {
  // Step 1 (its retreat's first point certified with the shipped search, above) with a search
  // time limit (nearest_foothold.time_limit) spent before the first candidate: no candidate is
  // checked, and the answer is not a certified stand-in; it says why.
  const ShippedPipeline& p = pipeline();
  FootstepPlannerConfig no_time = p.config;
  no_time.nearest_foothold.time_limit = 1e-9;
  const FootstepTransitionPlanner planner(p.model, p.contact, no_time);
  const FootstepTransition step = planNearestReachable(walkRequests()[0], &planner);
  std::cout << step.reason << "\n";
  EXPECT_EQ(step.candidates_checked, 0);
  EXPECT_NE(step.foothold_source, FootholdSource::kNearestReachable);
  EXPECT_EQ(step.certificate, Certificate::kNone);
  EXPECT_NE(step.reason.find("deadline reached"), std::string::npos) << step.reason;
}

TEST(NearestReachable, APastDeadlineEndsThePlanAfterItsFirstPass) {
  // The walk's step 1 (its target through the stance sole) with the deadline already past: the
  // target's quick pass ends at its kinematic stage, no candidate is checked and the OCP stops
  // at once.
  FootstepPlanRequest r = walkRequests()[0];
  r.deadline = std::chrono::steady_clock::now();
  const FootstepTransition step = planNearestReachable(r);
  std::cout << step.reason << "\n";
  EXPECT_EQ(step.candidates_checked, 0);
  EXPECT_EQ(step.check_passes, 1);
  EXPECT_NE(step.foothold_source, FootholdSource::kNearestReachable);
  EXPECT_EQ(step.certificate, Certificate::kNone);
  EXPECT_NE(step.reason.find("deadline reached"), std::string::npos) << step.reason;
  // A kinematically feasible target that is certified without a deadline (step 5,
  // ACertifiedTargetIsKept): its check stops before its first slice, cut short, and shows
  // nothing reachable; its kinematic stage stands; its OCP, stopped at the deadline, gives no
  // trajectory that was not re-checked.
  FootstepPlanRequest feasible = walkRequests()[2];
  feasible.deadline = std::chrono::steady_clock::now();
  const FootstepTransition s5 = planNearestReachable(feasible);
  std::cout << s5.reason << "\n";
  EXPECT_EQ(s5.check_passes, 1);
  EXPECT_TRUE(s5.kinematically_feasible);
  EXPECT_FALSE(s5.reachable);
  EXPECT_NE(s5.verdict, StepVerdict::kReachable);
  EXPECT_NE(s5.reason.find("deadline came during the check"), std::string::npos) << s5.reason;
  EXPECT_NE(s5.trajectory.status, OcpStatus::kConverged);
  if (s5.certificate == Certificate::kLocalSolve)
    ADD_FAILURE() << "a local solve past its deadline";
}

TEST(NearestReachable, APassStartsOnlyWithAsLongLeftAsAPassTook) {
  // FootstepPlanRequest::hasTimeFor, the test before each pass after the first and each
  // candidate: without a deadline always; with one, only while more than the pass's time is
  // left (margins of seconds: no timing in this test).
  FootstepPlanRequest r;
  EXPECT_TRUE(r.hasTimeFor(1e6));
  r.deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  EXPECT_TRUE(r.hasTimeFor(1.0));
  EXPECT_FALSE(r.hasTimeFor(60.0));
  EXPECT_FALSE(r.pastDeadline());
  r.deadline = std::chrono::steady_clock::now() - std::chrono::milliseconds(1);
  EXPECT_FALSE(r.hasTimeFor(0.0));
  EXPECT_TRUE(r.pastDeadline());
}
