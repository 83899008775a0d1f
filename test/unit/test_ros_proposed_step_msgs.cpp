// ROS layer, messages of a proposed walking step (no master): the check becomes the
// ReachabilityResult of reachability_node (or its "unreachable" verdict for a kinematically
// infeasible foothold), its markers, and the OCP's TransitionTrajectory, all stamped with the
// time of the check in "world".

#include <gtest/gtest.h>

#include <string>

#include "reach_trajopt/ros/markers.h"
#include "reach_trajopt/ros/proposed_step_msgs.h"

using namespace reach_trajopt;
namespace rb = reach_trajopt::ros_bridge;

namespace {

const std::string kUrdf = std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf";

// A check with `slices` window slices of three samples each, the last slice the witness.
ReachResult makeReach(int slices) {
  ReachResult r;
  r.reachable = true;
  r.reason = "reachable: d_H below delta";
  for (int j = 0; j < slices; ++j) {
    SampleSlice s;
    s.time = 0.03 + 0.001 * j;
    s.parent = {-1, -1, -1};
    s.output = Eigen::MatrixXd::Zero(3, 3);
    s.output(0, 1) = 0.01;
    s.output(1, 2) = 0.01;
    s.boundary = {0, 1, 2};
    r.forward.push_back(s);
    r.backward.push_back(s);
    SliceComparison c;
    c.time = s.time;
    c.forward_slice = c.backward_slice = j;
    c.distance.hausdorff = 1e-3 / (j + 1);
    c.distance.resolution_a = c.distance.resolution_b = 0.01;
    c.distance.closest = 0.0;
    c.distance.closest_a = c.distance.closest_b = 0;
    r.window.push_back(c);
  }
  r.best = slices - 1;
  return r;
}

TransitionResult makeTrajectory(const RobotModel& model, int knots) {
  TransitionResult t;
  t.status = OcpStatus::kConverged;
  t.nlopt_status = "FTOL_REACHED";
  t.time = Eigen::VectorXd::LinSpaced(knots, 0.0, 0.001 * (knots - 1));
  t.q = Eigen::MatrixXd::Zero(model.nq(), knots);
  t.qd = t.q;
  t.qdd = t.q;
  t.u = Eigen::MatrixXd::Zero(model.nu(), knots);
  t.lambda = Eigen::MatrixXd::Zero(12, knots);
  t.landing_position = Eigen::Vector3d(0.1, 0.2, 0.0);
  return t;
}

/// What toProposedStepMsgs reads of a step whose `swing` sole moves: the biped, the default
/// contact section, the step's record and its FootstepTransition (to be filled by the test).
struct ProposedStepInputs {
  std::shared_ptr<const RobotModel> model;
  ContactConfig contact;
  StepRecord record;
  FootstepTransition step;
};

ProposedStepInputs proposedStepInputs(Side swing) {
  ProposedStepInputs in;
  in.model = RobotModel::fromUrdfFile(kUrdf);
  in.record.swing = swing;
  return in;
}

}  // namespace

TEST(RosProposedStepMsgs, CheckedFootholdIsTheTvrFootholdOnTheGround) {
  StepRecord r;
  r.planned_tvr = Eigen::Vector2d(0.4, -0.3);
  r.planned = Eigen::Vector2d(0.35, -0.28);  // the landing point after the check
  EXPECT_EQ(rb::checkedFoothold(r, 0.002), Eigen::Vector3d(0.4, -0.3, 0.002));
}

