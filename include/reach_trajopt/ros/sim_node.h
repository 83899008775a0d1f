#pragma once
/// \file sim_node.h
/// The node behind nodes/sim_node.cpp (its header comment lists the topics and parameters): the
/// walking experiment of the paper's Sec. IV run in simulated time and published for ROS. The
/// constructor reads the parameters, builds the experiment, advertises the topics, waits for
/// the services it is told to use and for the subscribers it is told to wait for; run() walks.

#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/MarkerArray.h>

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "reach_trajopt/PlanFootstep.h"
#include "reach_trajopt/ProposeFootstep.h"
#include "reach_trajopt/ros/conversions.h"
#include "reach_trajopt/ros/fallback_service_call.h"
#include "reach_trajopt/ros/node_setup.h"
#include "reach_trajopt/walk/walk_setup.h"

namespace reach_trajopt {
namespace ros_bridge {

/// @brief sim_node's own parameters (private, `~name`; the walk's are read into WalkSetup).
struct SimNodeParams {
  double publish_period = 0.01;  ///< [s of sim time]
  double clock_period = 0.001;   ///< [s of sim time]
  double marker_period = 0.1;    ///< [s of sim time]
  int wait_for_subscribers = 0;
  int wait_for_com_subscribers = 0;
  double wait_timeout = 20.0;     ///< [s wall], in [0, 1e6]
  double real_time_factor = 0.0;  ///< <= 0: as fast as possible (finite)
  double linger = 1.0;            ///< [s wall], in [0, 3600]
  bool exit_when_done = true;
  bool reachability_samples = true;
  bool in_process = true;
  std::string plan_service = "plan_footstep";
  std::string propose_service = "propose_footstep";
  int plan_retries = 2;
  double plan_timeout = 60.0;  ///< [s wall]

  /// Reads the parameters that are set (the others keep the defaults above) and validates.
  static SimNodeParams read(const ros::NodeHandle& pnh);
  /// \throws ConfigError naming the parameter out of its range.
  void validate() const;
};

/// The walk's configs of ~config and ~sim_config with the walk parameters (~policy, ~steps,
/// ~seed, ~forward_speed, ~push_vx, ~push_vy, ~midswing_push_vx, ~midswing_push_vy) applied,
/// validated. \throws ReachError naming the file, key or parameter.
WalkSetup readSimWalkSetup(const ros::NodeHandle& pnh);

/// @brief The walking experiment as a ROS node (nodes/sim_node.cpp).
class SimNode {
 public:
  /// \throws ReachError (a missing robot_description, a bad configuration or parameter, a
  /// service that ~in_process false needs and that did not appear).
  SimNode(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  SimNode(const SimNode&) = delete;
  SimNode& operator=(const SimNode&) = delete;

  /// Walks, publishing as it goes; then the fall report, the summary on walk_result, ~linger,
  /// and with ~exit_when_done false waits for shutdown. Returns at a ROS shutdown during the
  /// walk too (with a warning).
  void run();

 private:
  struct Shutdown {};  ///< thrown from the tick callback to leave the walk on ROS shutdown

  void advertise();
  void connectServices();
  void waitForSubscribers();
  void onTick(const WalkTick& tick);
  void publishState(const WalkTick& tick, const ros::Time& stamp);
  void onStep(const StepRecord& r);
  void onCheck(const StepRecord& r, const FootstepTransition& step);
  FootstepTransition planThroughNode(const FootstepPlanRequest& request);
  TvrProposal proposeThroughNode(const TvrProposalRequest& request);
  void publishMarkers(const ros::Time& stamp);
  void publishEnd(const WalkResult& result);
  /// The sim time of a check: the last control tick's plus one time step.
  ros::Time checkStamp() const;

  ros::NodeHandle nh_;
  const TempUrdf urdf_;  ///< robot_description, for the Bullet world
  WalkSetup setup_;
  const SimNodeParams params_;
  std::unique_ptr<WalkingExperiment> experiment_;
  const RobotModel& model_;
  const bool checks_footholds_, through_node_;
  Workspace ws_;
  LinkTransforms link_tf_;

  ros::Publisher clock_pub_, joint_pub_, com_pub_, contact_pub_, wrench_pub_[2], step_pub_,
      marker_pub_, result_pub_;
  ros::Publisher reach_pub_, reach_marker_pub_, traj_pub_, traj_marker_pub_;  // with a check
  std::vector<ros::Publisher*> pubs_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  std::unique_ptr<FallbackServiceCall<reach_trajopt::PlanFootstep>> plan_call_;
  std::unique_ptr<FallbackServiceCall<reach_trajopt::ProposeFootstep>> propose_call_;

  std::vector<Eigen::Vector3d> planned_, executed_, com_path_, swing_path_;
  visualization_msgs::MarkerArray swing_paths_;  ///< one LINE_STRIP per finished step
  sensor_msgs::JointState joint_msg_;
  double ground_z_ = 0.0;  ///< height of the last executed foothold [m]
  double next_publish_, next_clock_ = 0.0, next_marker_;
  /// The last control tick seen: the proposed mode's check runs at the start of the next one.
  double last_tick_time_ = 0.0;
  double sole_z_[2] = {0.0, 0.0};  ///< measured sole heights at that tick [m]
  bool planned_here_ = true;       ///< the last checked step was planned in this process
  ros::WallTime wall_start_;
};

}  // namespace ros_bridge
}  // namespace reach_trajopt
