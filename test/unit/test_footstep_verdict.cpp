// The verdict of the per-step pipeline (FootstepTransitionPlanner) on footsteps of the demo's
// pushed proposed walk (test/fixtures/pushed_walk_requests.jsonl: the requests of its steps 1, 2
// and 5, written by `walk_experiment --push 0,0.4 --plan-requests`) and on bench/reach's case:
// a "reachable" verdict comes with a certificate that this test re-checks step by step with
// the model (eq. 1, the held sole, the limits, x(t_f) against x_f) and a converged strict OCP;
// footholds out of reach are never reachable. An analyzer that always answered "reachable"
// fails the far and bench cases, one that never did fails the walk's steps.
#include <gtest/gtest.h>

#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/step/footstep_plan_request_json.h"
#include "reach_trajopt/step/footstep_transition_planner.h"
#include "reach_trajopt/testing/reference_cases.h"
#include "reach_trajopt/testing/transition_recheck.h"

using namespace reach_trajopt;

namespace {

const std::string kRepo = REACH_TRAJOPT_SOURCE_DIR;

const ShippedPipeline& pipeline() { return shippedPipeline(kRepo); }

std::vector<FootstepPlanRequest> requestsOf(const std::string& fixture) {
  return pipeline().requests(fixture);
}

std::vector<FootstepPlanRequest> walkRequests() { return requestsOf("pushed_walk_requests.jsonl"); }

/// test/fixtures/hull_pass_requests.jsonl, each with reach.quick_retry_constraint_margin set to
/// `retry_margin` [m] (0: no wide hull retry).
std::vector<FootstepPlanRequest> hullPassRequests(double retry_margin) {
  std::vector<FootstepPlanRequest> requests = requestsOf("hull_pass_requests.jsonl");
  for (FootstepPlanRequest& r : requests) {
    ReachConfig reach = r.reach ? *r.reach : pipeline().config.reach;
    reach.quick_retry_constraint_margin = retry_margin;
    r.reach = reach;
  }
  return requests;
}

/// Largest |M qdd + b - S^T u - J^T lambda| [N, Nm] along the bridged witness, its held sole's
/// largest displacement [m] and where it ends against x_f.
struct WitnessRecheck {
  double dynamics = 0.0, sole = 0.0, end_q = 0.0, end_qd = 0.0;
};

WitnessRecheck recheck(const FootstepTransition& step) {
  const RobotModel& m = *pipeline().model;
  const WitnessPath& w = step.check.reach.witness;
  const FrameId sole = m.frameId(pipeline().contact.soleFrame(step.transition.stance));
  Workspace ws(m);
  Eigen::MatrixXd M(m.nq(), m.nq()), J(6, m.nq());
  Eigen::VectorXd b(m.nq());
  WitnessRecheck r;
  const double dt = step.request.reach ? step.request.reach->dt : pipeline().config.reach.dt;
  for (int k = 0; k < w.q.cols(); ++k) {
    m.update(ws, w.q.col(k), w.qd.col(k));
    r.sole = std::max(
        r.sole,
        (m.framePose(ws, sole).translation() - step.transition.stance_contact.position).norm());
    if (k + 1 == w.q.cols()) break;
    m.massMatrix(ws, M);
    m.bias(ws, b);
    m.frameJacobian(ws, sole, J);
    Eigen::VectorXd res =
        M * (w.qd.col(k + 1) - w.qd.col(k)) / dt + b - J.transpose() * w.lambda.col(k).head<6>();
    res.tail(m.nu()) -= w.u.col(k);
    r.dynamics = std::max(r.dynamics, res.cwiseAbs().maxCoeff());
  }
  r.end_q = (w.q.col(w.q.cols() - 1) - step.check.kinematics.q_f).cwiseAbs().maxCoeff();
  r.end_qd = (w.qd.col(w.qd.cols() - 1) - step.check.qdf).cwiseAbs().maxCoeff();
  return r;
}

FootstepTransition planStrict(FootstepPlanRequest r,
                              const FootstepTransitionPlanner& planner = *pipeline().planner) {
  r.ocp_policy = OcpPolicy::kStrict;
  return planner.plan(r);
}

/// The shipped pipeline without the legs' clearance (contact.leg_clearance false), for the
/// passes' tests: their fixture steps were recorded before it, and with it the quick pass's
/// strict OCP solves both, so that no step would need a second pass to test.
const FootstepTransitionPlanner& plannerWithoutLegClearance() {
  static const std::unique_ptr<FootstepTransitionPlanner> planner = [] {
    ShippedBiped biped(kRepo);
    biped.contact.leg_clearance = false;
    return biped.makePlanner();
  }();
  return *planner;
}

/// The quick pass of `request` as the only pass; none when its strict OCP converged (the step
/// then needs no second pass: the OCP's solver decides which fixture steps do).
std::optional<FootstepTransition> planQuickPassAlone(FootstepPlanRequest request,
                                                     const FootstepTransitionPlanner& planner) {
  ReachConfig quick_alone = *request.reach;  // budgets.quick as the only pass's budget
  quick_alone.budgets.full = quick_alone.budgets.quick;
  quick_alone.quick_pass = false;
  request.reach = quick_alone;
  FootstepTransition quick = planStrict(request, planner);
  if (quick.trajectory.status == OcpStatus::kConverged && !quick.trajectory.relaxed) {
    std::cout << "the quick pass's strict OCP converged: no second pass to test on this step\n";
    return std::nullopt;
  }
  return quick;
}

/// A step the second pass ended (its reason naming that pass) with a strict trajectory within
/// the OCP's tolerance and a certificate.
void expectSecondPassEndsStrict(const FootstepTransition& step, const std::string& pass_reason) {
  std::cout << step.reason << "\n";
  EXPECT_EQ(step.check_passes, 2);
  EXPECT_NE(step.reason.find(pass_reason), std::string::npos) << step.reason;
  EXPECT_EQ(step.verdict, StepVerdict::kReachable);
  EXPECT_NE(step.certificate, Certificate::kNone);
  EXPECT_EQ(step.trajectory.status, OcpStatus::kConverged) << step.trajectory.reason;
  EXPECT_FALSE(step.trajectory.relaxed);
  EXPECT_LE(step.trajectory.violation.max(), pipeline().config.ocp.tolerance);
}

}  // namespace

