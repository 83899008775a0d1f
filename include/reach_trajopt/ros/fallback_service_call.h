#pragma once
/// \file fallback_service_call.h
/// The calls of one service of the walk's graph by a caller that can do the work itself (sim_node
/// planning a step or proposing a contact, transition_ocp_node checking a footstep): a call
/// that fails (the node died or went away) is repeated `retries` times, 0.1 s apart; a call not
/// answered within `timeout` wall seconds means the node is hung (stopped, not dead; a
/// ros::ServiceClient::call would block for ever, async_service_call.h), and the service is not
/// asked again. Either way the caller gets no answer and does the work in process; each case
/// is logged as a warning.

#include <ros/ros.h>

#include <optional>
#include <string>
#include <utility>

#include "reach_trajopt/ros/async_service_call.h"

namespace reach_trajopt {
namespace ros_bridge {

/// @brief One service's calls with retries, a deadline and the hung state.
template <class Service>
class FallbackServiceCall {
 public:
  /// \param service  relative or absolute name (resolved in `nh`)
  /// \param caller   names the caller in the warnings (e.g. "sim_node")
  FallbackServiceCall(const ros::NodeHandle& nh, const std::string& service, int retries,
                      double timeout, std::string caller)
      : nh_(nh),
        service_(nh.resolveName(service)),
        retries_(retries),
        timeout_(timeout),
        caller_(std::move(caller)) {}

  /// The response of the first call that returned (success true or not: the caller reads
  /// it), or none: every call failed, or one timed out (hung() from then on). `what` names the
  /// work in the warnings (e.g. "step 3").
  std::optional<typename Service::Response> call(const typename Service::Request& request,
                                                 const std::string& what) {
    for (int attempt = 0; attempt <= retries_ && !hung_; ++attempt) {
      if (attempt > 0) {
        ROS_WARN("%s: the call of '%s' failed (attempt %d of %d)", caller_.c_str(),
                 service_.c_str(), attempt, retries_ + 1);
        ros::WallDuration(0.1).sleep();
      }
      const auto pending = callAsync<Service>(nh_, service_, request);
      if (!pending->waitUntil(ros::WallTime::now() + ros::WallDuration(timeout_))) {
        hung_ = true;
        ROS_WARN(
            "%s: '%s' did not answer within %.1f s: hung; %s and everything later done in "
            "process",
            caller_.c_str(), service_.c_str(), timeout_, what.c_str());
        return std::nullopt;
      }
      std::lock_guard<std::mutex> lock(pending->mutex);
      if (pending->ok) return std::move(pending->response);
    }
    if (!hung_)
      ROS_WARN("%s: the call of '%s' failed %d times; %s done in process", caller_.c_str(),
               service_.c_str(), retries_ + 1, what.c_str());
    return std::nullopt;
  }

  /// A call timed out: the service is not asked again.
  bool hung() const { return hung_; }
  const std::string& service() const { return service_; }

 private:
  ros::NodeHandle nh_;
  std::string service_;
  int retries_;
  double timeout_;
  std::string caller_;
  bool hung_ = false;
};

}  // namespace ros_bridge
}  // namespace reach_trajopt
