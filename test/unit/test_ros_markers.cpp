// ROS layer, pure marker builders (no master): frames, namespaces, sizes, point counts and the
// rejection of bad input.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/ros/markers.h"

using namespace reach_trajopt;
namespace rb = reach_trajopt::ros_bridge;
using visualization_msgs::Marker;

TEST(RosMarkers, FootholdsAreSoleSizedCubesInTheWorld) {
  const std::vector<Eigen::Vector3d> planned = {{0.1, 0.2, 0.0}, {0.3, -0.2, 0.0}};
  const std::vector<Eigen::Vector3d> executed = {{0.11, 0.19, 0.001}};
  const auto a = rb::footholdMarkers(planned, executed, 0.135, 0.08, ros::Time(2.0));
  ASSERT_EQ(a.markers.size(), 2u);
  const Marker& p = a.markers[0];
  const Marker& e = a.markers[1];
  EXPECT_EQ(p.ns, rb::kNsFootholdsPlanned);
  EXPECT_EQ(e.ns, rb::kNsFootholdsExecuted);
  for (const Marker* m : {&p, &e}) {
    EXPECT_EQ(m->header.frame_id, "world");
    EXPECT_EQ(m->header.stamp, ros::Time(2.0));
    EXPECT_EQ(m->type, Marker::CUBE_LIST);
    EXPECT_EQ(m->action, Marker::ADD);
    EXPECT_DOUBLE_EQ(m->scale.x, 0.27);
    EXPECT_DOUBLE_EQ(m->scale.y, 0.16);
    EXPECT_GT(m->scale.z, 0.0);
    EXPECT_EQ(m->pose.orientation.w, 1.0);
    EXPECT_GT(m->color.a, 0.0f);
  }
  ASSERT_EQ(p.points.size(), 2u);
  EXPECT_EQ(p.points[1].x, 0.3);
  ASSERT_EQ(e.points.size(), 1u);
  EXPECT_EQ(e.points[0].z, 0.001);
  EXPECT_THROW(rb::footholdMarkers(planned, executed, 0.0, 0.08, ros::Time()), ReachError);
  EXPECT_THROW(rb::footholdMarkers({{std::nan(""), 0, 0}}, {}, 0.1, 0.1, ros::Time()), ReachError);
}

TEST(RosMarkers, PathIsALineStrip) {
  std::vector<Eigen::Vector3d> path;
  for (int i = 0; i < 5; ++i) path.emplace_back(0.1 * i, 0.0, 0.9);
  const Marker m = rb::pathMarker(path, rb::kNsComPath, 4, 0.01, {1, 0, 0, 1}, ros::Time(1.0));
  EXPECT_EQ(m.header.frame_id, "world");
  EXPECT_EQ(m.ns, "com_path");
  EXPECT_EQ(m.id, 4);
  EXPECT_EQ(m.type, Marker::LINE_STRIP);
  EXPECT_EQ(m.scale.x, 0.01);
  ASSERT_EQ(m.points.size(), 5u);
  EXPECT_DOUBLE_EQ(m.points[4].x, 0.4);
  EXPECT_THROW(rb::pathMarker(path, "p", 0, -1.0, {1, 0, 0, 1}, ros::Time()), ReachError);
  path[2].y() = INFINITY;
  EXPECT_THROW(rb::pathMarker(path, "p", 0, 0.01, {1, 0, 0, 1}, ros::Time()), ReachError);
}

namespace {
reach_trajopt::ReachabilityResult makeResult(int slices) {
  reach_trajopt::ReachabilityResult r;
  r.header.frame_id = "world";
  r.header.stamp = ros::Time(5.0);
  r.verdict = "reachable";
  for (int i = 0; i < slices; ++i) {
    reach_trajopt::ReachabilitySlice s;
    s.header.frame_id = "world";
    s.header.stamp = ros::Time(5.0 + 0.001 * i);
    s.time = 0.001 * i;
    geometry_msgs::Point p;
    for (int k = 0; k < 4; ++k) {
      p.x = std::cos(k * M_PI / 2);
      p.y = std::sin(k * M_PI / 2);
      s.forward_outputs.push_back(p);
      s.forward_boundary.push_back(p);
      s.backward_boundary.push_back(p);
    }
    r.slices.push_back(s);
  }
  r.witness_forward.x = 1.0;
  r.witness_backward.x = 1.0;
  return r;
}
}  // namespace

TEST(RosMarkers, ReachableSetsPerSliceWithClosedBoundaries) {
  const auto a = rb::reachabilityMarkers(makeResult(3), 20);
  int forward = 0, fb = 0, bb = 0, witness = 0, backward = 0;
  for (const Marker& m : a.markers) {
    EXPECT_EQ(m.header.frame_id, "world");
    if (m.ns == rb::kNsForwardSet) {
      ++forward;
      EXPECT_EQ(m.type, Marker::POINTS);
      EXPECT_EQ(m.points.size(), 4u);
      EXPECT_EQ(m.header.stamp, ros::Time(5.0 + 0.001 * m.id));
    } else if (m.ns == rb::kNsForwardBoundary || m.ns == rb::kNsBackwardBoundary) {
      (m.ns == rb::kNsForwardBoundary ? fb : bb)++;
      EXPECT_EQ(m.type, Marker::LINE_STRIP);
      ASSERT_EQ(m.points.size(), 5u);  // closed: first point repeated
      EXPECT_EQ(m.points.front().x, m.points.back().x);
      EXPECT_EQ(m.points.front().y, m.points.back().y);
    } else if (m.ns == rb::kNsWitness) {
      ++witness;
      EXPECT_EQ(m.points.size(), 2u);
    } else if (m.ns == rb::kNsBackwardSet) {
      ++backward;
    }
  }
  EXPECT_EQ(forward, 3);
  EXPECT_EQ(backward, 0);  // no backward samples were sent
  EXPECT_EQ(fb, 3);
  EXPECT_EQ(bb, 3);
  EXPECT_EQ(witness, 1);
}

