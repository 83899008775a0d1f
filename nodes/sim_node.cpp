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
/// ~forward_speed [m/s], ~push_vx, ~push_vy [m/s], ~publish_period [s of sim time, 0.01],
/// ~clock_period [s, 0.001], ~marker_period [s, 0.1], ~wait_for_subscribers (N: wait until every
/// topic has N subscribers, e.g. a recorder; 0), ~wait_for_com_subscribers (N: wait until com_state
/// has N subscribers, e.g. + the planner), ~wait_timeout [s wall, 20], ~real_time_factor (0: as
/// fast as possible), ~linger [s wall, 1], ~exit_when_done (true: exit ~linger seconds after the
/// walk ends, so a launch with required="true" ends with it; false: stay up, walk_result stays
/// available, until shutdown), ~reachability_samples (true: reachability_result carries the output
/// samples of every slice, at most 500 per set and slice; false: boundaries only; true).
/// ~in_process (true: the checked footsteps are planned in this process; false: through
/// transition_ocp_node's plan_footstep service, which plans them as the in-process loop does and
/// publishes the four check topics above itself; the simulation waits, in sim time, for each
/// answer; true), ~plan_service (the service's name, relative: remappable; plan_footstep).
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

#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/String.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/MarkerArray.h>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "reach_trajopt/PlanFootstep.h"
#include "reach_trajopt/ProposeFootstep.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/ros/conversions.h"
#include "reach_trajopt/ros/fallback_service_call.h"
#include "reach_trajopt/ros/footstep_plan_msgs.h"
#include "reach_trajopt/ros/markers.h"
#include "reach_trajopt/ros/node_setup.h"
#include "reach_trajopt/ros/proposed_step_msgs.h"
#include "reach_trajopt/ros/service_requests.h"
#include "reach_trajopt/ros/tvr_proposal_msgs.h"
#include "reach_trajopt/walk/walk_setup.h"

using namespace reach_trajopt;
namespace rb = reach_trajopt::ros_bridge;

