// ROS layer, the plan_footstep service's conversions (no master): a walking loop's request and
// the planner's answer go through the messages and come back bit for bit (what the node-wired
// walk needs to equal the in-process one), and every malformed request is rejected naming its
// field.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>

#include "reach_trajopt/ros/footstep_plan_msgs.h"
#include "reach_trajopt/ros/service_requests.h"
#include "ros_message_checks.h"

using namespace reach_trajopt;
namespace rb = reach_trajopt::ros_bridge;
using reach_trajopt::test::awkward;
using reach_trajopt::test::expectRejected;
using reach_trajopt::test::sameBits;

namespace {

const std::string kUrdf = std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf";

FootstepPlanRequest makeRequest(int nq) {
  FootstepPlanRequest r;
  r.stance = Side::kRight;
  r.stance_contact = {awkward(3, 1), 0.1 / 3.0};
  r.target = {awkward(3, 2), 0.2 / 3.0};
  r.q0 = awkward(nq, 3);
  r.qd0 = awkward(nq, 4);
  r.touchdown_com = LipmState{awkward(2, 5), awkward(2, 6)};
  r.make_contact_consistent = true;
  r.check_reachability = true;
  r.solve_ocp = false;
  r.horizon = 0.15;
  r.ocp_policy = OcpPolicy::kAuto;
  r.on_infeasible = InfeasibleFootholdPolicy::kRelaxTowardTarget;
  return r;
}

}  // namespace

TEST(RosFootstepPlanMsgs, RequestRoundTripIsExact) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  ReachConfig reach;
  reach.horizon = 0.2;
  reach.seed = 7;
  const FootstepPlanRequest r = makeRequest(model->nq());
  const auto m = rb::toPlanFootstepRequestMsg(r, reach, ros::Time(1.5));
  EXPECT_EQ(m.header.frame_id, "world");
  EXPECT_EQ(m.reach_horizon, 0.2);
  EXPECT_EQ(m.seed, 7);
  ReachConfig base;  // the node's: another horizon and seed, replaced by the message's
  base.seed = 3;
  const FootstepPlanRequest back = rb::fromPlanFootstepRequestMsg(m, model->nq(), base);
  EXPECT_EQ(back.stance, Side::kRight);
  // The stance sole travels as a flat pose: its heading back within rounding.
  EXPECT_TRUE(sameBits(back.stance_contact.position, r.stance_contact.position));
  EXPECT_NEAR(back.stance_contact.yaw, r.stance_contact.yaw, 1e-15);
  EXPECT_TRUE(sameBits(back.target.position, r.target.position));
  EXPECT_EQ(back.target.yaw, r.target.yaw);
  EXPECT_TRUE(sameBits(back.q0, r.q0));
  EXPECT_TRUE(sameBits(back.qd0, r.qd0));
  ASSERT_TRUE(back.touchdown_com.has_value());
  EXPECT_TRUE(sameBits(back.touchdown_com->p, r.touchdown_com->p));
  EXPECT_TRUE(sameBits(back.touchdown_com->pd, r.touchdown_com->pd));
  EXPECT_TRUE(back.make_contact_consistent);
  EXPECT_TRUE(back.check_reachability);
  EXPECT_FALSE(back.solve_ocp);
  EXPECT_EQ(back.horizon, 0.15);
  EXPECT_EQ(back.ocp_policy, OcpPolicy::kAuto);
  EXPECT_EQ(back.on_infeasible, InfeasibleFootholdPolicy::kRelaxTowardTarget);
  ASSERT_TRUE(back.reach.has_value());
  EXPECT_EQ(back.reach->horizon, 0.2);
  EXPECT_EQ(back.reach->seed, 7u);
  EXPECT_EQ(back.reach->budgets.full.initial_samples, base.budgets.full.initial_samples);
  // The sender's three sample budgets travel (budgets), each key of each; the hull budget whole
  // (its unset keys the full budget's).
  reach.budgets.full.certificate_candidates = base.budgets.full.certificate_candidates + 3;
  reach.budgets.full.max_boundary = 50;
  reach.budgets.quick.constraint_margin = 0.031;
  reach.budgets.hull.children_per_parent = 5;
  const FootstepPlanRequest sent = rb::fromPlanFootstepRequestMsg(
      rb::toPlanFootstepRequestMsg(r, reach, ros::Time(0)), model->nq(), base);
  EXPECT_EQ(sent.reach->budgets.full.certificate_candidates,
            base.budgets.full.certificate_candidates + 3);
  EXPECT_EQ(sent.reach->budgets.full.max_boundary, 50);
  EXPECT_EQ(sent.reach->budgets.quick.constraint_margin, 0.031);
  EXPECT_EQ(sent.reach->budgets.hullBudget().children_per_parent, 5);
  EXPECT_EQ(sent.reach->budgets.hullBudget().max_boundary, 50);
  EXPECT_EQ(sent.reach->budgets.hullBudget().initial_samples, 2500);
  EXPECT_EQ(sent.reach->threads, base.threads);

  // No yaw (the stance sole's heading), no touchdown CoM, the node's seed and horizon.
  FootstepPlanRequest plain = r;
  plain.touchdown_com.reset();
  auto pm = rb::toPlanFootstepRequestMsg(plain, reach, ros::Time(0));
  pm.target_yaw.clear();
  pm.seed = -1;
  pm.reach_horizon = 0.0;
  pm.budgets.clear();
  const FootstepPlanRequest pb = rb::fromPlanFootstepRequestMsg(pm, model->nq(), base);
  EXPECT_EQ(pb.target.yaw, pb.stance_contact.yaw);
  EXPECT_FALSE(pb.touchdown_com.has_value());
  EXPECT_EQ(pb.reach->seed, 3u);
  EXPECT_EQ(pb.reach->horizon, base.horizon);
}

