#pragma once
/// \file conversions.h
/// Pure conversions between the core library's types and ROS messages (no node, no master):
/// Eigen geometry <-> geometry_msgs, the model's forward kinematics -> TF transforms of every
/// link, the measured state -> sensor_msgs/JointState, and the walking loop's records -> the
/// package's messages. Conventions (docs/method.md Sec. 1, REP 103): SI units, the world frame
/// "world" with z up, wrenches [f; tau] in world orientation at the sole centre.

#include <geometry_msgs/Point.h>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Transform.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Vector3.h>
#include <geometry_msgs/Wrench.h>
#include <geometry_msgs/WrenchStamped.h>
#include <ros/time.h>
#include <sensor_msgs/JointState.h>

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "reach_trajopt/CenterOfMassState.h"
#include "reach_trajopt/ContactPlan.h"
#include "reach_trajopt/ContactState.h"
#include "reach_trajopt/StepReport.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/planner/tvr_planner.h"
#include "reach_trajopt/walk/walking_experiment.h"

namespace reach_trajopt {
namespace ros_bridge {

/// The world frame of every message of this package (REP 105 "world", z up).
inline constexpr char kWorldFrame[] = "world";
/// Throws RequestError "<field>unknown frame '<frame_id>': positions must be in 'world'" unless
/// `frame_id` (a request's header.frame_id) is empty or kWorldFrame.
void requireWorldFrame(const std::string& frame_id, const std::string& field = "");

// ---- Responses of remote services -----------------------------------------------------------
/// Throws ReachError "<service> response: <field>: expected <size> entries, got <n>" unless `v`
/// has `size` entries: a malformed answer of a remote service (not a bad request).
template <typename T>
void requireResponseEntries(const std::string& service, const std::vector<T>& v, size_t size,
                            const char* field) {
  if (v.size() != size)
    throw ReachError(service + " response: " + field + ": expected " + std::to_string(size) +
                     " entries, got " + std::to_string(v.size()));
}
/// Response field `field` of `size` numbers as a vector (requireResponseEntries first).
Eigen::VectorXd responseVector(const std::string& service, const std::vector<double>& v,
                               size_t size, const char* field);

// ---- Geometry -------------------------------------------------------------------------------
geometry_msgs::Point toPointMsg(const Eigen::Vector3d& p);
/// A horizontal point (x, y) at height z [m].
geometry_msgs::Point toPointMsg(const Eigen::Vector2d& xy, double z = 0.0);
geometry_msgs::Vector3 toVector3Msg(const Eigen::Vector3d& v);
geometry_msgs::Vector3 toVector3Msg(const Eigen::Vector2d& xy, double z = 0.0);
geometry_msgs::Pose toPoseMsg(const Eigen::Isometry3d& T);
geometry_msgs::Transform toTransformMsg(const Eigen::Isometry3d& T);
/// Wrench [f; tau] (N, Nm) -> geometry_msgs/Wrench (force, torque).
geometry_msgs::Wrench toWrenchMsg(const Vector6d& w);

Eigen::Vector3d fromPointMsg(const geometry_msgs::Point& p);
Eigen::Vector3d fromVector3Msg(const geometry_msgs::Vector3& v);
/// Throws ReachError when the quaternion is not finite or has a norm far from 1.
Eigen::Isometry3d fromPoseMsg(const geometry_msgs::Pose& pose);
/// Throws ReachError when the quaternion is not finite or has a norm far from 1.
Eigen::Isometry3d fromTransformMsg(const geometry_msgs::Transform& t);
Vector6d fromWrenchMsg(const geometry_msgs::Wrench& w);

/// @brief The TF tree of a robot from its forward kinematics: one transform per link of
/// model.linkNames(), parent link -> link, computed as framePose(parent)^-1 framePose(link);
/// the root link hangs from the world frame with its world pose (the floating base).
/// Frame ids and buffers are set up once; compute() allocates nothing.
class LinkTransforms {
 public:
  /// \param world_frame  parent frame of the root link (default "world")
  explicit LinkTransforms(const RobotModel& model, const std::string& world_frame = kWorldFrame);

  /// Transforms at the state last given to model.update(ws, ...), stamped `stamp`.
  const std::vector<geometry_msgs::TransformStamped>& compute(const Workspace& ws,
                                                              const ros::Time& stamp);
  const std::vector<geometry_msgs::TransformStamped>& transforms() const { return msgs_; }

 private:
  const RobotModel& model_;
  std::vector<FrameId> child_;
  std::vector<FrameId> parent_;  // -1: the world frame
  std::vector<geometry_msgs::TransformStamped> msgs_;
};

/// Fills `msg` with the actuated joints of the model (URDF joint names, the six virtual
/// floating-base coordinates left out): position q [rad or m], velocity qd, effort u [Nm or N].
/// Reuses msg's storage (no allocation after the first call). `u` may be empty (no effort).
/// \throws ReachError on wrong sizes.
void fillJointState(const RobotModel& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                    const Eigen::VectorXd& u, const ros::Time& stamp, sensor_msgs::JointState& msg);

/// A sole's measured ground wrench expressed in the sole frame (frame_id = the sole frame, for
/// viewers): f_sole = R^T f, tau_sole = R^T tau, moment about the sole centre [N, Nm].
geometry_msgs::WrenchStamped toSoleWrenchMsg(const SoleContact& sole, const ros::Time& stamp);

/// The CoM state of one walking tick (frame "world").
reach_trajopt::CenterOfMassState toCenterOfMassStateMsg(const WalkTick& tick,
                                                        const ros::Time& stamp);

/// Sole contacts of one walking tick: measured wrenches from the simulator, commanded ones from
/// the controller (left first, right second, in the order of tick.soles).
reach_trajopt::ContactState toContactStateMsg(const WalkTick& tick, const ros::Time& stamp);

/// One footstep record. `fell`: the run ended with a fall at this step. `ground_z` is the height
/// given to the horizontal planned points [m].
reach_trajopt::StepReport toStepReportMsg(const StepRecord& record, const WalkingPolicy& policy,
                                          bool fell, double ground_z = 0.0);

/// A contact plan of one step: SS(stance) for `single_support` seconds then DS for
/// `double_support` seconds, the swing sole landing at step.alpha (at height ground_z).
/// \throws ReachError on non-positive durations.
reach_trajopt::ContactPlan toContactPlanMsg(const TvrInput& input, const TvrStep& step,
                                            double single_support, double double_support,
                                            double ground_z, const ros::Time& stamp);

}  // namespace ros_bridge
}  // namespace reach_trajopt
