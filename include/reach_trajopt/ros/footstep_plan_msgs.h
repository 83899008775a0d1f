#pragma once
/// \file footstep_plan_msgs.h
/// Pure conversions (no node, no master) of the walking loop's per-step planning through
/// transition_ocp_node's plan_footstep service (reach_trajopt/PlanFootstep): a
/// FootstepPlanRequest to the request message and back (validated, each rejection naming its
/// field), and a FootstepTransition to the response and back. Every number travels as float64,
/// so the loop sees bit for bit what the in-process FootstepTransitionPlanner decides. Frame
/// "world" (REP 103), SI units.

#include <ros/time.h>

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "reach_trajopt/PlanFootstep.h"
#include "reach_trajopt/SampleBudget.h"
#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/ocp/transition_result.h"
#include "reach_trajopt/reach/reach_config.h"
#include "reach_trajopt/step/footstep_transition_planner.h"

namespace reach_trajopt {
namespace ros_bridge {

/// The vector of a message field that must hold `size` finite numbers.
/// \throws RequestError naming `field` (its size, a non-finite number).
Eigen::VectorXd finiteVector(const std::vector<double>& v, size_t size, const std::string& field);
/// The float64[] of a message field.
std::vector<double> asVector(const Eigen::Ref<const Eigen::VectorXd>& v);
/// A witness's PathViolation as the services' 9 witness_violation numbers
/// (reach/witness_path.h order: dynamics, cone, torque, position and velocity limits, contact,
/// contact velocity, integration, ground) and back.
std::vector<double> pathViolationVector(const PathViolation& v);
/// \throws ReachError "<service> response: witness_violation: ..." unless `v` has 9 numbers.
PathViolation pathViolationFromVector(const std::vector<double>& v, const std::string& service);

/// A sampling budget as its message (msg/SamplingBudget.msg) and back; the message's budget is
/// not validated here (the caller validates it with the rest of its request).
reach_trajopt::SampleBudget toSampleBudgetMsg(const SamplingBudget& budget);
SamplingBudget fromSampleBudgetMsg(const reach_trajopt::SampleBudget& m);

/// The names of the messages: "by_verdict" | "strict" | "auto".
const char* ocpPolicyName(OcpPolicy p);
/// "nearest_feasible" | "relax_toward_target" | "reject" | "no_fallback".
const char* infeasibleFootholdPolicyName(InfeasibleFootholdPolicy p);

/// The request message of `request` as planned with the reachability settings `reach` (its
/// horizon, seed and three sample budgets are sent; request.reach overrides them when set; the
/// other keys must be the node's), stamped t0 in "world".
reach_trajopt::PlanFootstep::Request toPlanFootstepRequestMsg(const FootstepPlanRequest& request,
                                                              const ReachConfig& reach,
                                                              const ros::Time& t0);

/// The FootstepPlanRequest of a request message for a model with `nq` coordinates; its
/// reachability settings are `base` with the message's reach_horizon, seed and budgets (each
/// when given).
/// \throws RequestError naming the field: an unknown frame or name, wrong sizes, non-finite
///     numbers, a stance_pose whose rotation is not one, a horizon outside (0,
///     kMaxTransitionHorizon], a negative seed other than -1.
FootstepPlanRequest fromPlanFootstepRequestMsg(const reach_trajopt::PlanFootstep::Request& m,
                                               int nq, const ReachConfig& base);

/// The response of a planned step (success = true), its trajectory stamped t0.
reach_trajopt::PlanFootstep::Response toPlanFootstepResponseMsg(const FootstepTransition& step,
                                                                const RobotModel& model,
                                                                const ContactConfig& contact,
                                                                const ros::Time& t0);

/// What the walking loop uses of a FootstepTransition, from a successful response to `request`
/// (the verdict fields, the witness's violations and gaps, the foothold and the trajectory;
/// not the reachable sets, which the node publishes on reachability_result).
/// \throws ReachError naming the field of a malformed response (sizes for `model`).
FootstepTransition fromPlanFootstepResponseMsg(const reach_trajopt::PlanFootstep::Response& m,
                                               const FootstepPlanRequest& request,
                                               const RobotModel& model);

}  // namespace ros_bridge
}  // namespace reach_trajopt