TEST(FootstepVerdict, WalkStepCertifiedByTheBridge) {
  const std::vector<FootstepPlanRequest> requests = walkRequests();
  ASSERT_EQ(requests.size(), 3u);
  const FootstepTransition step = planStrict(requests[2]);  // the walk's step 5
  std::cout << step.reason << "\n";
  EXPECT_EQ(step.verdict, StepVerdict::kReachable);
  EXPECT_EQ(step.certificate, Certificate::kBridge);
  const WitnessPath& w = step.check.reach.witness;
  ASSERT_TRUE(w.certified);
  EXPECT_EQ(w.junction, -1);
  EXPECT_NEAR(w.time.back(), step.transition.horizon, 1e-12);
  const ReachConfig& reach = *step.request.reach;
  const WitnessRecheck r = recheck(step);
  std::cout << "witness: eq. (1) " << r.dynamics << " N, held sole " << r.sole
            << " m, x(t_f) - x_f " << r.end_q << " / " << r.end_qd << "\n";
  EXPECT_LE(r.dynamics, 1e-6);
  EXPECT_LE(r.sole, reach.contact_tolerance);
  EXPECT_LE(r.end_q, reach.terminal_position_tolerance);
  EXPECT_LE(r.end_qd, reach.terminal_velocity_tolerance);
  // A certified witness is a feasible point of the strict OCP: it converges from it.
  EXPECT_EQ(step.trajectory.status, OcpStatus::kConverged) << step.trajectory.reason;
}

TEST(FootstepVerdict, WalkStepReachableWithAStrictTrajectory) {
  const FootstepTransition step = planStrict(walkRequests()[1]);  // the walk's step 2
  std::cout << step.reason << "\n";
  EXPECT_EQ(step.verdict, StepVerdict::kReachable);
  EXPECT_NE(step.certificate, Certificate::kNone);
  EXPECT_EQ(step.trajectory.status, OcpStatus::kConverged) << step.trajectory.reason;
  EXPECT_LE(step.trajectory.violation.max(), pipeline().config.ocp.tolerance);
}

TEST(FootstepVerdict, FootholdsOutOfReachAreNeverReachable) {
  const std::vector<FootstepPlanRequest> requests = walkRequests();
  // The walk's step 1: TVR's narrow step through the stance sole.
  const FootstepTransition narrow = planStrict(requests[0]);
  EXPECT_EQ(narrow.verdict, StepVerdict::kKinematicallyInfeasible);
  EXPECT_FALSE(narrow.reachable);
  // Step 5's foothold 0.6 m farther forward.
  FootstepPlanRequest far = requests[2];
  far.target.position.x() += 0.6;
  const FootstepTransition f = planStrict(far);
  EXPECT_FALSE(f.reachable) << f.reason;
  EXPECT_NE(f.verdict, StepVerdict::kReachable);
}

