#pragma once
/// \file proposed_step_msgs.h
/// Pure conversions (no node, no master) of what one step of the proposed walking mode found
/// (paper Sec. III as run in Sec. IV: kinematic feasibility III-B, the reachability check
/// (13)-(21), the transition OCP (22)-(23)) to the messages reachability_node and
/// transition_ocp_node publish, so that a recorded walk carries them too. Frame "world" (REP
/// 103), SI units.

#include <ros/time.h>
#include <visualization_msgs/MarkerArray.h>

#include <Eigen/Core>
#include <string>

#include "reach_trajopt/ReachabilityResult.h"
#include "reach_trajopt/TransitionTrajectory.h"
#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/step/footstep_transition_planner.h"
#include "reach_trajopt/walk/walking_experiment.h"

namespace reach_trajopt {
namespace ros_bridge {

/// The messages of one proposed step's check.
struct ProposedStepMsgs {
  /// The check: sets, window, witness ("reachable" | "unreachable"), or for a kinematically
  /// infeasible foothold "unreachable" with the IK's reason and no sets (infeasibleFootholdMsg).
  reach_trajopt::ReachabilityResult reachability;
  visualization_msgs::MarkerArray markers;  ///< reachabilityMarkers(reachability)
  /// The OCP's trajectory, knot times from t_0 (empty with status "failed" when no terminal
  /// posture was found).
  reach_trajopt::TransitionTrajectory trajectory;
};

/// The foothold a proposed step checked, from the record the walking loop hands to its
/// on_check callback: the TVR foothold of eq. (11) (record.planned_tvr; the proposed mode plans
/// without heuristic bounds; record.planned already holds where the swing will land after the
/// check) on the ground at the stance sole's height `ground_z` [m].
Eigen::Vector3d checkedFoothold(const StepRecord& record, double ground_z);

/// The check's ReachabilityResult before the OCP's verdict, as reachability_node's
/// check_footstep answers it: for a kinematically infeasible foothold infeasibleFootholdMsg,
/// else toReachabilityResultMsg of check.reach (its verdict the check's), stamped t0.
/// \param swing_frame  the swing sole's frame (the output's)
reach_trajopt::ReachabilityResult checkedFootstepMsg(const FootstepCheckResult& check,
                                                     const std::string& swing_frame,
                                                     const Eigen::Vector3d& foothold, double delta,
                                                     const ros::Time& t0, bool samples,
                                                     int max_points = 500);

/// The messages of one proposed step from its check's message `checked` (checkedFootstepMsg,
/// e.g. built by reachability_node): the planner's verdict applied to it (a kinematically
/// feasible foothold), its markers and the OCP's trajectory, stamped t0.
ProposedStepMsgs toProposedStepMsgs(const RobotModel& model, const ContactConfig& contact,
                                    const FootstepTransition& step,
                                    reach_trajopt::ReachabilityResult checked, const ros::Time& t0);

/// @brief The messages of one proposed step, all stamped `t0` (the sim time of the check, x_0)
/// in frame "world".
/// \param record    the step as handed to on_check (swing side)
/// \param step      the planner's output (full check and OCP result)
/// \param foothold  the checked foothold [m] (checkedFoothold())
/// \param delta     threshold delta of the check (Prop. 2) [m]
/// \param samples   send the output samples of each slice (at most `max_points` per set and
///                  slice); boundaries are always sent
ProposedStepMsgs toProposedStepMsgs(const RobotModel& model, const ContactConfig& contact,
                                    const StepRecord& record, const FootstepTransition& step,
                                    const Eigen::Vector3d& foothold, double delta,
                                    const ros::Time& t0, bool samples, int max_points = 500);

}  // namespace ros_bridge
}  // namespace reach_trajopt
