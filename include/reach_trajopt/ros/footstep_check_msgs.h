#pragma once
/// \file footstep_check_msgs.h
/// Pure conversions (no node, no master) of the planner's footstep check through
/// reachability_node's check_footstep service (reach_trajopt/CheckFootstep,
/// step/footstep_check.h): the request to the message and back (validated, each rejection naming
/// its field), the check to the response and back. The response carries what the planner and
/// the walk read of a FootstepCheckResult (the IK, qd_f, the verdict, the window's distances, the
/// witness) and the OCP's slices of the forward set instead of the sets; every number as
/// float64, so the plan is the in-process plan bit for bit. Frame "world", SI units.

#include <ros/time.h>

#include <optional>

#include "reach_trajopt/CheckFootstep.h"
#include "reach_trajopt/reach/reach_config.h"
#include "reach_trajopt/step/footstep_check.h"

namespace reach_trajopt {
namespace ros_bridge {

/// What a check_footstep request asks.
struct FootstepCheckCall {
  ContactTransition request;
  ReachConfig reach;  ///< the node's with the request's horizon and seed
  /// The pass to run (the request's budget and sets); none: the node's own pass schedule.
  std::optional<CheckPass> pass;
  bool reachability = true;  ///< false: the kinematic stage only
  bool samples = true;       ///< the published result carries the output samples
};

/// The request of a check of `request` with the reachability settings `reach` and one pass
/// `pass` of the step planner (its horizon, seed, the pass's budget and sets are sent, so the
/// pass is checked as in process; the rest must be the node's; no pass: the node's own pass
/// schedule), stamped t0.
reach_trajopt::CheckFootstep::Request toCheckFootstepRequestMsg(
    const ContactTransition& request, const ReachConfig& reach,
    const std::optional<CheckPass>& pass, bool reachability, bool samples, const ros::Time& t0);

/// The call of a request message for a model with `nq` coordinates; its reachability settings
/// are `base` with the message's reach_horizon and seed (each when given), its pass the
/// message's budget, forward_set_only and forward_until (none without a budget).
/// \throws RequestError naming the field: an unknown side or frame, wrong sizes, non-finite
///     numbers, a horizon outside [0, kMaxTransitionHorizon], a negative seed other than -1.
FootstepCheckCall fromCheckFootstepRequestMsg(const reach_trajopt::CheckFootstep::Request& m,
                                              int nq, const ReachConfig& base);

/// The response of a check (success = true) with the ReachabilityResult to publish.
reach_trajopt::CheckFootstep::Response toCheckFootstepResponseMsg(
    const FootstepCheckResult& check, const reach_trajopt::ReachabilityResult& published);

/// The check of a successful response for a model with `nq` coordinates.
/// \throws ReachError naming the field of a malformed response (sizes).
FootstepCheckResult fromCheckFootstepResponseMsg(const reach_trajopt::CheckFootstep::Response& m,
                                                 int nq);

}  // namespace ros_bridge
}  // namespace reach_trajopt
