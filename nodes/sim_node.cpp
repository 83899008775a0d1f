/// sim_node: the walking experiment of the paper's Sec. IV (Bullet world + whole-body controller
/// at 1 kHz + TVR stepping loop) run in simulated time, published for ROS:
///   /clock (rosgraph_msgs/Clock)     sim time, every ~clock_period of sim time
///   joint_states (sensor_msgs)       actuated joints q, qd, u
///   /tf (tf2_ros)                    every link from the model's forward kinematics, world->pelvis
///   com_state (CenterOfMassState)    CoM position, velocity, controller reference
///   contact_state (ContactState)     measured and commanded sole wrenches, sole poses
///   contact_wrench/<sole> (geometry_msgs/WrenchStamped)  measured wrench in the sole frame
///   step_report (StepReport)         one per touchdown (and one for a step ending in a fall)
///   markers (visualization_msgs/MarkerArray)  footholds planned/executed, CoM and swing paths
///   walk_result (std_msgs/String, latched)    the summary line, published when the run ends
/// With a policy that checks footholds, once per checked step (stamped with the sim time of the
/// check, x_0, in "world"; the topics of reachability_node and transition_ocp_node):
///   reachability_result (ReachabilityResult)  the check: sets per slice, d_H, witness; or
///                                              "unreachable" for a kinematically infeasible
///                                              foothold, with the IK's reason
///   reachability_markers (visualization_msgs/MarkerArray)  its sets, witness and foothold
///   transition_trajectory (TransitionTrajectory)  the OCP's trajectory (converged, relaxed or
///                                              failed) the swing then tracks
///   transition_markers (visualization_msgs/MarkerArray)  its swing sole path and landing
/// Parameters (private): ~config (YAML with sections contact, planner, walk, wbc, and for the
/// policies with a check kinematic_feasibility, reach, ocp, nearest_foothold; default
/// config/biped.yaml of the package), ~sim_config (YAML with a sim section, optional), ~policy (a
/// walking policy: baseline|unbounded|kinematic|proposed[,part=value...]), ~steps, ~seed,
/// ~forward_speed [m/s], ~push_vx, ~push_vy [m/s], ~midswing_push_vx,
/// ~midswing_push_vy [m/s] (WalkConfig::midswing_push), ~publish_period [s of sim time, 0.01],
/// ~clock_period [s, 0.001], ~marker_period [s, 0.1], ~wait_for_subscribers (N: wait until every
/// topic has N subscribers, e.g. a recorder; 0), ~wait_for_com_subscribers (N: wait until com_state
/// has N subscribers, e.g. + the planner), ~wait_timeout [s wall, 20; <= 1e6], ~real_time_factor
/// (0: as fast as possible), ~linger [s wall, 1; <= 3600], ~exit_when_done (true: exit ~linger
/// seconds after the walk ends, so a launch with required="true" ends with it; false: stay up,
/// walk_result stays available, until shutdown), ~reachability_samples (true: reachability_result
/// carries the output samples of every slice, at most 500 per set and slice; false: boundaries
/// only; true). ~in_process (true: the checked footsteps are planned in this process; false:
/// through transition_ocp_node's plan_footstep service, which plans them as the in-process loop
/// does and publishes the four check topics above itself; the simulation waits, in sim time, for
/// each answer; true), ~plan_service (the service's name, relative: remappable; plan_footstep).
/// ~plan_retries (calls of a step repeated after a failed one, 0.1 s apart; 2). A step whose
/// calls all fail (the node died or went away) is planned in process instead, with a warning,
/// and its messages published here: the walk and the bag lose nothing. ~plan_timeout (wall
/// seconds a call may take; 60): a node that does not answer in time is hung (stopped, not
/// dead): that step and every later one are planned in process, with a warning.
/// With ~in_process false every policy's TVR contacts (eq. 11, at lift-off and during the
/// swing's first part) are proposed by tvr_planner_node's propose_footstep service
/// (~propose_service, relative: remappable; propose_footstep), with the same retries and
/// timeout; a proposal whose calls fail is planned here, with a warning.
/// The robot is read from the `robot_description` parameter (URDF text).

#include "reach_trajopt/ros/sim_node.h"

#include <ros/ros.h>

int main(int argc, char** argv) {
  ros::init(argc, argv, "sim_node");
  ros::NodeHandle nh, pnh("~");
  try {
    reach_trajopt::ros_bridge::SimNode node(nh, pnh);
    node.run();
  } catch (const std::exception& e) {
    ROS_FATAL("sim_node: %s", e.what());
    return 2;
  }
  return 0;
}
