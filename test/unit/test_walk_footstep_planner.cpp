// The stepping loop's per-step planning is pluggable (WalkingExperiment::setFootstepPlanner, what
// sim_node ~in_process:=false uses to plan through transition_ocp_node): a plugged planner is
// asked once per checked step with the policy's request and, planning as the in-process one
// does, gives the same walk bit for bit; a planner that rejects leaves the steps unchecked
// ("check_error" with its reason), as the in-process planner's errors do, each step sent to the
// TVR step clipped to the heuristic bounds.

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

// A planner that throws (a bad state, a node that is gone) leaves the step without a plan of
// the policy's: it takes the last resort of a fallback that found nothing, the TVR step clipped
// to the heuristic bounds box about the stance sole (config/biped.yaml's planner section), not
// the unbounded TVR step, which after a push can be a metre away.
TEST(WalkFootstepPlanner, ARejectingPlannerSendsTheStepToTheBoundedTvrStep) {
  WalkSetup setup =
      WalkSetup::fromYamlFile(std::string(REACH_TRAJOPT_SOURCE_DIR) + "/config/biped.yaml");
  const std::unique_ptr<WalkingExperiment> e = proposedExperiment(4, Eigen::Vector2d(0.0, 0.4));
  e->setFootstepPlanner([](const FootstepPlanRequest&) -> FootstepTransition {
    throw RequestError("plan_footstep: no such node");
  });
  const WalkResult r = e->run();
  ASSERT_FALSE(r.records.empty()) << r.summaryLine();
  const TvrConfig& box = setup.tvr;
  int outside = 0;  // TVR steps the box moved
  for (const StepRecord& s : r.records) {
    SCOPED_TRACE("step " + std::to_string(s.index));
    EXPECT_EQ(s.verdict, StepVerdict::kCheckError);
    EXPECT_EQ(s.reason, "plan_footstep: no such node");
    EXPECT_FALSE(s.ocp_status.has_value());
    EXPECT_EQ(s.foothold_source, FootholdSource::kClippedToBounds);
    // The box: x offset in [x_min, x_max], the y offset toward the swing's side in
    // [y_min, y_max] (the walk in place keeps heading 0).
    const double side = s.swing == Side::kLeft ? 1.0 : -1.0;
    auto inBox = [&](const Eigen::Vector2d& p) {
      const Eigen::Vector2d d = p - s.stance;
      const double tol = 1e-9;
      return d.x() >= box.foot_offset_x_min - tol && d.x() <= box.foot_offset_x_max + tol &&
             side * d.y() >= box.foot_offset_y_min - tol &&
             side * d.y() <= box.foot_offset_y_max + tol;
    };
    EXPECT_TRUE(inBox(s.planned)) << s.planned.transpose() << " about " << s.stance.transpose();
    if (inBox(s.planned_tvr)) {
      EXPECT_TRUE(s.planned.isApprox(s.planned_tvr, 1e-12));
    } else {
      ++outside;
      EXPECT_GT((s.planned - s.planned_tvr).norm(), 1e-6);
    }
  }
  EXPECT_GT(outside, 0) << "no TVR step of this walk left the box: the case tests nothing";
}
