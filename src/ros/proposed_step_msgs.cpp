#include "reach_trajopt/ros/proposed_step_msgs.h"

#include "reach_trajopt/ros/markers.h"
#include "reach_trajopt/ros/service_requests.h"

namespace reach_trajopt {
namespace ros_bridge {

Eigen::Vector3d checkedFoothold(const StepRecord& record, double ground_z) {
  return Eigen::Vector3d(record.planned_tvr.x(), record.planned_tvr.y(), ground_z);
}

ProposedStepMsgs toProposedStepMsgs(const RobotModel& model, const ContactConfig& contact,
                                    const StepRecord& record, const FootstepTransition& step,
                                    const Eigen::Vector3d& foothold, double delta,
                                    const ros::Time& t0, bool samples, int max_points) {
  ProposedStepMsgs m;
  const std::string& swing_frame = swingFrame(contact, opposite(record.swing));
  const FootstepResult& check = step.check;
  if (!check.kinematically_feasible)
    m.reachability = infeasibleFootholdMsg(check.kinematics.reason, swing_frame, foothold, t0);
  else {
    m.reachability =
        toReachabilityResultMsg(check.reach, foothold, swing_frame, delta, t0, samples, max_points);
    applyPlannerVerdict(step, m.reachability);
  }
  m.markers = reachabilityMarkers(m.reachability);
  m.trajectory = toTransitionTrajectoryMsg(step.trajectory, model,
                                           {contact.left_sole_frame, contact.right_sole_frame}, t0);
  return m;
}

}  // namespace ros_bridge
}  // namespace reach_trajopt
