// ROS layer, service request validation (no master): every malformed request is rejected with
// its reason, a valid one is filled from the model's forward kinematics.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

#include "reach_trajopt/ros/conversions.h"
#include "reach_trajopt/ros/service_requests.h"
#include "reach_trajopt/walk/standing_pose.h"

using namespace reach_trajopt;
namespace rb = reach_trajopt::ros_bridge;

namespace {

const std::string kUrdf = std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf";

struct Fixture {
  std::shared_ptr<const RobotModel> model = RobotModel::fromUrdfFile(kUrdf);
  ContactConfig contact;
  Eigen::VectorXd standing = standingConfiguration(*model, 0.6, "l_sole", RobotConfig{});
  geometry_msgs::Point foothold = [] {
    geometry_msgs::Point p;
    p.x = 0.1;
    p.y = -0.2;
    return p;
  }();

  ContactTransition parse(const std::string& frame, const std::string& mode,
                          const std::vector<double>& q, const std::vector<double>& qd,
                          double duration = 0.0) const {
    return rb::parseFootholdRequest(*model, contact, frame, mode, q, qd, foothold, duration, 0.08,
                                    standing);
  }
};

void expectReason(const std::function<void()>& f, const std::string& reason) {
  try {
    f();
    ADD_FAILURE() << "no error; expected '" << reason << "'";
  } catch (const ReachError& e) {
    EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(RosServiceRequests, RejectsMalformedRequestsWithTheReason) {
  Fixture f;
  const int nq = f.model->nq();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expectReason([&] { f.parse("map", "SS-L", {}, {}); }, "unknown frame 'map'");
  expectReason([&] { f.parse("world", "", {}, {}); }, "empty contact set");
  expectReason([&] { f.parse("world", "flight", {}, {}); }, "empty contact set");
  expectReason([&] { f.parse("world", "DS", {}, {}); }, "no swing sole");
  expectReason([&] { f.parse("world", "SS-Q", {}, {}); }, "SS-Q");
  expectReason([&] { f.parse("world", "SS-L", std::vector<double>(3, 0.0), {}); }, "expected size");
  std::vector<double> q(f.standing.data(), f.standing.data() + nq), qd(nq, 0.0);
  q[7] = nan;
  expectReason([&] { f.parse("world", "SS-L", q, qd); }, "non-finite");
  expectReason([&] { f.parse("world", "SS-L", {}, {}, -0.1); }, "must be positive");
  // Over-limit requests are rejected before any IK or check runs (docs/limits.md).
  expectReason([&] { f.parse("world", "SS-L", {}, {}, 1000.0); }, "swing_duration");
  expectReason([&] { f.parse("world", "SS-L", {}, {}, nan); }, "swing_duration");
  expectReason([&] { f.parse("world", "SS-L", std::vector<double>(200000, 0.0), qd); },
               "q: expected size");
  const ContactTransition tiny = f.parse("world", "SS-L", {}, {}, 1e-300);
  // Named as swing_duration, not as the scaled window (issue 43).
  expectReason([&] { rb::reachConfigForDuration(ReachConfig{}, tiny.horizon).validate(); },
               "swing_duration 1e-300 s is shorter than one time step of the check");
  expectReason([&] { rb::reachConfigForDuration(ReachConfig{}, 1e-9); },
               "swing_duration 1e-09 s is shorter than one time step");
  expectReason([&] { f.parse("world", "SS-L", {}, {}, INFINITY); },
               "swing_duration must be finite");
  f.foothold.x = INFINITY;
  expectReason([&] { f.parse("world", "SS-L", {}, {}); }, "non-finite");
  f.foothold.x = 0.1;
  f.foothold.z = 0.25;
  expectReason([&] { f.parse("world", "SS-L", {}, {}); }, "must lie on the ground");
}

TEST(RosServiceRequests, ValidRequestTakesTheStanceSoleFromTheModel) {
  Fixture f;
  const ContactTransition r = f.parse("", "SS-R", {}, {});  // "" means "world"
  EXPECT_EQ(r.stance, Side::kRight);
  EXPECT_EQ(r.q0, f.standing);
  EXPECT_TRUE(r.qd0.isZero());
  EXPECT_DOUBLE_EQ(r.horizon, 0.08);
  Workspace ws(*f.model);
  f.model->update(ws, f.standing, Eigen::VectorXd::Zero(f.model->nq()));
  const Eigen::Vector3d sole = f.model->framePose(ws, f.model->frameId("r_sole")).translation();
  EXPECT_LT((r.stance_contact.position - sole).norm(), 1e-12);
  EXPECT_NEAR(r.stance_contact.yaw, 0.0, 1e-9);
  EXPECT_EQ(r.target.position, Eigen::Vector3d(0.1, -0.2, 0.0));
  const ContactTransition r2 = f.parse("world", "SS-L", {}, {}, 0.3);
  EXPECT_EQ(r2.stance, Side::kLeft);
  EXPECT_DOUBLE_EQ(r2.horizon, 0.3);
}

TEST(RosServiceRequests, TrajectoryMessageIsKnotMajor) {
  Fixture f;
  TransitionResult r;
  r.status = OcpStatus::kRelaxed;
  r.nlopt_status = "FTOL_REACHED";
  r.time = Eigen::VectorXd::LinSpaced(3, 0.0, 0.002);
  r.q = Eigen::MatrixXd::Zero(f.model->nq(), 3);
  r.q(1, 2) = 7.0;  // coordinate 1 at knot 2
  r.qd = r.q;
  r.u = Eigen::MatrixXd::Zero(f.model->nu(), 3);
  r.lambda = Eigen::MatrixXd::Zero(12, 3);
  r.lambda(8, 1) = 5.0;  // right sole fz at knot 1
  r.eps = Eigen::Vector2d(0.01, -0.02);
  const auto m = rb::toTransitionTrajectoryMsg(r, *f.model, {"l_sole", "r_sole"}, ros::Time(2.0));
  EXPECT_EQ(m.status, "relaxed");
  EXPECT_EQ(m.header.frame_id, "world");
  EXPECT_EQ(m.time.size(), 3u);
  EXPECT_EQ(m.q.size(), static_cast<size_t>(3 * f.model->nq()));
  EXPECT_EQ(m.q[2 * f.model->nq() + 1], 7.0);
  EXPECT_EQ(m.lambda[1 * 12 + 8], 5.0);
  EXPECT_EQ(m.actuated_joint_names.size(), static_cast<size_t>(f.model->nu()));
  EXPECT_DOUBLE_EQ(m.relaxation.y, -0.02);
  EXPECT_NE(m.message.find("FTOL_REACHED"), std::string::npos);
}

TEST(RosServiceRequests, ReachConfigKeepsTheWindowFractionsOfTheHorizon) {
  ReachConfig base;
  base.horizon = 0.08;
  base.window_start = 0.03;
  base.window_end = 0.05;
  const ReachConfig same = rb::reachConfigForDuration(base, 0.08);
  EXPECT_EQ(same.horizon, base.horizon);  // a request without a duration: bit for bit
  EXPECT_EQ(same.window_start, base.window_start);
  EXPECT_EQ(same.window_end, base.window_end);
  const ReachConfig twice = rb::reachConfigForDuration(base, 0.16);
  EXPECT_DOUBLE_EQ(twice.horizon, 0.16);
  EXPECT_DOUBLE_EQ(twice.window_start, 0.06);
  EXPECT_DOUBLE_EQ(twice.window_end, 0.10);
  EXPECT_EQ(twice.budgets.full.initial_samples, base.budgets.full.initial_samples);
}

TEST(RosServiceRequests, ReachProblemHoldsTheStanceSoleAndTargetsTheFoothold) {
  Fixture f;
  const ContactTransition r = f.parse("world", "SS-R", {}, {});
  KinematicFeasibilityResult ik;
  ik.feasible = true;
  ik.q_f = f.standing;
  ik.q_f[0] += 0.01;
  ik.qd_f = Eigen::VectorXd::Zero(f.model->nq());
  const ReachProblem p = footstepProblem(r, ik.q_f, ik.qd_f);
  EXPECT_EQ(p.mode, ContactMode::singleSupport(Side::kRight));
  EXPECT_EQ(p.q0, r.q0);
  EXPECT_EQ(p.qd0, r.qd0);
  EXPECT_EQ(p.qf, ik.q_f);
  EXPECT_EQ(p.qdf, ik.qd_f);
  EXPECT_FALSE(p.footholds[0].has_value());
  ASSERT_TRUE(p.footholds[1].has_value());
  EXPECT_TRUE(p.footholds[1]->isApprox(r.stance_contact.pose()));
  ASSERT_TRUE(p.target.has_value());
  EXPECT_EQ(p.target->translation(), Eigen::Vector3d(0.1, -0.2, 0.0));
  EXPECT_EQ(rb::swingFrame(f.contact, Side::kRight), "l_sole");
  EXPECT_EQ(rb::swingFrame(f.contact, Side::kLeft), "r_sole");
}

TEST(RosServiceRequests, InfeasibleFootholdIsUnreachableWithoutSets) {
  const auto m = rb::infeasibleFootholdMsg("joint limits", "r_sole",
                                           Eigen::Vector3d(0.9, -0.1, 0.0), ros::Time(3.0));
  EXPECT_EQ(m.verdict, "unreachable");
  EXPECT_EQ(m.message, "kinematically infeasible foothold: joint limits");
  EXPECT_EQ(m.header.frame_id, "world");
  EXPECT_EQ(m.header.stamp, ros::Time(3.0));
  EXPECT_EQ(m.swing_frame, "r_sole");
  EXPECT_EQ(m.foothold.x, 0.9);
  EXPECT_TRUE(m.slices.empty());
  EXPECT_EQ(m.hausdorff_distance, -1.0);
  EXPECT_EQ(m.witness_distance, -1.0);
}

TEST(RosServiceRequests, ReachabilityMessageFromAResultAndAFoothold) {
  // Two slices of two samples each; the second has the smaller d_H and is the witness slice.
  ReachResult r;
  r.reachable = true;
  r.reason = "d_H below delta";
  for (int j = 0; j < 2; ++j) {
    SampleSlice f, b;
    f.time = b.time = 0.01 * j;
    f.parent = b.parent = {-1, -1};
    f.output = Eigen::MatrixXd::Zero(3, 2);
    f.output(0, 1) = 1.0;
    b.output = f.output;
    b.output(1, 0) = 0.5;
    f.boundary = b.boundary = {0, 1};
    r.forward.push_back(f);
    r.backward.push_back(b);
    SliceComparison c;
    c.time = 0.01 * j;
    c.forward_slice = c.backward_slice = j;
    c.distance.hausdorff = j == 0 ? 0.5 : 0.25;
    c.distance.resolution_a = c.distance.resolution_b = 1.0;
    c.distance.closest = 0.1;
    c.distance.closest_a = 1;
    c.distance.closest_b = 0;
    r.window.push_back(c);
  }
  r.best = 1;
  r.counts.forward_qps = 70;
  r.counts.backward_qps = 30;
  r.budgets = 2;
  const Eigen::Vector3d foothold(0.2, -0.25, 0.001);
  const auto m = rb::toReachabilityResultMsg(r, foothold, "r_sole", 1e-5, ros::Time(4.0), true);
  EXPECT_EQ(m.verdict, "reachable");
  EXPECT_EQ(m.message, "d_H below delta");
  EXPECT_EQ(m.foothold.x, 0.2);
  EXPECT_EQ(m.foothold.z, 0.001);
  ASSERT_EQ(m.slices.size(), 2u);
  EXPECT_NEAR(m.slices[1].header.stamp.toSec(), 4.01, 1e-9);
  EXPECT_EQ(m.slices[1].forward_outputs.size(), 2u);
  EXPECT_DOUBLE_EQ(m.hausdorff_distance, 0.25);
  EXPECT_DOUBLE_EQ(m.witness_time, 0.01);
  EXPECT_DOUBLE_EQ(m.witness_forward.x, 1.0);
  EXPECT_DOUBLE_EQ(m.witness_backward.y, 0.5);
  EXPECT_EQ(m.qps, 100u);
  EXPECT_EQ(m.budgets, 2u);
  EXPECT_FALSE(m.gave_up);
  r.budgets = 1;
  r.gave_up = true;  // the quick budget alone, given up
  const auto given_up =
      rb::toReachabilityResultMsg(r, foothold, "r_sole", 1e-5, ros::Time(4.0), false);
  EXPECT_EQ(given_up.budgets, 1u);
  EXPECT_TRUE(given_up.gave_up);
  // The request overload is the same message with the request's target.
  Fixture f;
  ContactTransition q = f.parse("world", "SS-L", {}, {});
  q.target.position = foothold;
  const auto m2 = rb::toReachabilityResultMsg(r, q, "r_sole", 1e-5, ros::Time(4.0), false);
  EXPECT_EQ(m2.foothold, m.foothold);
  EXPECT_TRUE(m2.slices[1].forward_outputs.empty());
  EXPECT_EQ(m2.slices[1].forward_boundary, m.slices[1].forward_boundary);
}

TEST(RosServiceRequests, ARejectedRequestGetsAnErrorTrajectoryWithItsReason) {
  const ros::Time t0(1.5);
  const reach_trajopt::TransitionTrajectory m = rb::errorTrajectoryMsg("q0: 3 numbers", t0);
  EXPECT_EQ(m.status, "error");
  EXPECT_EQ(m.message, "q0: 3 numbers");
  EXPECT_EQ(m.header.stamp, t0);
  EXPECT_EQ(m.header.frame_id, std::string(rb::kWorldFrame));
  EXPECT_TRUE(m.q.empty());
}
