#pragma once
/// \file action_goals.h
/// What the two long-call action servers (reachability_node's check_reachability_action,
/// transition_ocp_node's plan_transition_action) share: the check's progress as feedback and
/// the request a goal asks (the service's), the end of a goal (preempted when cancelled, else
/// succeeded or aborted by the answer).

#include <cstdint>
#include <string>

#include "reach_trajopt/reach/reach_progress.h"

namespace reach_trajopt {
namespace ros_bridge {

/// The service request of an action goal: the fields both actions share with their service
/// (header, contact_mode, q, qd, foothold, swing_duration); the caller copies the rest.
template <class Request, class Goal>
Request footholdRequestOf(const Goal& goal) {
  Request req;
  req.header = goal.header;
  req.contact_mode = goal.contact_mode;
  req.q = goal.q;
  req.qd = goal.qd;
  req.foothold = goal.foothold;
  req.swing_duration = goal.swing_duration;
  return req;
}

/// Copies one progress report of the check (per time slice) into a feedback message with the
/// fields direction, slices_done, slices_total, samples and qps.
template <class Feedback>
void fillCheckFeedback(const ReachProgress& p, Feedback& f) {
  f.direction = p.forward ? "forward" : "backward";
  f.slices_done = static_cast<uint32_t>(p.slices_done);
  f.slices_total = static_cast<uint32_t>(p.slices_total);
  f.samples = static_cast<uint64_t>(p.samples);
  f.qps = static_cast<uint64_t>(p.qps);
}

/// Ends the current goal of `server` with `result`: preempted when `cancelled`, else succeeded
/// when `success`, else aborted; `message` is the status text.
template <class Server, class Result>
void finishGoal(Server& server, const Result& result, bool cancelled, bool success,
                const std::string& message) {
  if (cancelled)
    server.setPreempted(result, message);
  else if (success)
    server.setSucceeded(result, message);
  else
    server.setAborted(result, message);
}

}  // namespace ros_bridge
}  // namespace reach_trajopt
