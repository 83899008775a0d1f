#pragma once
/// \file service_requests.h
/// Pure helpers of the check_reachability and plan_transition services (no node, no master):
/// validation of a foothold request with a reason for every rejection (non-finite numbers,
/// wrong sizes, an unknown frame, an empty contact set, a foothold in the air), and the
/// conversion of the engines' results (ReachResult, TransitionResult) to messages.
/// Frames (REP 103): every position is in "world"; units SI.

#include <geometry_msgs/Point.h>
#include <ros/time.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "reach_trajopt/ReachabilityResult.h"
#include "reach_trajopt/TransitionTrajectory.h"
#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/contact/contact_mode.h"
#include "reach_trajopt/contact/contact_transition.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/ocp/transition_request.h"
#include "reach_trajopt/ocp/transition_result.h"
#include "reach_trajopt/planner/kinematic_feasibility.h"
#include "reach_trajopt/reach/footstep_reachability.h"
#include "reach_trajopt/reach/reachability_analyzer.h"
#include "reach_trajopt/step/footstep_transition_planner.h"

namespace reach_trajopt {
namespace ros_bridge {

/// Limits of what a request may ask.
struct FootholdRequestLimits {
  double ground_tolerance = 0.02;  ///< |foothold z - stance sole z| allowed [m] (flat ground)
  /// Longest swing_duration a request may ask [s] (the OCP's kMaxTransitionHorizon): longer
  /// ones are rejected up front, before any IK, check or solve runs.
  double max_duration = kMaxTransitionHorizon;
};

/// Validates a request of either service: the contact transition it asks for, the robot in
/// single support on `stance` at x_0 = (q0, qd0), the held sole where it is at x_0 (flat), the
/// swing sole to land flat at `target` (the stance sole's heading) after `horizon` seconds
/// (qf, qdf empty: the kinematic check builds x_f).
/// \param frame_id          header.frame_id of the request: "" or "world"
/// \param contact_mode      "SS-L" | "SS-R" (the current mode during the swing)
/// \param q, qd             x_0 (size n_q each), or both empty: `standing_q` with qd = 0
/// \param duration          [s]; 0 takes `default_duration`
/// \throws ReachError with the reason: unknown frame, unknown or empty contact set (flight),
///         double support, wrong sizes, non-finite numbers, a non-positive duration or one over
///         limits.max_duration, a foothold
///         above (or below) the ground.
ContactTransition parseFootholdRequest(const RobotModel& model, const ContactConfig& contact,
                                       const std::string& frame_id, const std::string& contact_mode,
                                       const std::vector<double>& q, const std::vector<double>& qd,
                                       const geometry_msgs::Point& foothold, double duration,
                                       double default_duration, const Eigen::VectorXd& standing_q,
                                       const FootholdRequestLimits& limits = {});

/// The frame of the sole that swings while `stance` is held (the check's output frame).
const std::string& swingFrame(const ContactConfig& contact, Side stance);

/// The reachability configuration for a swing of `duration` seconds [s, > 0]: the horizon
/// t_f - t_0 set to `duration`, the overlap window [t_2, t_1] kept at the same fractions of it.
/// Not validated (the caller may change more fields first).
/// \throws RequestError naming swing_duration when `duration` is shorter than base.dt.
ReachConfig reachConfigForDuration(const ReachConfig& base, double duration);

/// A ReachabilityResult message from a check (verdict "reachable" | "unreachable").
/// Per window slice: d_H, counts, boundaries; output samples when `samples` (at most
/// `max_points` per set and slice, evenly thinned). Stamped t_0, frame "world".
/// \param foothold  the foothold that was checked (sole centre) [m]
reach_trajopt::ReachabilityResult toReachabilityResultMsg(const ReachResult& result,
                                                          const Eigen::Vector3d& foothold,
                                                          const std::string& swing_frame,
                                                          double delta, const ros::Time& t0,
                                                          bool samples, int max_points = 500);
/// Same, the foothold taken from the request's target.
reach_trajopt::ReachabilityResult toReachabilityResultMsg(const ReachResult& result,
                                                          const ContactTransition& request,
                                                          const std::string& swing_frame,
                                                          double delta, const ros::Time& t0,
                                                          bool samples, int max_points = 500);

/// The verdict on a foothold that failed the kinematic feasibility check (Sec. III-B: no
/// reachable path toward the next mode exists, so no sets are computed): "unreachable", the
/// message "kinematically infeasible foothold: <ik_reason>", no slices, d_H = -1.
reach_trajopt::ReachabilityResult infeasibleFootholdMsg(const std::string& ik_reason,
                                                        const std::string& swing_frame,
                                                        const Eigen::Vector3d& foothold,
                                                        const ros::Time& t0);

/// A ReachabilityResult message for a rejected or failed check (verdict "error" or the given
/// verdict, e.g. "unreachable" for a kinematically infeasible foothold) with its reason.
reach_trajopt::ReachabilityResult reachabilityVerdictMsg(const std::string& verdict,
                                                         const std::string& message,
                                                         const ros::Time& t0);

/// The planner's verdict on a result built from its check (toReachabilityResultMsg): "reachable"
/// when a certificate exists (the bridge or the local solve), its kind and the reason.
void applyPlannerVerdict(const FootstepTransition& step, reach_trajopt::ReachabilityResult& m);

/// The TransitionTrajectory message of a rejected request: status "error" and the reason.
reach_trajopt::TransitionTrajectory errorTrajectoryMsg(const std::string& reason,
                                                       const ros::Time& t0);

/// A TransitionTrajectory message from an OCP result (row-major N x n matrices).
/// \param lambda_frames  names of the 12 rows of result.lambda in blocks of 6 (left, right)
reach_trajopt::TransitionTrajectory toTransitionTrajectoryMsg(
    const TransitionResult& result, const RobotModel& model,
    const std::vector<std::string>& lambda_frames, const ros::Time& t0);

/// A TransitionResult from a TransitionTrajectory message (status, knots, q, qd, qdd, u,
/// lambda, relaxation, landing, cost, iterations, solve time; its message as the reason).
/// \throws ReachError naming the field of a matrix whose size does not fit `model`.
TransitionResult fromTransitionTrajectoryMsg(const reach_trajopt::TransitionTrajectory& m,
                                             const RobotModel& model);

}  // namespace ros_bridge
}  // namespace reach_trajopt