TEST(RosProposedStepMsgs, ReachableStepGivesSetsMarkersAndTrajectory) {
  auto [model, contact, record, step] = proposedStepInputs(Side::kLeft);
  step.check.kinematically_feasible = true;
  step.check.reachable = true;
  step.check.reach = makeReach(4);
  step.trajectory = makeTrajectory(*model, 5);
  // The planner's verdict (certified by the local solve) is what the message carries.
  step.reachable = true;
  step.certificate = Certificate::kLocalSolve;
  step.verdict = StepVerdict::kReachable;
  const Eigen::Vector3d foothold(0.1, 0.2, 0.0);
  const ros::Time t0(2.14);
  const rb::ProposedStepMsgs m =
      rb::toProposedStepMsgs(*model, contact, record, step, foothold, 1e-5, t0, true);

  EXPECT_EQ(m.reachability.verdict, "reachable");
  EXPECT_EQ(m.reachability.certificate, "local_solve");
  EXPECT_EQ(m.reachability.header.frame_id, "world");
  EXPECT_EQ(m.reachability.header.stamp, t0);
  EXPECT_EQ(m.reachability.swing_frame, "l_sole");  // the left sole swings
  EXPECT_EQ(m.reachability.foothold.y, 0.2);
  EXPECT_EQ(m.reachability.delta, 1e-5);
  ASSERT_EQ(m.reachability.slices.size(), 4u);
  EXPECT_EQ(m.reachability.slices[0].forward_outputs.size(), 3u);  // samples were asked for
  EXPECT_DOUBLE_EQ(m.reachability.hausdorff_distance, 0.25e-3);

  int sets = 0, checked = 0;
  for (const auto& mk : m.markers.markers) {
    EXPECT_EQ(mk.header.frame_id, "world") << mk.ns;
    EXPECT_GE(mk.header.stamp, t0) << mk.ns;
    sets += mk.ns == rb::kNsForwardSet;
    checked += mk.ns == rb::kNsCheckedFoothold;
  }
  EXPECT_EQ(sets, 4);
  EXPECT_EQ(checked, 1);

  EXPECT_EQ(m.trajectory.status, "converged");
  EXPECT_EQ(m.trajectory.header.frame_id, "world");
  EXPECT_EQ(m.trajectory.header.stamp, t0);
  ASSERT_EQ(m.trajectory.time.size(), 5u);
  for (size_t k = 1; k < m.trajectory.time.size(); ++k)
    EXPECT_GT(m.trajectory.time[k], m.trajectory.time[k - 1]);
  EXPECT_EQ(m.trajectory.q.size(), 5u * m.trajectory.joint_names.size());
  EXPECT_EQ(m.trajectory.contact_frames, (std::vector<std::string>{"l_sole", "r_sole"}));

  const rb::ProposedStepMsgs thin =
      rb::toProposedStepMsgs(*model, contact, record, step, foothold, 1e-5, t0, false);
  EXPECT_TRUE(thin.reachability.slices[0].forward_outputs.empty());
  EXPECT_EQ(thin.reachability.slices[0].forward_boundary.size(), 3u);
}

TEST(RosProposedStepMsgs, KinematicallyInfeasibleStepIsUnreachableWithoutSets) {
  auto [model, contact, record, step] = proposedStepInputs(Side::kRight);
  step.verdict = StepVerdict::kKinematicallyInfeasible;
  step.check.kinematically_feasible = false;
  step.check.kinematics.reason = "knee at its limit";
  step.trajectory.status = OcpStatus::kFailed;
  step.trajectory.reason = "no kinematically feasible foothold toward the target";
  const ros::Time t0(1.0);
  const rb::ProposedStepMsgs m = rb::toProposedStepMsgs(
      *model, contact, record, step, Eigen::Vector3d(0.9, -0.2, 0.0), 1e-5, t0, true);
  EXPECT_EQ(m.reachability.verdict, "unreachable");
  EXPECT_EQ(m.reachability.message, "kinematically infeasible foothold: knee at its limit");
  EXPECT_EQ(m.reachability.swing_frame, "r_sole");
  EXPECT_EQ(m.reachability.foothold.x, 0.9);
  EXPECT_TRUE(m.reachability.slices.empty());
  ASSERT_EQ(m.markers.markers.size(), 1u);  // only the foothold, no witness at the origin
  EXPECT_EQ(m.markers.markers[0].ns, rb::kNsCheckedFoothold);
  EXPECT_EQ(m.markers.markers[0].header.frame_id, "world");
  EXPECT_EQ(m.trajectory.status, "failed");
  EXPECT_TRUE(m.trajectory.time.empty());
  EXPECT_EQ(m.trajectory.header.stamp, t0);
  EXPECT_NE(m.trajectory.message.find("no kinematically feasible foothold"), std::string::npos);
}
