/// \file transition_ocp_node_params.cpp
/// transition_ocp_node's own parameters (transition_ocp_node_params.h).

#include "reach_trajopt/ros/transition_ocp_node_params.h"

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/common/format_number.h"
#include "reach_trajopt/ocp/transition_request.h"
#include "reach_trajopt/reach/reach_config.h"

namespace reach_trajopt {
namespace ros_bridge {

TransitionOcpNodeParams TransitionOcpNodeParams::read(const ros::NodeHandle& pnh,
                                                      const ReachConfig& reach) {
  TransitionOcpNodeParams p;
  p.default_horizon = reach.horizon;
  pnh.getParam("default_horizon", p.default_horizon);
  pnh.getParam("reachability_samples", p.reachability_samples);
  pnh.getParam("check_service", p.check_service);
  pnh.getParam("check_timeout", p.check_timeout);
  pnh.getParam("workers", p.workers);
  pnh.getParam("worker_prefix", p.worker_prefix);
  pnh.getParam("worker_timeout", p.worker_timeout);
  pnh.getParam("worker_retry_period", p.worker_retry_period);
  p.validate();
  return p;
}

void TransitionOcpNodeParams::validate() const {
  if (!(default_horizon > 0.0) || default_horizon > kMaxTransitionHorizon)
    throw ConfigError("~default_horizon must be in (0, " + formatNumber(kMaxTransitionHorizon) +
                      "] s, got " + formatNumber(default_horizon));
  if (!(check_timeout > 0.0) || check_timeout > kMaxWait)
    throw ConfigError("~check_timeout must be in (0, " + formatNumber(kMaxWait) + "] s");
  if (workers < 0 || workers > kMaxWorkers)
    throw ConfigError("~workers must be in [0, " + std::to_string(kMaxWorkers) + "], got " +
                      std::to_string(workers));
  if (!(worker_timeout > 0.0) || worker_timeout > kMaxWait)
    throw ConfigError("~worker_timeout must be in (0, " + formatNumber(kMaxWait) + "] s");
  if (!(worker_retry_period >= 0.0) || worker_retry_period > kMaxWait)
    throw ConfigError("~worker_retry_period must be in [0, " + formatNumber(kMaxWait) + "] s");
}

}  // namespace ros_bridge
}  // namespace reach_trajopt
