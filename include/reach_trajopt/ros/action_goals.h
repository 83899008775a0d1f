#pragma once
/// \file action_goals.h
/// What the two long-call action servers (reachability_node's check_reachability_action,
/// transition_ocp_node's plan_transition_action) share: the check's progress as feedback and
/// the request a goal asks (the service's), the end of a goal (preempted when cancelled, else
/// succeeded or aborted by the answer).

#include <cstdint>
#include <string>

#include "reach_trajopt/CheckReachability.h"
#include "reach_trajopt/CheckReachabilityGoal.h"
#include "reach_trajopt/PlanTransition.h"
#include "reach_trajopt/PlanTransitionGoal.h"
#include "reach_trajopt/reach/reach_progress.h"

namespace reach_trajopt {
namespace ros_bridge {

/// The options only a check_reachability_action goal has, copied into its service request.
inline void copyGoalOptions(const reach_trajopt::CheckReachabilityGoal& goal,
                            reach_trajopt::CheckReachability::Request& req) {
  req.forward_samples = goal.forward_samples;
  req.backward_samples = goal.backward_samples;
  req.seed = goal.seed;
  req.return_samples = goal.return_samples;
}

/// The options only a plan_transition_action goal has, copied into its service request.
inline void copyGoalOptions(const reach_trajopt::PlanTransitionGoal& goal,
                            reach_trajopt::PlanTransition::Request& req) {
  req.check_reachability = goal.check_reachability;
  req.allow_relaxation = goal.allow_relaxation;
}

/// The service request an action goal asks (every field): those both actions share with their
/// service (header, contact_mode, q, qd, foothold, swing_duration), then copyGoalOptions.
template <class Request, class Goal>
Request serviceRequestOf(const Goal& goal) {
  Request req;
  req.header = goal.header;
  req.contact_mode = goal.contact_mode;
  req.q = goal.q;
  req.qd = goal.qd;
  req.foothold = goal.foothold;
  req.swing_duration = goal.swing_duration;
  copyGoalOptions(goal, req);
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

/// @brief Answers the current goal of `server` as its service would: `answer(response)` fills a
/// service Response (reading `cancelled`, which the goal's progress callback sets); the
/// action's Result takes its success and message, and `copyRest(response, result)` copies
/// the rest; then finishGoal.
template <class Response, class Result, class Server, class Answer, class CopyRest>
void finishGoalWithAnswer(Server& server, const bool& cancelled, Answer&& answer,
                          CopyRest&& copyRest) {
  Response res;
  answer(res);
  Result result;
  result.success = res.success;
  result.message = res.message;
  copyRest(res, result);
  finishGoal(server, result, cancelled, res.success, res.message);
}

}  // namespace ros_bridge
}  // namespace reach_trajopt
