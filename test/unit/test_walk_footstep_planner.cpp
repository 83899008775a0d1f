// The stepping loop's per-step planning is pluggable (WalkingExperiment::setFootstepPlanner, what
// sim_node ~in_process:=false uses to plan through transition_ocp_node): a plugged planner is
// asked once per checked step with the policy's request and, planning as the in-process one
// does, gives the same walk bit for bit; a planner that rejects leaves the steps unchecked
// ("check_error" with its reason), as the in-process planner's errors do.

#include <gtest/gtest.h>

#include <string>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/walk/walk_setup.h"

using namespace reach_trajopt;

namespace {

std::unique_ptr<WalkingExperiment> proposedExperiment(int steps, const Eigen::Vector2d& push) {
  WalkSetup setup =
      WalkSetup::fromYamlFile(std::string(REACH_TRAJOPT_SOURCE_DIR) + "/config/biped.yaml");
  setup.walk.policy = WalkingPolicy::preset("proposed");
  setup.walk.steps = steps;
  setup.walk.initial_com_velocity = push;
  return setup.experiment(std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf");
}

}  // namespace

TEST(WalkFootstepPlanner, APluggedPlannerIsAskedPerCheckAndGivesTheSameWalk) {
  const std::unique_ptr<WalkingExperiment> e = proposedExperiment(2, Eigen::Vector2d(0.0, 0.4));
  ASSERT_NE(e->footstepPlanner(), nullptr);
  const WalkResult in_process = e->run();
  int calls = 0;
  e->setFootstepPlanner([&](const FootstepPlanRequest& request) {
    ++calls;
    EXPECT_TRUE(request.check_reachability);
    EXPECT_TRUE(request.solve_ocp);
    return e->footstepPlanner()->plan(request);
  });
  const WalkResult plugged = e->run();
  EXPECT_EQ(calls, 2);
  ASSERT_EQ(plugged.records.size(), in_process.records.size());
  EXPECT_EQ(plugged.steps, in_process.steps);
  EXPECT_EQ(plugged.fell, in_process.fell);
  EXPECT_EQ(plugged.sim_time, in_process.sim_time);
  EXPECT_EQ(plugged.max_touchdown_error, in_process.max_touchdown_error);
  for (size_t i = 0; i < plugged.records.size(); ++i) {
    const StepRecord &a = plugged.records[i], &b = in_process.records[i];
    EXPECT_EQ(a.verdict, b.verdict) << i;
    EXPECT_EQ(a.certificate, b.certificate) << i;
    EXPECT_EQ(a.ocp_status, b.ocp_status) << i;
    EXPECT_EQ(a.planned, b.planned) << i;
    EXPECT_EQ(a.executed, b.executed) << i;
    EXPECT_EQ(a.touchdown_time, b.touchdown_time) << i;
    EXPECT_EQ(a.hausdorff_distance, b.hausdorff_distance) << i;
  }
  // Unplugged again: the in-process planner.
  e->setFootstepPlanner({});
  calls = 0;
  const WalkResult again = e->run();
  EXPECT_EQ(calls, 0);
  ASSERT_FALSE(again.records.empty());
  EXPECT_EQ(again.records.back().executed, in_process.records.back().executed);
}

TEST(WalkFootstepPlanner, ARejectingPlannerLeavesTheStepsUnchecked) {
  const std::unique_ptr<WalkingExperiment> e = proposedExperiment(1, Eigen::Vector2d::Zero());
  e->setFootstepPlanner([](const FootstepPlanRequest&) -> FootstepTransition {
    throw RequestError("plan_footstep: no such node");
  });
  const WalkResult r = e->run();
  ASSERT_FALSE(r.records.empty()) << r.summaryLine();
  EXPECT_EQ(r.records.front().verdict, StepVerdict::kCheckError);
  EXPECT_EQ(r.records.front().reason, "plan_footstep: no such node");
  EXPECT_FALSE(r.records.front().ocp_status.has_value());
}