TEST(FootstepVerdict, BenchCaseSoleCannotStopInTime) {
  // bench/reach's case: the right sole 3 cm short of its target and 2 cm up at 0.75 m/s,
  // 80 ms before touchdown with x_f at rest. Neither the bridge nor the strict OCP finds a
  // path (the OCP converged on none of an 11 x 11 grid around it): not shown reachable.
  const ShippedPipeline& p = pipeline();
  const FootstepPlanRequest r = benchSwingCase(p.model, p.config, p.contact);
  const FootstepTransition step = planStrict(r);
  std::cout << step.reason << "\n";
  ASSERT_TRUE(step.kinematically_feasible);
  EXPECT_EQ(step.verdict, StepVerdict::kUnreachable);
  EXPECT_EQ(step.certificate, Certificate::kNone);
  EXPECT_NE(step.trajectory.status, OcpStatus::kConverged);
}

TEST(FootstepVerdict, QuickPassKeepsTheFullBudgetsVerdictWhereItCertifiesNothing) {
  // reach.quick_pass: where the quick pass certifies nothing (the bench case), the step is
  // planned again with the full budget, and that pass is the planner without the quick pass:
  // the same verdict, witness attempt and OCP outcome. Where the quick pass certifies (the
  // walk's step 5), its certificate passes the same re-check as the full budget's.
  const ShippedPipeline& p = pipeline();
  auto withQuickPass = [&](FootstepPlanRequest r, bool quick) {
    ReachConfig c = r.reach ? *r.reach : p.config.reach;
    c.quick_pass = quick;
    r.reach = c;
    return planStrict(r);
  };
  const FootstepPlanRequest bench = benchSwingCase(p.model, p.config, p.contact);
  const FootstepTransition quick = withQuickPass(bench, true);
  const FootstepTransition full = withQuickPass(bench, false);
  // 2, 3 or 4: the wide hull retry and the hull pass may run before the full budget.
  EXPECT_GE(quick.check_passes, 2);
  EXPECT_LE(quick.check_passes, 4);
  EXPECT_EQ(full.check_passes, 1);
  EXPECT_EQ(quick.verdict, full.verdict);
  EXPECT_EQ(quick.certificate, full.certificate);
  EXPECT_EQ(quick.check.reach.witness.terminal_position_gap,
            full.check.reach.witness.terminal_position_gap);
  EXPECT_EQ(quick.trajectory.status, full.trajectory.status);
  EXPECT_EQ(quick.trajectory.cost, full.trajectory.cost);
  const std::string& tail = full.reason;
  ASSERT_GE(quick.reason.size(), tail.size());
  EXPECT_EQ(quick.reason.substr(quick.reason.size() - tail.size()), tail) << quick.reason;

  const FootstepTransition step5 = withQuickPass(walkRequests()[2], true);
  EXPECT_EQ(step5.verdict, StepVerdict::kReachable) << step5.reason;
  EXPECT_EQ(step5.trajectory.status, OcpStatus::kConverged) << step5.reason;
  if (step5.certificate == Certificate::kBridge) {
    const WitnessRecheck r = recheck(step5);
    const ReachConfig& reach = *step5.request.reach;
    EXPECT_LE(r.dynamics, 1e-6);
    EXPECT_LE(r.sole, reach.contact_tolerance);
    EXPECT_LE(r.end_q, reach.terminal_position_tolerance);
    EXPECT_LE(r.end_qd, reach.terminal_velocity_tolerance);
  }
}

