// ROS layer, pure conversions (no master): geometry round trips and rejections, the TF of every
// link against the URDF's joint origins and axes read independently by urdfdom, joint states,
// the sole-frame wrench, and the walking records -> messages.

#include <gtest/gtest.h>
#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <map>
#include <random>

#include "reach_trajopt/ros/conversions.h"

using namespace reach_trajopt;
namespace rb = reach_trajopt::ros_bridge;

namespace {

const std::string kUrdf = std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf";

Eigen::Isometry3d urdfPose(const urdf::Pose& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  T.linear() =
      Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).toRotationMatrix();
  return T;
}

Eigen::Isometry3d randomIsometry(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(n(rng), n(rng), n(rng));
  return T;
}

}  // namespace

TEST(RosConversions, TransformAndPoseRoundTrip) {
  std::mt19937 rng(3);
  for (int k = 0; k < 20; ++k) {
    const Eigen::Isometry3d T = randomIsometry(rng);
    const Eigen::Isometry3d A = rb::fromTransformMsg(rb::toTransformMsg(T));
    const Eigen::Isometry3d B = rb::fromPoseMsg(rb::toPoseMsg(T));
    EXPECT_LT((A.matrix() - T.matrix()).norm(), 1e-12);
    EXPECT_LT((B.matrix() - T.matrix()).norm(), 1e-12);
    EXPECT_GE(rb::toTransformMsg(T).rotation.w, 0.0);
  }
  Vector6d w;
  w << 1, -2, 3, -4, 5, -6;
  EXPECT_EQ(rb::fromWrenchMsg(rb::toWrenchMsg(w)), w);
  const geometry_msgs::Point p = rb::toPointMsg(Eigen::Vector2d(0.3, -0.2), 0.05);
  EXPECT_EQ(p.x, 0.3);
  EXPECT_EQ(p.y, -0.2);
  EXPECT_EQ(p.z, 0.05);
}

TEST(RosConversions, RejectsBadQuaternions) {
  geometry_msgs::Pose pose;  // all zero: norm 0
  EXPECT_THROW(rb::fromPoseMsg(pose), ReachError);
  pose.orientation.w = std::nan("");
  EXPECT_THROW(rb::fromPoseMsg(pose), ReachError);
  geometry_msgs::Transform t;
  t.rotation.w = 2.0;
  EXPECT_THROW(rb::fromTransformMsg(t), ReachError);
  t.rotation.w = 1.0;
  EXPECT_NO_THROW(rb::fromTransformMsg(t));
}

// Every link's TF equals the URDF joint origin times the joint motion (read by urdfdom, not by
// our model), and world -> root is the floating base x, y, z, R = Rz(yaw) Ry(pitch) Rx(roll).
TEST(RosConversions, LinkTransformsMatchUrdfJoints) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  const urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDFFile(kUrdf);
  ASSERT_TRUE(urdf);
  Workspace ws(*model);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  Eigen::VectorXd q = model->neutralConfiguration();
  for (int i = 0; i < model->nq(); ++i) q[i] += u(rng);
  model->update(ws, q, Eigen::VectorXd::Zero(model->nq()));

  rb::LinkTransforms tf(*model);
  const auto& msgs = tf.compute(ws, ros::Time(1.5));
  ASSERT_EQ(msgs.size(), model->linkNames().size());
  std::map<std::string, std::string> parent_of;
  for (const auto& m : msgs) {
    EXPECT_EQ(m.header.stamp, ros::Time(1.5));
    parent_of[m.child_frame_id] = m.header.frame_id;
    const Eigen::Isometry3d rel = rb::fromTransformMsg(m.transform);
    const urdf::LinkConstSharedPtr link = urdf->getLink(m.child_frame_id);
    ASSERT_TRUE(link) << m.child_frame_id;
    Eigen::Isometry3d expected = Eigen::Isometry3d::Identity();
    if (!link->parent_joint) {  // the root: floating base
      EXPECT_EQ(m.header.frame_id, "world");
      expected.translation() = q.head<3>();
      expected.linear() = (Eigen::AngleAxisd(q[3], Eigen::Vector3d::UnitZ()) *
                           Eigen::AngleAxisd(q[4], Eigen::Vector3d::UnitY()) *
                           Eigen::AngleAxisd(q[5], Eigen::Vector3d::UnitX()))
                              .toRotationMatrix();
    } else {
      const urdf::Joint& j = *link->parent_joint;
      EXPECT_EQ(m.header.frame_id, j.parent_link_name);
      expected = urdfPose(j.parent_to_joint_origin_transform);
      const Eigen::Vector3d axis(j.axis.x, j.axis.y, j.axis.z);
      if (j.type == urdf::Joint::REVOLUTE || j.type == urdf::Joint::CONTINUOUS) {
        expected.rotate(Eigen::AngleAxisd(q[model->jointIndex(j.name)], axis));
      } else if (j.type == urdf::Joint::PRISMATIC) {
        expected.translate(q[model->jointIndex(j.name)] * axis);
      }
    }
    EXPECT_LT((rel.matrix() - expected.matrix()).norm(), 1e-9) << m.child_frame_id;
  }
  // The tree is connected: every link reaches "world" through its parents.
  for (const auto& [child, parent] : parent_of) {
    std::string f = child;
    int hops = 0;
    while (f != "world" && hops++ < 100) {
      ASSERT_TRUE(parent_of.count(f)) << "frame " << f << " has no parent";
      f = parent_of[f];
    }
    EXPECT_EQ(f, "world");
  }
}