namespace {

struct Shutdown {};  // thrown from the tick callback to leave the walking loop on ros shutdown

template <typename T>
T param(const ros::NodeHandle& nh, const std::string& name, const T& fallback) {
  T value;
  return nh.getParam(name, value) ? value : fallback;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "sim_node");
  ros::NodeHandle nh, pnh("~");
  try {
    const std::string urdf_xml = rb::robotDescription(nh);
    const std::string config_path = rb::configPath(pnh);
    const std::string sim_config_path = param<std::string>(pnh, "sim_config", "");

    WalkSetup setup = WalkSetup::fromYamlFile(config_path);
    if (!sim_config_path.empty())
      setup.sim = SimConfig::fromYaml(YamlSection::loadFile(sim_config_path).section("sim"));
    WalkConfig& walk = setup.walk;
    const ContactConfig& contact = setup.contact;
    const FootstepPlannerConfig& proposed = setup.footsteps;  // policies with a check
    std::string policy;
    if (pnh.getParam("policy", policy)) walk.policy = WalkingPolicy::parse(policy);
    int int_value = 0;
    if (pnh.getParam("steps", int_value)) walk.steps = int_value;
    if (pnh.getParam("seed", int_value)) {
      if (int_value < 0) throw ConfigError("~seed must be >= 0");
      walk.seed = static_cast<unsigned>(int_value);
    }
    pnh.getParam("forward_speed", walk.forward_speed);
    pnh.getParam("push_vx", walk.initial_com_velocity.x());
    pnh.getParam("push_vy", walk.initial_com_velocity.y());
    walk.validate();

    const double publish_period = param(pnh, "publish_period", 0.01);
    const double clock_period = param(pnh, "clock_period", 0.001);
    const double marker_period = param(pnh, "marker_period", 0.1);
    const int wait_for_subscribers = param(pnh, "wait_for_subscribers", 0);
    const int wait_for_com_subscribers = param(pnh, "wait_for_com_subscribers", 0);
    const double wait_timeout = param(pnh, "wait_timeout", 20.0);
    const double real_time_factor = param(pnh, "real_time_factor", 0.0);
    const double linger = param(pnh, "linger", 1.0);
    const bool exit_when_done = param(pnh, "exit_when_done", true);
    const bool reachability_samples = param(pnh, "reachability_samples", true);
    const bool in_process = param(pnh, "in_process", true);
    const std::string plan_service = param<std::string>(pnh, "plan_service", "plan_footstep");
    const std::string propose_service =
        param<std::string>(pnh, "propose_service", "propose_footstep");
    const int plan_retries = param(pnh, "plan_retries", 2);
    if (plan_retries < 0) throw ConfigError("~plan_retries must be >= 0");
    const double plan_timeout = param(pnh, "plan_timeout", 60.0);
    if (!(plan_timeout > 0.0) || plan_timeout > 1e6)
      throw ConfigError("~plan_timeout must be in (0, 1e6] s");
    if (!(publish_period > 0.0) || !(clock_period > 0.0) || !(marker_period > 0.0))
      throw ConfigError("~publish_period, ~clock_period and ~marker_period must be > 0");

    const rb::TempUrdf urdf(urdf_xml);
    const std::unique_ptr<WalkingExperiment> experiment_ptr = setup.experiment(urdf.path());
    WalkingExperiment& experiment = *experiment_ptr;
    const bool checks_footholds = walk.policy.checksFoothold();
    const RobotModel& model = experiment.model();
    Workspace ws(model);
    rb::LinkTransforms link_tf(model);

    // Large queues: the loop may run faster than real time, a recorder must not lose messages.
    const int kQueue = 2000;
    ros::Publisher clock_pub = nh.advertise<rosgraph_msgs::Clock>("/clock", kQueue);
    ros::Publisher joint_pub = nh.advertise<sensor_msgs::JointState>("joint_states", kQueue);
    ros::Publisher com_pub = nh.advertise<reach_trajopt::CenterOfMassState>("com_state", kQueue);
    ros::Publisher contact_pub = nh.advertise<reach_trajopt::ContactState>("contact_state", kQueue);
    ros::Publisher wrench_pub[2] = {nh.advertise<geometry_msgs::WrenchStamped>(
                                        "contact_wrench/" + contact.left_sole_frame, kQueue),
                                    nh.advertise<geometry_msgs::WrenchStamped>(
                                        "contact_wrench/" + contact.right_sole_frame, kQueue)};
    ros::Publisher step_pub = nh.advertise<reach_trajopt::StepReport>("step_report", 100);
    ros::Publisher marker_pub = nh.advertise<visualization_msgs::MarkerArray>("markers", 100);
    ros::Publisher result_pub = nh.advertise<std_msgs::String>("walk_result", 1, true);
    std::vector<ros::Publisher*> pubs = {&clock_pub,   &joint_pub,     &com_pub,
                                         &contact_pub, &wrench_pub[0], &wrench_pub[1],
                                         &step_pub,    &marker_pub,    &result_pub};
    ros::Publisher reach_pub, reach_marker_pub, traj_pub, traj_marker_pub;  // with a check
    if (checks_footholds) {
      reach_pub = nh.advertise<reach_trajopt::ReachabilityResult>("reachability_result", 100);
      reach_marker_pub = nh.advertise<visualization_msgs::MarkerArray>("reachability_markers", 100);
      traj_pub = nh.advertise<reach_trajopt::TransitionTrajectory>("transition_trajectory", 100);
      traj_marker_pub = nh.advertise<visualization_msgs::MarkerArray>("transition_markers", 100);
      pubs.insert(pubs.end(), {&reach_pub, &reach_marker_pub, &traj_pub, &traj_marker_pub});
    }
    tf2_ros::TransformBroadcaster tf_broadcaster;

    // The TVR proposals through tvr_planner_node and the checked footsteps through
    // transition_ocp_node (~in_process false). Not persistent: a connection per call (a
    // millisecond beside a check of seconds) finds a restarted node.
    const FootstepTransitionPlanner* local_planner = experiment.footstepPlanner();
    const bool through_node = checks_footholds && !in_process;
    auto requireService = [&](const std::string& name, const char* param_name) {
      if (!ros::service::waitForService(nh.resolveName(name), ros::Duration(wait_timeout)))
        throw ConfigError(
            "~in_process is false but the service '" + nh.resolveName(name) + "' (" + param_name +
            ") did not appear within ~wait_timeout = " + std::to_string(wait_timeout) + " s");
    };
    if (!in_process) requireService(propose_service, "~propose_service");
    if (through_node) requireService(plan_service, "~plan_service");
    rb::FallbackServiceCall<reach_trajopt::PlanFootstep> plan_call(nh, plan_service, plan_retries,
                                                                   plan_timeout, "sim_node");
    rb::FallbackServiceCall<reach_trajopt::ProposeFootstep> propose_call(
        nh, propose_service, plan_retries, plan_timeout, "sim_node");

    if (wait_for_subscribers > 0 || wait_for_com_subscribers > 0) {
      const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(wait_timeout);
      auto ready = [&]() {
        for (const ros::Publisher* p : pubs)
          if (static_cast<int>(p->getNumSubscribers()) < wait_for_subscribers) return false;
        return static_cast<int>(com_pub.getNumSubscribers()) >= wait_for_com_subscribers;
      };
      while (ros::ok() && !ready() && ros::WallTime::now() < deadline)
        ros::WallDuration(0.05).sleep();
      if (!ready()) ROS_WARN("sim_node: starting before every subscriber connected");
      ros::WallDuration(0.5).sleep();  // let /tf's subscribers connect as well
    }
    ROS_INFO("sim_node: %s walk (%s) of %d steps, seed %u, robot '%s'", walk.policy.name.c_str(),
             walk.policy.definition().c_str(), walk.steps, walk.seed, model.name().c_str());

    std::vector<Eigen::Vector3d> planned, executed, com_path, swing_path;
    visualization_msgs::MarkerArray swing_paths;  // one LINE_STRIP per finished step
    sensor_msgs::JointState joint_msg;
    const double half_length = contact.half_length, half_width = contact.half_width;
    double ground_z = 0.0;  // height of the last executed foothold [m]
    double next_publish = publish_period, next_clock = 0.0, next_marker = marker_period;
    // The last control tick seen: the proposed mode's check runs at the start of the next one.
    double last_tick_time = 0.0;
    double sole_z[2] = {0.0, 0.0};  // measured sole heights at that tick [m]
    const ros::WallTime wall_start = ros::WallTime::now();
    const Eigen::VectorXd no_effort;

    auto publishMarkers = [&](const ros::Time& stamp) {
      visualization_msgs::MarkerArray a =
          rb::footholdMarkers(planned, executed, half_length, half_width, stamp);
      a.markers.push_back(
          rb::pathMarker(com_path, rb::kNsComPath, 0, 0.01, {0.9f, 0.2f, 0.2f, 1.0f}, stamp));
      if (!swing_path.empty())  // the current swing, id = next step index
        a.markers.push_back(rb::pathMarker(swing_path, rb::kNsSwingPath,
                                           static_cast<int>(executed.size()) + 1, 0.005,
                                           {0.6f, 0.2f, 0.8f, 1.0f}, stamp));
      a.markers.insert(a.markers.end(), swing_paths.markers.begin(), swing_paths.markers.end());
      marker_pub.publish(a);
    };

    auto onTick = [&](const WalkTick& tick) {
      if (!ros::ok()) throw Shutdown{};
      const double t = tick.time;
      last_tick_time = t;
      if (tick.soles)
        for (size_t i = 0; i < tick.soles->size() && i < 2; ++i)
          sole_z[i] = (*tick.soles)[i].sole_pose.translation().z();
      if (t + 1e-9 >= next_clock) {
        rosgraph_msgs::Clock c;
        c.clock = ros::Time(t);
        clock_pub.publish(c);
        next_clock += clock_period;
      }
      if (tick.mode.isSingleSupport() && tick.soles)
        swing_path.push_back(
            (*tick.soles)[static_cast<int>(tick.mode.swing())].sole_pose.translation());
      if (t + 1e-9 < next_publish) return;
      next_publish += publish_period;
      const ros::Time stamp(t);
      model.update(ws, *tick.q, *tick.qd);
      tf_broadcaster.sendTransform(link_tf.compute(ws, stamp));
      rb::fillJointState(model, *tick.q, *tick.qd, tick.wbc ? tick.wbc->u : no_effort, stamp,
                         joint_msg);
      joint_pub.publish(joint_msg);
      com_pub.publish(rb::toCenterOfMassStateMsg(tick, stamp));
      contact_pub.publish(rb::toContactStateMsg(tick, stamp));
      if (tick.soles)
        for (size_t i = 0; i < tick.soles->size() && i < 2; ++i)
          wrench_pub[i].publish(rb::toSoleWrenchMsg((*tick.soles)[i], stamp));
      com_path.push_back(tick.com);
      if (t + 1e-9 >= next_marker) {
        next_marker += marker_period;
        publishMarkers(stamp);
      }
      if (real_time_factor > 0.0) {
        const double ahead = t / real_time_factor - (ros::WallTime::now() - wall_start).toSec();
        if (ahead > 0.0) ros::WallDuration(ahead).sleep();
      }
    };

    auto onStep = [&](const StepRecord& r) {
      ground_z = r.executed.z();
      step_pub.publish(rb::toStepReportMsg(r, walk.policy, false, ground_z));
      planned.emplace_back(r.planned.x(), r.planned.y(), r.executed.z());
      executed.push_back(r.executed);
      swing_paths.markers.push_back(rb::pathMarker(swing_path, rb::kNsSwingPath, r.index, 0.005,
                                                   {0.6f, 0.2f, 0.8f, 1.0f},
                                                   ros::Time(r.touchdown_time)));
      swing_path.clear();
      publishMarkers(ros::Time(r.touchdown_time));
    };

    // The walking loop checks a step at the start of a control tick, before that tick's
    // on_tick: its sim time is the last tick's plus one time step.
    bool planned_here = true;  // the last checked step was planned in this process
    if (through_node)
      experiment.setFootstepPlanner([&](const FootstepPlanRequest& request) {
        reach_trajopt::PlanFootstep::Request plan_request =
            rb::toPlanFootstepRequestMsg(request, local_planner->config().reach,
                                         ros::Time(last_tick_time + setup.sim.time_step));
        plan_request.marker_id = static_cast<uint32_t>(executed.size() + 1);  // the step index
        const auto answer =
            plan_call.call(plan_request, "step " + std::to_string(executed.size() + 1));
        if (answer) {
          // A rejected request is what the in-process planner throws for it.
          if (!answer->success) throw RequestError(answer->message);
          planned_here = false;
          return rb::fromPlanFootstepResponseMsg(*answer, request, model);
        }
        planned_here = true;
        return local_planner->plan(request);
      });
    if (!in_process)
      experiment.setTvrProposer([&](const TvrProposalRequest& request) {
        const auto answer =
            propose_call.call(rb::toProposeFootstepRequestMsg(
                                  request, ros::Time(last_tick_time + setup.sim.time_step)),
                              "the TVR proposal of step " + std::to_string(executed.size() + 1));
        if (answer) {
          // A rejected request is what the in-process planner throws for it.
          if (!answer->success) throw RequestError(answer->message);
          try {
            return rb::fromProposeFootstepResponseMsg(*answer, request);
          } catch (const ReachError& e) {
            ROS_WARN("sim_node: malformed answer of '%s' (%s); proposed in process",
                     propose_call.service().c_str(), e.what());
          }
        }
        return proposeFootstep(setup.tvr, request);
      });

    // The check's messages of a step planned here (transition_ocp_node publishes those it
    // plans). The foothold lies on the ground at the stance sole's height.
    auto onCheck = [&](const StepRecord& r, const FootstepTransition& step) {
      if (!planned_here) return;
      const ros::Time stamp(last_tick_time + setup.sim.time_step);
      const Eigen::Vector3d foothold =
          rb::checkedFoothold(r, sole_z[static_cast<int>(opposite(r.swing))]);
      const rb::ProposedStepMsgs msgs = rb::toProposedStepMsgs(
          model, contact, r, step, foothold, proposed.reach.delta, stamp, reachability_samples);
      reach_pub.publish(msgs.reachability);
      reach_marker_pub.publish(msgs.markers);
      traj_pub.publish(msgs.trajectory);
      const FrameId swing_sole = model.frameId(rb::swingFrame(contact, opposite(r.swing)));
      traj_marker_pub.publish(
          rb::transitionMarkers(step.trajectory, model, swing_sole, r.index, stamp));
    };

    WalkResult result;
    try {
      result = experiment.run(onTick, onStep, onCheck);
    } catch (const Shutdown&) {
      ROS_WARN("sim_node: shut down during the walk");
      return 0;
    }
    const ros::Time end_stamp(result.sim_time);
    // A fall gets its own report (fell = true, touched_down = false), stamped at the fall: the
    // step in progress when the loop recorded it, otherwise the next step's index.
    if (result.fell) {
      StepRecord r;
      if (!result.records.empty() && !result.records.back().touched_down) {
        r = result.records.back();
      } else {
        r.index = result.steps + 1;
        if (!result.records.empty()) r.swing = opposite(result.records.back().swing);
      }
      reach_trajopt::StepReport msg = rb::toStepReportMsg(r, walk.policy, true, ground_z);
      msg.header.stamp = end_stamp;
      step_pub.publish(msg);
    }
    rosgraph_msgs::Clock c;
    c.clock = end_stamp;
    clock_pub.publish(c);
    publishMarkers(end_stamp);
    std_msgs::String summary;
    summary.data = result.summaryLine();
    result_pub.publish(summary);
    ROS_INFO("sim_node: %s", summary.data.c_str());
    ros::WallDuration(linger).sleep();  // let subscribers (a recorder) receive the last messages
    if (!exit_when_done) ros::waitForShutdown();  // keep the latched walk_result available
  } catch (const std::exception& e) {
    ROS_FATAL("sim_node: %s", e.what());
    return 2;
  }
  return 0;
}