TEST(FootstepVerdict, HullPassSolvesTheQuickPassesOcpInTheFullBudgetsForwardHulls) {
  // reach.hull_pass on step 13 of the walk pushed at (0, 0.25) m/s and step 11 of the unpushed
  // one (test/fixtures/hull_pass_requests.jsonl, `walk_experiment --push 0,0.25|0,0
  // --plan-requests`): the quick pass's strict OCP fails in its sparse hulls (seeded with its
  // bridge's witness in the first, with its closest bridged path, the local solve, in the
  // second); the hull pass keeps the quick pass's check and witness and solves the OCP in the
  // hull pass's denser forward hulls, converged and strict, without the full pass. A bridge's
  // certificate passes the same model re-check as every other.
  // The wide hull retry (reach.quick_retry_constraint_margin) is off here (as shipped): it
  // would end these steps before the hull pass (WideHullRetry... below).
  // A fixture step whose quick pass the OCP now solves (the first, since the analytic
  // derivatives) is skipped; at least one must still need the second pass.
  const std::vector<FootstepPlanRequest> requests = hullPassRequests(0.0);
  ASSERT_EQ(requests.size(), 2u);
  int second_passes = 0;
  for (const FootstepPlanRequest& request : requests) {
    const ReachConfig& reach = *request.reach;
    ASSERT_TRUE(reach.quick_pass && reach.hull_pass);
    const FootstepTransitionPlanner& planner = plannerWithoutLegClearance();
    const std::optional<FootstepTransition> quick_pass = planQuickPassAlone(request, planner);
    if (!quick_pass) continue;
    ++second_passes;
    const FootstepTransition& quick = *quick_pass;
    ASSERT_TRUE(quick.check.reach.witness.valid) << quick.reason;
    const FootstepTransition step = planStrict(request, planner);
    expectSecondPassEndsStrict(step, "the hull pass's forward set");
    // The quick pass's check stands: its witness, bit for bit.
    EXPECT_EQ(step.check.reach.witness.terminal_position_gap,
              quick.check.reach.witness.terminal_position_gap);
    EXPECT_EQ(step.check.reach.counts.forward_qps, quick.check.reach.counts.forward_qps);
    if (step.certificate == Certificate::kBridge) {
      const WitnessRecheck r = recheck(step);
      EXPECT_LE(r.dynamics, 1e-6);
      EXPECT_LE(r.sole, reach.contact_tolerance);
      EXPECT_LE(r.end_q, reach.terminal_position_tolerance);
      EXPECT_LE(r.end_qd, reach.terminal_velocity_tolerance);
    }
  }
  EXPECT_GE(second_passes, 1) << "no fixture step needs the second pass any more";
}

TEST(FootstepVerdict, WideHullRetrySolvesTheQuickPassesOcpInItsGrownHulls) {
  // reach.quick_retry_constraint_margin on the hull pass's fixtures: the quick pass's strict
  // OCP fails in its hulls (seeded with its bridge's witness in the first, with its closest
  // bridged path, the local solve, in the second). The retry keeps the quick pass's check (no
  // sample drawn) and solves the strict OCP again in the quick forward hulls grown to the retry's
  // margin: converged and strict in the second pass. The trajectory is re-checked here on the
  // model, eq. (1) sample by sample.
  const std::vector<FootstepPlanRequest> requests = hullPassRequests(0.04);  // off as shipped
  ASSERT_EQ(requests.size(), 2u);
  int second_passes = 0;
  for (const FootstepPlanRequest& request : requests) {
    const ReachConfig& reach = *request.reach;
    ASSERT_GT(reach.quick_retry_constraint_margin, reach.budgets.quick.constraint_margin);
    const FootstepTransitionPlanner& planner = plannerWithoutLegClearance();
    const std::optional<FootstepTransition> quick_pass = planQuickPassAlone(request, planner);
    if (!quick_pass) continue;
    ++second_passes;
    const FootstepTransition& quick = *quick_pass;
    const FootstepTransition step = planStrict(request, planner);
    expectSecondPassEndsStrict(step, "solved in them grown to");
    ASSERT_EQ(step.trajectory.status, OcpStatus::kConverged);
    // No sample drawn after the quick pass: its check, its time.
    EXPECT_EQ(step.check.reach.counts.forward_qps, quick.check.reach.counts.forward_qps);
    EXPECT_EQ(step.check.reach.witness.valid, quick.check.reach.witness.valid);
    const TransitionRecheck r = recheckTransition(*pipeline().model, pipeline().contact, step);
    std::cout << "trajectory: eq. (1) " << r.dynamics << " N, stance sole " << r.held_sole
              << " m, x(t_f) - x_f " << r.end_q << " / " << r.end_qd << "\n";
    EXPECT_LE(r.dynamics, 1e-3);
    EXPECT_LE(r.held_sole, 1e-3);
    EXPECT_LE(r.end_q, 1e-3);
    EXPECT_LE(r.end_qd, 1e-2);
  }
  EXPECT_GE(second_passes, 1) << "no fixture step needs the second pass any more";
}
