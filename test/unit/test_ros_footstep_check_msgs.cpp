// ROS layer, the check_footstep service's conversions (no master): a step of the demo's pushed
// walk (test/fixtures/pushed_walk_requests.jsonl) planned with its footstep check sent through
// the request and answered through the response is the step the in-process planner plans, bit
// for bit (verdict, passes, witness, eq. 23's hulls, the OCP's trajectory), as reachability_node
// and transition_ocp_node need; the request carries the pass's sample budget and hull margin
// (the quick pass's differ from the node's); malformed
// requests are rejected naming the field, malformed answers are errors naming it.

#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "reach_trajopt/common/config_fields.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/ros/footstep_check_msgs.h"
#include "reach_trajopt/step/footstep_plan_request_json.h"
#include "reach_trajopt/step/footstep_transition_planner.h"
#include "reach_trajopt/testing/reference_cases.h"
#include "ros_message_checks.h"

using namespace reach_trajopt;
namespace rb = reach_trajopt::ros_bridge;
using reach_trajopt::test::expectRejected;
using reach_trajopt::test::sameBits;

namespace {

const std::string kRepo = REACH_TRAJOPT_SOURCE_DIR;

const ShippedBiped& pipeline() {
  static const ShippedBiped p(kRepo);
  return p;
}

// The `index`-th footstep of the pushed walk fixture.
FootstepPlanRequest walkRequest(size_t index) {
  const std::vector<FootstepPlanRequest> all =
      readPlanRequests(kRepo + "/test/fixtures/pushed_walk_requests.jsonl", pipeline().model->nq(),
                       pipeline().config.reach);
  if (index >= all.size()) throw std::runtime_error("fixture: no request " + std::to_string(index));
  return all[index];
}

// The footstep check the planner makes of the fixture's step `index` (x_0 made contact
// consistent by the planner's step 1, the foothold flat in the stance heading).
ContactTransition footstepRequest(size_t index) {
  FootstepPlanRequest plan = walkRequest(index);
  plan.check_reachability = false;
  plan.solve_ocp = false;
  const FootstepTransition kinematic = pipeline().makePlanner()->plan(plan);
  ContactTransition r;  // as checked, without the touchdown's pelvis and qd_f
  r.stance = kinematic.transition.stance;
  r.stance_contact = kinematic.transition.stance_contact;
  r.target = kinematic.transition.target;
  r.q0 = kinematic.transition.q0;
  r.qd0 = kinematic.transition.qd0;
  if (plan.touchdown_com) r.touchdown.com_velocity = plan.touchdown_com->pd;
  return r;
}

}  // namespace

TEST(RosFootstepCheckMsgs, StepCheckedThroughTheMessagesIsTheInProcessStep) {
  const ShippedBiped& p = pipeline();
  const auto here = p.makePlanner();
  // What reachability_node does with each request, and transition_ocp_node with the answer.
  const auto node = p.makePlanner();
  auto there = p.makePlanner();
  int calls = 0;
  there->setFootstepCheck([&](const ContactTransition& request, const ReachConfig& reach,
                              const CheckPass& pass, bool reachability) {
    ++calls;
    const auto request_msg =
        rb::toCheckFootstepRequestMsg(request, reach, pass, reachability, false, ros::Time(2.0));
    const rb::FootstepCheckCall call =
        rb::fromCheckFootstepRequestMsg(request_msg, p.model->nq(), p.config.reach);
    const FootstepCheckResult checked = checkFootstep(node->footstepReachability(), call.request,
                                                      call.reach, call.pass, call.reachability);
    const auto response = rb::toCheckFootstepResponseMsg(checked, ReachabilityResult());
    return rb::fromCheckFootstepResponseMsg(response, p.model->nq());
  });
  for (size_t index : {0u, 1u}) {
    SCOPED_TRACE("fixture step " + std::to_string(index));
    const FootstepPlanRequest request = walkRequest(index);
    const FootstepTransition a = here->plan(request);
    const FootstepTransition b = there->plan(request);
    EXPECT_EQ(b.verdict, a.verdict);
    EXPECT_EQ(b.certificate, a.certificate);
    EXPECT_EQ(b.check_passes, a.check_passes);
    EXPECT_EQ(b.reason, a.reason);
    EXPECT_EQ(b.kinematically_feasible, a.kinematically_feasible);
    EXPECT_EQ(b.check.reachable, a.check.reachable);
    EXPECT_TRUE(sameBits(b.check.kinematics.q_f, a.check.kinematics.q_f));
    EXPECT_TRUE(sameBits(b.check.reach.witness.q, a.check.reach.witness.q));
    EXPECT_EQ(b.check.reach.witness.time, a.check.reach.witness.time);
    EXPECT_EQ(b.trajectory.status, a.trajectory.status);
    EXPECT_TRUE(sameBits(b.trajectory.q, a.trajectory.q));
    EXPECT_TRUE(sameBits(b.trajectory.u, a.trajectory.u));
    EXPECT_TRUE(sameBits(b.foothold, a.foothold));
  }
  EXPECT_GT(calls, 0);
}