TEST(RosMarkers, ReachableSetsAreThinnedToMaxSlicesIncludingTheEnds) {
  const auto a = rb::reachabilityMarkers(makeResult(101), 5);
  std::vector<int> ids;
  for (const Marker& m : a.markers)
    if (m.ns == rb::kNsForwardSet) ids.push_back(m.id);
  EXPECT_EQ(ids, (std::vector<int>{0, 25, 50, 75, 100}));
  reach_trajopt::ReachabilityResult err = makeResult(0);
  err.verdict = "error";
  err.header.frame_id.clear();
  EXPECT_TRUE(rb::reachabilityMarkers(err).markers.empty());
}

TEST(RosMarkers, CheckedFootholdColouredByVerdictAndNoWitnessWithoutSets) {
  reach_trajopt::ReachabilityResult r = makeResult(2);
  r.foothold.x = 0.3;
  r.foothold.y = -0.2;
  auto find = [](const visualization_msgs::MarkerArray& a, const std::string& ns) {
    const Marker* found = nullptr;
    for (const Marker& m : a.markers)
      if (m.ns == ns) found = &m;
    return found ? *found : Marker();
  };
  const Marker reachable = find(rb::reachabilityMarkers(r), rb::kNsCheckedFoothold);
  EXPECT_EQ(reachable.ns, rb::kNsCheckedFoothold);
  EXPECT_EQ(reachable.type, Marker::SPHERE);
  EXPECT_EQ(reachable.header.frame_id, "world");
  EXPECT_EQ(reachable.header.stamp, ros::Time(5.0));
  EXPECT_EQ(reachable.pose.position.x, 0.3);
  EXPECT_EQ(reachable.pose.position.y, -0.2);
  EXPECT_GT(reachable.color.g, reachable.color.r);
  // A kinematically infeasible foothold: "unreachable", no sets, witness_distance -1.
  reach_trajopt::ReachabilityResult infeasible = makeResult(0);
  infeasible.verdict = "unreachable";
  infeasible.witness_distance = -1.0;
  infeasible.foothold = r.foothold;
  const auto a = rb::reachabilityMarkers(infeasible);
  ASSERT_EQ(a.markers.size(), 1u);
  EXPECT_EQ(a.markers[0].ns, rb::kNsCheckedFoothold);
  EXPECT_GT(a.markers[0].color.r, a.markers[0].color.g);
}

TEST(RosMarkers, DeleteAll) {
  const Marker m = rb::deleteAllMarker(ros::Time(1.0));
  EXPECT_EQ(m.action, Marker::DELETEALL);
  EXPECT_EQ(m.header.frame_id, "world");
}

TEST(RosMarkers, TransitionSwingPathFollowsForwardKinematics) {
  const auto model =
      RobotModel::fromUrdfFile(std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf");
  const FrameId sole = model->frameId("r_sole");
  TransitionResult traj;
  traj.status = OcpStatus::kRelaxed;
  traj.q = Eigen::MatrixXd::Zero(model->nq(), 5);
  for (int k = 0; k < 5; ++k) {
    traj.q(2, k) = 1.0;
    traj.q(model->jointIndex("r_hip_pitch"), k) = -0.1 * k;  // the leg swings forward
    traj.q(model->jointIndex("r_knee"), k) = 0.2 * k;
  }
  const ros::Time stamp(2.5);
  const auto a = rb::transitionMarkers(traj, *model, sole, 7, stamp);
  ASSERT_EQ(a.markers.size(), 2u);
  const Marker& path = a.markers[0];
  EXPECT_EQ(path.ns, rb::kNsTransitionSwingPath);
  EXPECT_EQ(path.type, Marker::LINE_STRIP);
  EXPECT_EQ(path.id, 7);
  EXPECT_EQ(path.header.frame_id, "world");
  EXPECT_EQ(path.header.stamp, stamp);
  ASSERT_EQ(path.points.size(), 5u);
  Workspace ws(*model);
  for (int k = 0; k < 5; ++k) {  // FK of each sample, independently of the builder
    model->update(ws, traj.q.col(k), Eigen::VectorXd::Zero(model->nq()));
    const Eigen::Vector3d p = model->framePose(ws, sole).translation();
    EXPECT_NEAR(path.points[k].x, p.x(), 1e-12);
    EXPECT_NEAR(path.points[k].y, p.y(), 1e-12);
    EXPECT_NEAR(path.points[k].z, p.z(), 1e-12);
  }
  const Marker& landing = a.markers[1];
  EXPECT_EQ(landing.ns, rb::kNsTransitionLanding);
  EXPECT_EQ(landing.type, Marker::SPHERE);
  EXPECT_DOUBLE_EQ(landing.pose.position.z, path.points.back().z);
  EXPECT_GT(landing.color.r, landing.color.b);  // relaxed: orange
  EXPECT_TRUE(rb::transitionMarkers(TransitionResult(), *model, sole, 0, stamp).markers.empty());
  traj.q.conservativeResize(3, Eigen::NoChange);
  EXPECT_THROW(rb::transitionMarkers(traj, *model, sole, 0, stamp), ReachError);
}
