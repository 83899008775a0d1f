#pragma once
/// \file fallback_service_call.h
/// The calls of one service of the walk's graph by a caller that can do the work itself (sim_node
/// planning a step or proposing a contact, transition_ocp_node checking a footstep): a call
/// that fails (the node died or went away) is repeated `retries` times, 0.1 s apart; a call not
/// answered within `timeout` wall seconds means the node is hung (stopped, not dead; a
/// ros::ServiceClient::call would block for ever, async_service_call.h), and the service is not
/// asked again. Either way the caller gets no answer and does the work in process; each case
/// is logged as a warning. The calls share one persistent connection (ServiceConnection),
/// reopened after a failed call.

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
      : connection_(nh, nh.resolveName(service)),
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
                 service().c_str(), attempt, retries_ + 1);
        ros::WallDuration(0.1).sleep();
      }
      const auto pending = connection_.callAsync(request);
      if (!pending->waitUntil(ros::WallTime::now() + ros::WallDuration(timeout_))) {
        hung_ = true;
        connection_.drop();
        ROS_WARN(
            "%s: '%s' did not answer within %.1f s: hung; %s and everything later done in "
            "process",
            caller_.c_str(), service().c_str(), timeout_, what.c_str());
        return std::nullopt;
      }
      std::lock_guard<std::mutex> lock(pending->mutex);
      if (pending->ok) return std::move(pending->response);
      connection_.drop();  // the node died or went away: a new connection finds its successor
    }
    if (!hung_)
      ROS_WARN("%s: the call of '%s' failed %d times; %s done in process", caller_.c_str(),
               service().c_str(), retries_ + 1, what.c_str());
    return std::nullopt;
  }

  /// A call timed out: the service is not asked again.
  bool hung() const { return hung_; }
  const std::string& service() const { return connection_.service(); }

 private:
  ServiceConnection<Service> connection_;
  int retries_;
  double timeout_;
  std::string caller_;
  bool hung_ = false;
};

}  // namespace ros_bridge
}  // namespace reach_trajopt
