#pragma once
/// \file remote_footstep_check.h
/// transition_ocp_node's footstep check (steps 2-3 of its plan_footstep planner,
/// step/footstep_check.h) through reachability_node's check_footstep service: the planner's
/// FootstepCheck, sent with the step's stamp; the answer is the check as the planner uses it
/// (footstep_check_msgs.h) and the ReachabilityResult built where it ran, which the node then
/// publishes with the planner's verdict. A call that fails or is malformed is checked in
/// process, one that times out too and every later one (the service is hung), with a warning
/// (fallback_service_call.h): the plans do not change either way.

#include <ros/ros.h>

#include <cstdint>
#include <memory>
#include <string>

#include "reach_trajopt/CheckFootstep.h"
#include "reach_trajopt/ReachabilityResult.h"
#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/ros/fallback_service_call.h"
#include "reach_trajopt/step/footstep_check.h"
#include "reach_trajopt/step/footstep_transition_planner.h"

namespace reach_trajopt {
namespace ros_bridge {

/// @brief The footstep check of one step at a time (plan_footstep is served on one thread):
/// beginStep(), the planner's check(), then checkedMessage().
class RemoteFootstepCheck {
 public:
  /// \param service  check_footstep's name (relative, remappable)
  /// \param timeout  [s wall] longest wait for an answer
  /// \param local    the in-process check (the fallback), configured as the remote one
  /// \param samples  the published result carries the output samples of every slice
  RemoteFootstepCheck(const ros::NodeHandle& nh, const std::string& service, double timeout,
                      std::shared_ptr<const FootstepTransitionPlanner> local,
                      const ContactConfig& contact, bool samples);

  /// The next check is the step stamped t0 (the sim time of the check, x_0).
  void beginStep(const ros::Time& t0);
  /// The planner's FootstepCheck (setFootstepCheck).
  /// \throws RequestError with the node's reason when it rejects the request
  FootstepCheckResult check(const ContactTransition& request, const ReachConfig& config,
                            const CheckPass& pass, bool reachability);
  /// The ReachabilityResult of the step's check, before the OCP's verdict
  /// (checkedFootstepMsg), built where it ran.
  const reach_trajopt::ReachabilityResult& checkedMessage() const { return checked_; }
  /// Checks answered by the service so far.
  uint64_t remoteChecks() const { return remote_checks_; }

 private:
  FootstepCheckResult checkHere(const ContactTransition& request, const ReachConfig& config,
                                const CheckPass& pass, bool reachability);
  FallbackServiceCall<reach_trajopt::CheckFootstep> call_;
  std::shared_ptr<const FootstepTransitionPlanner> local_;
  ContactConfig contact_;
  bool samples_;
  int nq_;
  ros::Time stamp_;
  reach_trajopt::ReachabilityResult checked_;
  uint64_t remote_checks_ = 0;
};

}  // namespace ros_bridge
}  // namespace reach_trajopt