TEST(RosFootstepCheckMsgs, RequestCarriesThePassesHorizonSeedAndSampleBudget) {
  const ShippedBiped& p = pipeline();
  ContactTransition r = footstepRequest(1);
  r.touchdown.pelvis_position = Eigen::Vector3d(0.01, -0.02, 0.9);
  ReachConfig reach = p.config.reach;
  reach.horizon = 0.17;
  reach.seed = 4000000000u;  // above INT_MAX: the walk's --seed range
  CheckPass pass;
  pass.budget = {900, 3, 7, 21, 5, 2, 0.023};
  const auto m = rb::toCheckFootstepRequestMsg(r, reach, pass, true, true, ros::Time(1.25));
  EXPECT_EQ(m.header.frame_id, "world");
  EXPECT_EQ(m.header.stamp, ros::Time(1.25));
  const rb::FootstepCheckCall c = rb::fromCheckFootstepRequestMsg(m, p.model->nq(), p.config.reach);
  EXPECT_TRUE(c.reachability);
  EXPECT_TRUE(c.samples);
  EXPECT_EQ(c.request.stance, r.stance);
  EXPECT_TRUE(sameBits(c.request.q0, r.q0));
  EXPECT_TRUE(sameBits(c.request.qd0, r.qd0));
  EXPECT_TRUE(sameBits(c.request.target.position, r.target.position));
  EXPECT_EQ(c.request.target.yaw, r.target.yaw);
  EXPECT_TRUE(sameBits(c.request.stance_contact.position, r.stance_contact.position));
  EXPECT_TRUE(sameBits(c.request.touchdown.com_velocity, r.touchdown.com_velocity));
  ASSERT_TRUE(c.request.touchdown.pelvis_position.has_value());
  EXPECT_TRUE(sameBits(*c.request.touchdown.pelvis_position, *r.touchdown.pelvis_position));
  EXPECT_TRUE(c.request.qdf.size() == 0);
  EXPECT_EQ(c.reach.horizon, 0.17);
  EXPECT_EQ(c.reach.seed, 4000000000u);
  ASSERT_TRUE(c.pass.has_value());
  const SamplingBudget& b = c.pass->budget;
  EXPECT_EQ(b.initial_samples, 900);
  EXPECT_EQ(b.children_per_parent, 3);
  EXPECT_EQ(b.backward_children_per_parent, 7);
  EXPECT_EQ(b.max_boundary, 21);
  EXPECT_EQ(b.interior_samples, 5);
  EXPECT_EQ(b.certificate_candidates, 2);
  EXPECT_EQ(b.constraint_margin, 0.023);
  EXPECT_FALSE(c.pass->forwardOnly());
  // The rest is the node's: here its delta and its budgets, not the sender's.
  EXPECT_EQ(c.reach.delta, p.config.reach.delta);
  EXPECT_EQ(c.reach.budgets.full.initial_samples, p.config.reach.budgets.full.initial_samples);

  // The hull pass: the forward set alone, up to a time (none: up to window_end).
  CheckPass hull{p.config.reach.budgets.hullBudget(), PassSets::kForwardOnly, 0.037};
  for (double until : {0.037, HUGE_VAL}) {
    hull.forward_until_s = until;
    const rb::FootstepCheckCall h = rb::fromCheckFootstepRequestMsg(
        rb::toCheckFootstepRequestMsg(r, reach, hull, true, false, ros::Time(1)), p.model->nq(),
        p.config.reach);
    ASSERT_TRUE(h.pass.has_value());
    EXPECT_TRUE(h.pass->forwardOnly());
    EXPECT_EQ(h.pass->forward_until_s, until);
    EXPECT_EQ(h.pass->budget.initial_samples, 2500);
    EXPECT_EQ(h.pass->budget.max_boundary, p.config.reach.budgets.full.max_boundary);
  }

  // No pass, horizon 0 and seed -1: the node's own (its pass schedule).
  const auto defaults =
      rb::toCheckFootstepRequestMsg(r, reach, std::nullopt, true, true, ros::Time(1.25));
  EXPECT_TRUE(defaults.budget.empty());
  auto own = defaults;
  own.reach_horizon = 0.0;
  own.seed = -1;
  const rb::FootstepCheckCall d =
      rb::fromCheckFootstepRequestMsg(own, p.model->nq(), p.config.reach);
  EXPECT_EQ(d.reach.horizon, p.config.reach.horizon);
  EXPECT_EQ(d.reach.seed, p.config.reach.seed);
  EXPECT_FALSE(d.pass.has_value());
}

