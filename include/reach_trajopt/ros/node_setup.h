#pragma once
/// \file node_setup.h
/// What the package's nodes share around their work (no algorithm here): the robot from the
/// `robot_description` parameter (URDF text, or a private temporary file for loaders that need a
/// path), the ~config YAML path, the setup both foothold services build (check_reachability,
/// plan_transition), a request handler that answers a bad request with its reason and keeps
/// serving (errors with context, caught at the node boundary), and the main() of a service node.
/// Parameters are private (`~name`); `robot_description` is a global, remappable name.

#include <ros/console.h>
#include <ros/init.h>
#include <ros/node_handle.h>

#include <Eigen/Core>
#include <memory>
#include <string>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/planner/kinematic_feasibility.h"
#include "reach_trajopt/reach/reach_config.h"
#include "reach_trajopt/reach/reachability_analyzer.h"
#include "reach_trajopt/ros/service_requests.h"
#include "reach_trajopt/step/footstep_transition_planner.h"

namespace reach_trajopt {
namespace ros_bridge {

/// The URDF text of the `robot_description` parameter (resolved in `nh`'s namespace).
/// \throws ReachError when it is not set or empty.
std::string robotDescription(const ros::NodeHandle& nh);

/// ~config: path of the YAML configuration; default config/biped.yaml of the reach_trajopt
/// package.
std::string configPath(const ros::NodeHandle& pnh);

/// A URDF text written to a private temporary file (/tmp/reach_trajopt_urdf_XXXXXX, for loaders
/// that read a file, e.g. the Bullet world); the file is removed on destruction.
class TempUrdf {
 public:
  /// \throws ReachError when the file cannot be created or written.
  explicit TempUrdf(const std::string& xml);
  ~TempUrdf();
  TempUrdf(const TempUrdf&) = delete;
  TempUrdf& operator=(const TempUrdf&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// @brief What check_reachability and plan_transition both build from `robot_description` and
/// ~config (sections contact, kinematic_feasibility, reach, optionally ocp, nearest_foothold and
/// walk for the standing posture of a request without a state), with ~ground_tolerance [m] for
/// the requests.
struct FootholdServiceSetup {
  YamlSection file;  ///< the whole ~config file, for the node's own sections (e.g. ocp)
  std::string config_path;
  std::shared_ptr<const RobotModel> model;
  ContactConfig contact;
  ReachConfig reach;
  FootholdRequestLimits limits;
  /// The core's step pipeline (kinematic check, reachability, OCP) built from the same
  /// sections; its kinematics() and analyzer() serve check_reachability. Not const: a node
  /// may plug where its candidate footholds are checked (setCandidateCheck) before it serves.
  std::shared_ptr<FootstepTransitionPlanner> planner;
  Eigen::VectorXd standing_q;  ///< x_0 of a request with empty q, qd (size n_q)

  /// Reads the parameters and builds everything.
  /// \throws ReachError (a missing robot_description, a bad URDF or configuration).
  static FootholdServiceSetup load(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);
};

/// @brief Handles one service request: runs `body()`; an exception thrown by it is a rejected
/// request, answered by `reject(reason)` (which fills the response: success = false, the
/// reason, an "error" result) and logged as a warning naming `service`. The node keeps serving.
/// \return true, the "answered" of a roscpp service callback.
template <typename Body, typename Reject>
bool answerOrReject(const char* service, Body&& body, Reject&& reject) {
  try {
    body();
  } catch (const std::exception& e) {
    reject(std::string(e.what()));
    ROS_WARN("%s: rejected: %s", service, e.what());
  }
  return true;
}

/// The answer to a rejected request: success = false, `reason` as the message, every other
/// field its message default (a reject of answerOrReject starts from it).
template <typename Response>
Response rejectedResponse(const std::string& reason) {
  Response res;
  res.success = false;
  res.message = reason;
  return res;
}

/// @brief The main() of a service node: ros::init as `name`, `Node node(nh, pnh)` with the
/// public and private node handles, ros::spin(). An error while building the node is logged
/// (ROS_FATAL) and gives exit status 2.
template <typename Node>
int runServiceNode(int argc, char** argv, const char* name) {
  ros::init(argc, argv, name);
  ros::NodeHandle nh, pnh("~");
  try {
    Node node(nh, pnh);
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("%s: %s", name, e.what());
    return 2;
  }
  return 0;
}

}  // namespace ros_bridge
}  // namespace reach_trajopt
