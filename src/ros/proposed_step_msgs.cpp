/// \file proposed_step_msgs.cpp
/// The messages of one proposed step (see the header).

#include "reach_trajopt/ros/proposed_step_msgs.h"

#include <utility>

#include "reach_trajopt/ros/markers.h"
#include "reach_trajopt/ros/service_requests.h"

namespace reach_trajopt {
namespace ros_bridge {

Eigen::Vector3d checkedFoothold(const StepRecord& record, double ground_z) {
  return Eigen::Vector3d(record.planned_tvr.x(), record.planned_tvr.y(), ground_z);
}

reach_trajopt::ReachabilityResult checkedFootstepMsg(const FootstepCheckResult& check,
                                                     const std::string& swing_frame,
                                                     const Eigen::Vector3d& foothold, double delta,
                                                     const ros::Time& t0, bool samples,
                                                     int max_points) {
  if (!check.kinematically_feasible)
    return infeasibleFootholdMsg(check.kinematics.reason, swing_frame, foothold, t0);
  return toReachabilityResultMsg(check.reach, foothold, swing_frame, delta, t0, samples,
                                 max_points);
}

ProposedStepMsgs toProposedStepMsgs(const RobotModel& model, const ContactConfig& contact,
                                    const FootstepTransition& step,
                                    reach_trajopt::ReachabilityResult checked,
                                    const ros::Time& t0) {
  ProposedStepMsgs m;
  m.reachability = std::move(checked);
  if (step.check.kinematically_feasible) applyPlannerVerdict(step, m.reachability);
  m.markers = reachabilityMarkers(m.reachability);
  m.trajectory = toTransitionTrajectoryMsg(step.trajectory, model,
                                           {contact.left_sole_frame, contact.right_sole_frame}, t0);
  return m;
}

ProposedStepMsgs toProposedStepMsgs(const RobotModel& model, const ContactConfig& contact,
                                    const StepRecord& record, const FootstepTransition& step,
                                    const Eigen::Vector3d& foothold, double delta,
                                    const ros::Time& t0, bool samples, int max_points) {
  const std::string& swing_frame = swingFrame(contact, opposite(record.swing));
  return toProposedStepMsgs(
      model, contact, step,
      checkedFootstepMsg(step.check, swing_frame, foothold, delta, t0, samples, max_points), t0);
}

}  // namespace ros_bridge
}  // namespace reach_trajopt