TEST(RosFootstepPlanMsgs, MalformedRequestsNameTheirField) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  const int nq = model->nq();
  const ReachConfig reach;
  const auto good = rb::toPlanFootstepRequestMsg(makeRequest(nq), reach, ros::Time(0));
  auto rejected = [&](const std::string& field,
                      const std::function<void(reach_trajopt::PlanFootstep::Request&)>& edit) {
    auto m = good;
    edit(m);
    expectRejected([&] { rb::fromPlanFootstepRequestMsg(m, nq, reach); }, field);
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  rejected("header.frame_id", [](auto& m) { m.header.frame_id = "map"; });
  rejected("stance", [](auto& m) { m.stance = "SS-L"; });
  rejected("stance_pose", [](auto& m) { m.stance_pose.resize(9); });
  rejected("stance_pose", [](auto& m) { m.stance_pose[0] = 2.0; });
  rejected("target", [&](auto& m) { m.target.y = nan; });
  rejected("target_yaw", [](auto& m) { m.target_yaw = {0.0, 1.0}; });
  rejected("q", [](auto& m) { m.q.pop_back(); });
  rejected("qd", [&](auto& m) { m.qd[3] = nan; });
  rejected("touchdown_com", [](auto& m) { m.touchdown_com.resize(2); });
  rejected("horizon", [](auto& m) { m.horizon = -0.1; });
  rejected("reach_horizon", [](auto& m) { m.reach_horizon = 100.0; });
  rejected("seed", [](auto& m) { m.seed = -2; });
  rejected("ocp_policy", [](auto& m) { m.ocp_policy = "loose"; });
  rejected("on_infeasible", [](auto& m) { m.on_infeasible = ""; });
  rejected("time_budget", [&](auto& m) { m.time_budget = nan; });
  rejected("time_budget", [](auto& m) { m.time_budget = -1.0; });
}

// The step's deadline crosses the messages as the wall time left (time_budget): none stays
// none; one 0.2 s away arrives as a deadline about 0.2 s after the receipt; one already past
// asks for the quickest answer (a deadline at once).
TEST(RosFootstepPlanMsgs, TheDeadlineCrossesAsTheTimeLeft) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  const int nq = model->nq();
  const ReachConfig reach;
  using Clock = std::chrono::steady_clock;
  FootstepPlanRequest r = makeRequest(nq);
  auto m = rb::toPlanFootstepRequestMsg(r, reach, ros::Time(0));
  EXPECT_EQ(m.time_budget, 0.0);
  EXPECT_FALSE(rb::fromPlanFootstepRequestMsg(m, nq, reach).deadline.has_value());
  const auto sent = Clock::now();
  r.deadline = sent + std::chrono::milliseconds(200);
  m = rb::toPlanFootstepRequestMsg(r, reach, ros::Time(0));
  EXPECT_GT(m.time_budget, 0.15);
  EXPECT_LE(m.time_budget, 0.2);
  const FootstepPlanRequest back = rb::fromPlanFootstepRequestMsg(m, nq, reach);
  ASSERT_TRUE(back.deadline.has_value());
  const double after_sent = std::chrono::duration<double>(*back.deadline - sent).count();
  EXPECT_GT(after_sent, 0.15);
  EXPECT_LT(after_sent, 0.5);
  r.deadline = sent - std::chrono::seconds(1);
  m = rb::toPlanFootstepRequestMsg(r, reach, ros::Time(0));
  EXPECT_DOUBLE_EQ(m.time_budget, 1e-3);
}

