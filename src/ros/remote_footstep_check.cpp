/// \file remote_footstep_check.cpp
/// The footstep check through check_footstep, with the in-process fallback (see the header).

#include "reach_trajopt/ros/remote_footstep_check.h"

#include <utility>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/ros/footstep_check_msgs.h"
#include "reach_trajopt/ros/proposed_step_msgs.h"
#include "reach_trajopt/ros/service_requests.h"
#include "reach_trajopt/step/footstep_transition_planner.h"

namespace reach_trajopt {
namespace ros_bridge {

RemoteFootstepCheck::RemoteFootstepCheck(const ros::NodeHandle& nh, const std::string& service,
                                         double timeout,
                                         std::shared_ptr<const FootstepTransitionPlanner> local,
                                         const ContactConfig& contact, bool samples)
    : call_(nh, service, 0, timeout, "transition_ocp_node"),
      local_(std::move(local)),
      contact_(contact),
      samples_(samples),
      nq_(local_->analyzer().model().nq()) {}

void RemoteFootstepCheck::beginStep(const ros::Time& t0) {
  stamp_ = t0;
  checked_ = reach_trajopt::ReachabilityResult();
}

FootstepCheckResult RemoteFootstepCheck::check(const ContactTransition& request,
                                               const ReachConfig& config, const CheckPass& pass,
                                               bool reachability) {
  const auto answer =
      call_.call(toCheckFootstepRequestMsg(request, config, pass, reachability, samples_, stamp_),
                 "the check");
  if (answer) {
    // A rejected request is what the in-process check throws for it.
    if (!answer->success) throw RequestError(answer->message);
    try {
      FootstepCheckResult result = fromCheckFootstepResponseMsg(*answer, nq_);
      // The hull pass's forward set alone has no verdict: the step's check is the one before.
      if (!pass.forwardOnly()) checked_ = answer->reachability;
      ++remote_checks_;
      return result;
    } catch (const ReachError& e) {
      ROS_WARN("transition_ocp_node: malformed answer of '%s' (%s); checked in process",
               call_.service().c_str(), e.what());
    }
  }
  return checkHere(request, config, pass, reachability);
}

FootstepCheckResult RemoteFootstepCheck::checkHere(const ContactTransition& request,
                                                   const ReachConfig& config, const CheckPass& pass,
                                                   bool reachability) {
  FootstepCheckResult result =
      checkFootstep(local_->footstepReachability(), request, config, pass, reachability);
  if (pass.forwardOnly()) return result;  // no verdict: the step's check is the one before
  checked_ = checkedFootstepMsg(result, swingFrame(contact_, request.stance),
                                request.target.position, config.delta, stamp_, samples_);
  return result;
}

}  // namespace ros_bridge
}  // namespace reach_trajopt
