#pragma once
/// \file tvr_proposal_msgs.h
/// Pure conversions (no node, no master) of the walking loop's TVR proposal through
/// tvr_planner_node's propose_footstep service (reach_trajopt/ProposeFootstep,
/// planner/tvr_proposal.h): the request to the message and back (validated, each rejection
/// naming its field), the proposal to the response and back. Every number travels as float64,
/// so the loop gets bit for bit what its own TvrPlanner proposes. Frame "world", SI units.

#include <ros/time.h>

#include "reach_trajopt/ProposeFootstep.h"
#include "reach_trajopt/planner/tvr_proposal.h"

namespace reach_trajopt {
namespace ros_bridge {

/// The request message of `request`, stamped t0.
reach_trajopt::ProposeFootstep::Request toProposeFootstepRequestMsg(
    const TvrProposalRequest& request, const ros::Time& t0);

/// The TvrProposalRequest of a request message.
/// \throws RequestError naming the field: wrong sizes, non-finite numbers, an unknown side, a
///     negative remaining time or a non-positive com_height.
TvrProposalRequest fromProposeFootstepRequestMsg(const reach_trajopt::ProposeFootstep::Request& m);

/// The response of a proposal (success = true).
reach_trajopt::ProposeFootstep::Response toProposeFootstepResponseMsg(const TvrProposal& p);

/// The proposal of a successful response to `request` (the input's stance and swing are the
/// request's). \throws ReachError naming the field of a malformed response.
TvrProposal fromProposeFootstepResponseMsg(const reach_trajopt::ProposeFootstep::Response& m,
                                           const TvrProposalRequest& request);

}  // namespace ros_bridge
}  // namespace reach_trajopt