TEST(RosFootstepPlanMsgs, ResponseRoundTripIsExact) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  ContactConfig contact;
  FootstepTransition step;
  step.kinematically_feasible = true;
  step.check.kinematics.reason = "ok";
  step.reachable = true;
  step.certificate = Certificate::kLocalSolve;
  step.verdict = StepVerdict::kReachable;
  step.reason = "strict OCP converged";
  step.hausdorff_distance = 0.1 / 3.0;
  step.check_time_s = 1.25;
  step.ocp_time_s = 0.5;
  step.foothold = awkward(3, 8);
  step.transition.horizon = 0.2;
  WitnessPath& w = step.check.reach.witness;
  w.valid = true;
  w.violation = PathViolation{1e-3 / 3, 2e-3 / 3, 3e-3 / 3, 0.0,      4e-3 / 3,
                              5e-3 / 3, 0.0,      6e-3 / 3, 7e-3 / 3, 8e-3 / 3};
  w.position_gap = 0.01 / 3;
  w.velocity_gap = 0.02 / 3;
  w.terminal_position_gap = 0.03 / 3;
  w.terminal_velocity_gap = 0.04 / 3;
  TransitionResult& t = step.trajectory;
  const int knots = 7;
  t.status = OcpStatus::kRelaxed;
  t.dt = 0.001;
  t.time = Eigen::VectorXd::LinSpaced(knots, 0.0, 0.006);
  t.q =
      Eigen::Map<const Eigen::MatrixXd>(awkward(model->nq() * knots, 9).data(), model->nq(), knots);
  t.qd = Eigen::Map<const Eigen::MatrixXd>(awkward(model->nq() * knots, 10).data(), model->nq(),
                                           knots);
  t.qdd = Eigen::Map<const Eigen::MatrixXd>(awkward(model->nq() * knots, 11).data(), model->nq(),
                                            knots);
  t.u = Eigen::Map<const Eigen::MatrixXd>(awkward(model->nu() * knots, 12).data(), model->nu(),
                                          knots);
  t.lambda = Eigen::Map<const Eigen::MatrixXd>(awkward(12 * knots, 13).data(), 12, knots);
  t.eps = awkward(2, 14);
  t.landing_position = awkward(3, 15);

  const FootstepPlanRequest request = makeRequest(model->nq());
  const auto m = rb::toPlanFootstepResponseMsg(step, *model, contact, ros::Time(2.0));
  EXPECT_TRUE(m.success);
  const FootstepTransition back = rb::fromPlanFootstepResponseMsg(m, request, *model);
  EXPECT_TRUE(back.kinematically_feasible);
  EXPECT_TRUE(back.reachable);
  EXPECT_EQ(back.certificate, Certificate::kLocalSolve);
  EXPECT_EQ(back.verdict, StepVerdict::kReachable);
  EXPECT_EQ(back.reason, step.reason);
  EXPECT_EQ(back.check.kinematics.reason, "ok");
  EXPECT_EQ(back.hausdorff_distance, step.hausdorff_distance);
  EXPECT_EQ(back.check_time_s, 1.25);
  EXPECT_EQ(back.ocp_time_s, 0.5);
  EXPECT_TRUE(sameBits(back.foothold, step.foothold));
  EXPECT_EQ(back.transition.horizon, 0.2);
  const WitnessPath& bw = back.check.reach.witness;
  ASSERT_TRUE(bw.valid);
  EXPECT_EQ(bw.violation.max(), w.violation.max());
  EXPECT_EQ(bw.violation.ground, w.violation.ground);
  EXPECT_EQ(bw.violation.leg_clearance, w.violation.leg_clearance);
  EXPECT_EQ(bw.violation.dynamics, w.violation.dynamics);
  EXPECT_EQ(bw.position_gap, w.position_gap);
  EXPECT_EQ(bw.velocity_gap, w.velocity_gap);
  EXPECT_EQ(bw.terminal_position_gap, w.terminal_position_gap);
  EXPECT_EQ(bw.terminal_velocity_gap, w.terminal_velocity_gap);
  const TransitionResult& bt = back.trajectory;
  EXPECT_EQ(bt.status, OcpStatus::kRelaxed);
  EXPECT_TRUE(back.usable());
  EXPECT_EQ(bt.dt, t.dt);
  EXPECT_TRUE(sameBits(bt.time, t.time));
  EXPECT_TRUE(sameBits(bt.q, t.q));
  EXPECT_TRUE(sameBits(bt.qd, t.qd));
  EXPECT_TRUE(sameBits(bt.qdd, t.qdd));
  EXPECT_TRUE(sameBits(bt.u, t.u));
  EXPECT_TRUE(sameBits(bt.lambda, t.lambda));
  EXPECT_TRUE(sameBits(bt.eps, t.eps));
  EXPECT_TRUE(sameBits(bt.landing_position, t.landing_position));

  // A malformed response is an error naming the field, not a wrong trajectory.
  auto bad = m;
  bad.trajectory.qdd.pop_back();
  EXPECT_THROW(rb::fromPlanFootstepResponseMsg(bad, request, *model), ReachError);
  bad = m;
  bad.witness_violation.resize(3);
  EXPECT_THROW(rb::fromPlanFootstepResponseMsg(bad, request, *model), ReachError);
  bad = m;
  bad.trajectory.status = "maybe";
  EXPECT_THROW(rb::fromPlanFootstepResponseMsg(bad, request, *model), ReachError);
}
