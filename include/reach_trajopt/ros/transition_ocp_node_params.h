#pragma once
/// \file transition_ocp_node_params.h
/// transition_ocp_node's own parameters (private, `~name`; the planner's come from ~config
/// through FootholdServiceSetup), read and checked before the node waits for any service:
/// a negative ros::Duration waits for ever, one past 32-bit seconds throws, and each absent
/// reachability worker costs a wait of ~worker_timeout at start.

#include <ros/node_handle.h>

#include <string>

namespace reach_trajopt {
struct ReachConfig;
namespace ros_bridge {

/// @brief transition_ocp_node's parameters (nodes/transition_ocp_node.cpp documents each).
struct TransitionOcpNodeParams {
  /// Reachability workers of one node: far more than the cores of a few hosts.
  static constexpr int kMaxWorkers = 64;
  /// Longest wait the node accepts for a service or an answer [s wall] (ros::Duration holds
  /// 32-bit seconds).
  static constexpr double kMaxWait = 1e6;

  double default_horizon = 0.0;  ///< [s] t_f - t_0 of a request that gives 0, in (0, 5]
  bool reachability_samples = true;
  std::string check_service;    ///< "": plan_footstep checks in this process
  double check_timeout = 60.0;  ///< [s wall], in (0, kMaxWait]
  int workers = 0;              ///< in [0, kMaxWorkers]; 0: candidates checked in this process
  std::string worker_prefix = "reachability_worker_";
  double worker_timeout = 10.0;       ///< [s wall], in (0, kMaxWait]
  double worker_retry_period = 30.0;  ///< [s wall], in [0, kMaxWait]

  /// Reads the parameters that are set (the others keep the defaults above; default_horizon's
  /// is the config's reach.horizon) and validates.
  static TransitionOcpNodeParams read(const ros::NodeHandle& pnh, const ReachConfig& reach);
  /// \throws ConfigError naming the parameter out of its range.
  void validate() const;
};

}  // namespace ros_bridge
}  // namespace reach_trajopt