TEST(RosConversions, JointStateHoldsActuatedJointsInUrdfNames) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  const urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDFFile(kUrdf);
  Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(model->nq(), 0.0, 1.0);
  Eigen::VectorXd qd = -q;
  Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(model->nu(), 10.0, 20.0);
  sensor_msgs::JointState js;
  rb::fillJointState(*model, q, qd, u, ros::Time(2.0), js);
  ASSERT_EQ(static_cast<int>(js.name.size()), model->nu());
  int movable = 0;
  for (const auto& [name, joint] : urdf->joints_)
    if (joint->type != urdf::Joint::FIXED) ++movable;
  EXPECT_EQ(static_cast<int>(js.name.size()), movable);
  for (size_t k = 0; k < js.name.size(); ++k) {
    ASSERT_TRUE(urdf->getJoint(js.name[k])) << js.name[k];
    const int i = model->jointIndex(js.name[k]);
    EXPECT_EQ(js.position[k], q[i]);
    EXPECT_EQ(js.velocity[k], qd[i]);
    EXPECT_EQ(js.effort[k], u[static_cast<int>(k)]);
  }
  rb::fillJointState(*model, q, qd, Eigen::VectorXd(), ros::Time(2.0), js);
  EXPECT_TRUE(js.effort.empty());
  EXPECT_THROW(rb::fillJointState(*model, q.head(3), qd, u, ros::Time(), js), ReachError);
  EXPECT_THROW(rb::fillJointState(*model, q, qd, u.head(2), ros::Time(), js), ReachError);
}

TEST(RosConversions, SoleWrenchIsExpressedInTheSoleFrame) {
  SoleContact sole;
  sole.frame = "l_sole";
  sole.sole_pose = Eigen::Isometry3d::Identity();
  sole.sole_pose.linear() =
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  sole.wrench << 1.0, 0.0, 500.0, 0.0, 2.0, 0.5;
  const geometry_msgs::WrenchStamped m = rb::toSoleWrenchMsg(sole, ros::Time(3.0));
  EXPECT_EQ(m.header.frame_id, "l_sole");
  // World x is the sole's -y after a +90 deg yaw; world y is the sole's +x.
  EXPECT_NEAR(m.wrench.force.x, 0.0, 1e-12);
  EXPECT_NEAR(m.wrench.force.y, -1.0, 1e-12);
  EXPECT_NEAR(m.wrench.force.z, 500.0, 1e-12);
  EXPECT_NEAR(m.wrench.torque.x, 2.0, 1e-12);
  EXPECT_NEAR(m.wrench.torque.y, 0.0, 1e-12);
  EXPECT_NEAR(m.wrench.torque.z, 0.5, 1e-12);
}