TEST(RosFootstepCheckMsgs, MalformedRequestsAreRejectedNamingTheField) {
  const ShippedBiped& p = pipeline();
  const int nq = p.model->nq();
  const auto good = rb::toCheckFootstepRequestMsg(footstepRequest(1), p.config.reach,
                                                  CheckPass{p.config.reach.budgets.quick}, true,
                                                  false, ros::Time(1));
  EXPECT_NO_THROW(rb::fromCheckFootstepRequestMsg(good, nq, p.config.reach));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto reject = [&](const std::function<void(reach_trajopt::CheckFootstep::Request&)>& edit,
                    const std::string& field) {
    auto m = good;
    edit(m);
    expectRejected([&] { rb::fromCheckFootstepRequestMsg(m, nq, p.config.reach); }, field);
  };
  reject([](auto& m) { m.header.frame_id = "map"; }, "header.frame_id");
  reject([](auto& m) { m.stance = "both"; }, "stance");
  reject([](auto& m) { m.stance_contact.resize(3); }, "stance_contact");
  reject([&](auto& m) { m.target[1] = nan; }, "target");
  reject([](auto& m) { m.q0.pop_back(); }, "q0");
  reject([&](auto& m) { m.qd0[0] = std::numeric_limits<double>::infinity(); }, "qd0");
  reject([](auto& m) { m.qdf = {0.0, 1.0}; }, "qdf");
  reject([](auto& m) { m.touchdown_com_velocity.clear(); }, "touchdown_com_velocity");
  reject([](auto& m) { m.touchdown_pelvis_position = {0.0}; }, "touchdown_pelvis_position");
  reject([](auto& m) { m.reach_horizon = -0.1; }, "reach_horizon");
  reject([&](auto& m) { m.reach_horizon = nan; }, "reach_horizon");
  reject([](auto& m) { m.reach_horizon = 1e9; }, "reach_horizon");
  reject([](auto& m) { m.seed = -2; }, "seed");
  reject([](auto& m) { m.budget.resize(2); }, "budget");
  reject([](auto& m) { m.budget[0].initial_samples = 0; }, "budget.initial_samples");
  reject([](auto& m) { m.budget[0].initial_samples = -5; }, "budget.initial_samples");
  reject([](auto& m) { m.budget[0].certificate_candidates = 0; }, "budget.certificate_candidates");
  reject([&](auto& m) { m.budget[0].constraint_margin = nan; }, "budget.constraint_margin");
  reject([](auto& m) { m.budget[0].constraint_margin = -0.01; }, "budget.constraint_margin");
  reject([](auto& m) { m.forward_until = {0.01}; }, "forward_until");  // not forward_set_only
  reject(
      [](auto& m) {
        m.forward_set_only = true;
        m.forward_until = {-0.01};
      },
      "forward_until");
  reject(
      [&](auto& m) {
        m.forward_set_only = true;
        m.forward_until = {nan};
      },
      "forward_until");
  reject(
      [](auto& m) {
        m.budget.clear();
        m.forward_set_only = true;
      },
      "forward_set_only");
  // A budget beyond the memory limit (an unbounded allocation) is refused before any sampling.
  reject(
      [](auto& m) {
        m.budget[0].initial_samples = 200000;
        m.budget[0].children_per_parent = 1000;
        m.budget[0].backward_children_per_parent = 1000;
      },
      "budget");
}

TEST(RosFootstepCheckMsgs, MalformedAnswersAreErrorsNamingTheField) {
  const ShippedBiped& p = pipeline();
  const int nq = p.model->nq();
  // A well-formed answer of a real check (the quick budget keeps it short).
  const auto node = p.makePlanner();
  const FootstepCheckResult checked =
      checkFootstep(node->footstepReachability(), footstepRequest(1), p.config.reach,
                    CheckPass{p.config.reach.budgets.quick}, true);
  ASSERT_TRUE(checked.kinematically_feasible) << checked.reason;
  const auto good = rb::toCheckFootstepResponseMsg(checked, ReachabilityResult());
  ASSERT_NO_THROW(rb::fromCheckFootstepResponseMsg(good, nq));
  ASSERT_FALSE(good.window_time.empty());
  ASSERT_FALSE(good.constraint_time.empty());
  auto malformed = [&](const std::function<void(reach_trajopt::CheckFootstep::Response&)>& edit,
                       const std::string& field) {
    auto m = good;
    edit(m);
    try {
      rb::fromCheckFootstepResponseMsg(m, nq);
      ADD_FAILURE() << field << ": accepted";
    } catch (const ReachError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  if (good.kinematically_feasible) malformed([](auto& m) { m.qdf.pop_back(); }, "qdf");
  malformed([](auto& m) { m.q_f.push_back(0.0); }, "q_f");
  malformed([](auto& m) { m.window_hausdorff.pop_back(); }, "window_hausdorff");
  malformed([](auto& m) { m.window_overlap.push_back(true); }, "window_overlap");
  malformed([](auto& m) { m.witness_q = {1.0, 2.0, 3.0}; }, "witness_q");
  malformed([](auto& m) { m.witness_bridge_start = 1 << 20; }, "witness_bridge_start");
  malformed([](auto& m) { m.constraint_rows.push_back(3); }, "constraint_rows");
  malformed([](auto& m) { m.constraint_rows[0] += 1; }, "constraint_normals");
  malformed([](auto& m) { m.constraint_offsets.pop_back(); }, "constraint_offsets");
  if (good.witness_valid)
    malformed([](auto& m) { m.witness_violation.resize(8); }, "witness_violation");
}