TEST(RosConversions, WalkTickMessages) {
  std::vector<SoleContact> soles(2);
  soles[0].frame = "l_sole";
  soles[1].frame = "r_sole";
  soles[0].in_contact = true;
  soles[0].wrench << 0, 0, 600, 0, 0, 0;
  soles[1].sole_pose.translation() = Eigen::Vector3d(0.1, -0.2, 0.0);
  WbcOutput wbc;
  wbc.lambda_left << 1, 2, 3, 4, 5, 6;
  wbc.lambda_right << -1, -2, -3, -4, -5, -6;
  WalkTick tick;
  tick.time = 0.5;
  tick.mode = ContactMode::singleSupport(Side::kLeft);
  tick.com = Eigen::Vector3d(0.1, 0.0, 0.95);
  tick.com_velocity = Eigen::Vector3d(0.3, -0.1, 0.0);
  tick.com_reference = Eigen::Vector3d(0.12, 0.01, 0.95);
  tick.wbc = &wbc;
  tick.soles = &soles;
  const auto com = rb::toCenterOfMassStateMsg(tick, ros::Time(0.5));
  EXPECT_EQ(com.header.frame_id, "world");
  EXPECT_EQ(com.contact_mode, "SS-L");
  EXPECT_EQ(com.position.z, 0.95);
  EXPECT_EQ(com.velocity.x, 0.3);
  EXPECT_EQ(com.reference.x, 0.12);
  const auto cs = rb::toContactStateMsg(tick, ros::Time(0.5));
  ASSERT_EQ(cs.frames.size(), 2u);
  EXPECT_EQ(cs.frames[1], "r_sole");
  EXPECT_TRUE(cs.in_contact[0]);
  EXPECT_FALSE(cs.in_contact[1]);
  EXPECT_EQ(cs.measured[0].force.z, 600.0);
  EXPECT_EQ(cs.commanded[0].torque.z, 6.0);
  EXPECT_EQ(cs.commanded[1].force.x, -1.0);
  EXPECT_EQ(cs.sole_poses[1].position.y, -0.2);
}

TEST(RosConversions, StepReportAndContactPlan) {
  StepRecord r;
  r.index = 3;
  r.swing = Side::kLeft;
  r.plan_time = 1.2;
  r.touchdown_time = 1.47;
  r.touched_down = true;
  r.stance = Eigen::Vector2d(0.1, -0.1);
  r.planned_tvr = Eigen::Vector2d(0.5, 0.4);
  r.planned = Eigen::Vector2d(0.42, 0.4);
  r.executed = Eigen::Vector3d(0.43, 0.39, 0.001);
  r.touchdown_error = std::hypot(0.01, 0.01);
  r.offset_clipped = true;
  r.com_at_plan.p = Eigen::Vector2d(0.2, 0.0);
  r.com_at_plan.pd = Eigen::Vector2d(0.4, 0.1);
  const auto m = rb::toStepReportMsg(r, WalkingPolicy::preset("baseline"), false, 0.001);
  EXPECT_EQ(m.header.stamp, ros::Time(1.47));
  EXPECT_EQ(m.header.frame_id, "world");
  EXPECT_EQ(m.index, 3u);
  EXPECT_EQ(m.mode, "baseline");
  EXPECT_EQ(m.policy, "bounds=on check=none on_fail=- swing=interpolation");
  EXPECT_EQ(m.swing_side, "left");
  EXPECT_EQ(m.planned.x, 0.42);
  EXPECT_EQ(m.planned.z, 0.001);
  EXPECT_EQ(m.planned_tvr.x, 0.5);
  EXPECT_EQ(m.executed.y, 0.39);
  EXPECT_TRUE(m.offset_clipped);
  EXPECT_FALSE(m.fell);
  EXPECT_EQ(m.com_velocity_at_plan.x, 0.4);
  EXPECT_EQ(m.verdict, "not_checked");
  EXPECT_EQ(m.ocp_status, "none");

  TvrInput in;
  in.swing = Side::kRight;
  in.stance = Eigen::Vector2d(0.0, 0.1);
  in.com.p = Eigen::Vector2d(0.05, 0.0);
  TvrStep step;
  step.alpha = Eigen::Vector2d(0.2, -0.2);
  step.alpha_tvr = Eigen::Vector2d(0.25, -0.2);
  step.com_velocity_used = Eigen::Vector2d(0.3, 0.0);
  const auto plan = rb::toContactPlanMsg(in, step, 0.25, 0.05, 0.0, ros::Time(4.0));
  ASSERT_EQ(plan.modes.size(), 2u);
  EXPECT_EQ(plan.modes[0], "SS-L");  // the right sole swings: the left one is the stance
  EXPECT_EQ(plan.modes[1], "DS");
  EXPECT_EQ(plan.durations[0], 0.25);
  ASSERT_EQ(plan.footholds.size(), 1u);
  EXPECT_EQ(plan.foothold_sides[0], "right");
  EXPECT_EQ(plan.footholds[0].x, 0.2);
  EXPECT_EQ(plan.foothold_tvr.x, 0.25);
  EXPECT_THROW(rb::toContactPlanMsg(in, step, 0.0, 0.05, 0.0, ros::Time()), ReachError);
  EXPECT_THROW(rb::toContactPlanMsg(in, step, 0.25, std::nan(""), 0.0, ros::Time()), ReachError);
}
