/// \file sim_node.cpp
/// The walking experiment as a ROS node (sim_node.h; topics and parameters: nodes/sim_node.cpp).

#include "reach_trajopt/ros/sim_node.h"

#include <std_msgs/String.h>

#include <algorithm>
#include <cmath>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/ros/footstep_plan_msgs.h"
#include "reach_trajopt/ros/markers.h"
#include "reach_trajopt/ros/proposed_step_msgs.h"
#include "reach_trajopt/ros/service_requests.h"
#include "reach_trajopt/ros/tvr_proposal_msgs.h"

namespace reach_trajopt {
namespace ros_bridge {

namespace {

template <typename T>
T param(const ros::NodeHandle& nh, const std::string& name, const T& fallback) {
  T value;
  return nh.getParam(name, value) ? value : fallback;
}

// Large queues: the loop may run faster than real time, a recorder must not lose messages.
constexpr int kQueue = 2000;

}  // namespace

SimNodeParams SimNodeParams::read(const ros::NodeHandle& pnh) {
  SimNodeParams p;
  p.publish_period = param(pnh, "publish_period", p.publish_period);
  p.clock_period = param(pnh, "clock_period", p.clock_period);
  p.marker_period = param(pnh, "marker_period", p.marker_period);
  p.wait_for_subscribers = param(pnh, "wait_for_subscribers", p.wait_for_subscribers);
  p.wait_for_com_subscribers = param(pnh, "wait_for_com_subscribers", p.wait_for_com_subscribers);
  p.wait_timeout = param(pnh, "wait_timeout", p.wait_timeout);
  p.real_time_factor = param(pnh, "real_time_factor", p.real_time_factor);
  p.linger = param(pnh, "linger", p.linger);
  p.exit_when_done = param(pnh, "exit_when_done", p.exit_when_done);
  p.reachability_samples = param(pnh, "reachability_samples", p.reachability_samples);
  p.in_process = param(pnh, "in_process", p.in_process);
  p.plan_service = param(pnh, "plan_service", p.plan_service);
  p.propose_service = param(pnh, "propose_service", p.propose_service);
  p.plan_retries = param(pnh, "plan_retries", p.plan_retries);
  p.plan_timeout = param(pnh, "plan_timeout", p.plan_timeout);
  p.validate();
  return p;
}

void SimNodeParams::validate() const {
  if (plan_retries < 0) throw ConfigError("~plan_retries must be >= 0");
  if (!(plan_timeout > 0.0) || plan_timeout > 1e6)
    throw ConfigError("~plan_timeout must be in (0, 1e6] s");
  if (!(publish_period > 0.0) || !(clock_period > 0.0) || !(marker_period > 0.0) ||
      !(publish_period <= 1e6) || !(clock_period <= 1e6) || !(marker_period <= 1e6))
    throw ConfigError("~publish_period, ~clock_period and ~marker_period must be in (0, 1e6] s");
  // ros::WallDuration holds 32-bit seconds: 1e12 s ended the node after its walk.
  if (!(wait_timeout >= 0.0) || wait_timeout > 1e6)
    throw ConfigError("~wait_timeout must be in [0, 1e6] s");
  if (!(linger >= 0.0) || linger > 3600.0) throw ConfigError("~linger must be in [0, 3600] s");
  if (!std::isfinite(real_time_factor))
    throw ConfigError("~real_time_factor must be finite (<= 0: as fast as possible)");
}

WalkSetup readSimWalkSetup(const ros::NodeHandle& pnh) {
  WalkSetup setup = WalkSetup::fromYamlFile(configPath(pnh));
  const std::string sim_config_path = param<std::string>(pnh, "sim_config", "");
  if (!sim_config_path.empty())
    setup.sim = SimConfig::fromYaml(YamlSection::loadFile(sim_config_path).section("sim"));
  WalkConfig& walk = setup.walk;
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
  pnh.getParam("midswing_push_vx", walk.midswing_push.x());
  pnh.getParam("midswing_push_vy", walk.midswing_push.y());
  std::string latency;
  if (pnh.getParam("plan_latency", latency) && !latency.empty())
    walk.setPlanLatency(latency, "~plan_latency");
  walk.validate();
  return setup;
}

SimNode::SimNode(ros::NodeHandle& nh, ros::NodeHandle& pnh)
    : nh_(nh),
      urdf_(robotDescription(nh)),
      setup_(readSimWalkSetup(pnh)),
      params_(SimNodeParams::read(pnh)),
      experiment_(setup_.experiment(urdf_.path())),
      model_(experiment_->model()),
      checks_footholds_(setup_.walk.policy.checksFoothold()),
      through_node_(checks_footholds_ && !params_.in_process),
      ws_(model_),
      link_tf_(model_),
      next_publish_(params_.publish_period),
      next_marker_(params_.marker_period) {
  advertise();
  connectServices();
  waitForSubscribers();
  const WalkConfig& walk = setup_.walk;
  ROS_INFO("sim_node: %s walk (%s) of %d steps, seed %u, robot '%s'", walk.policy.name.c_str(),
           walk.policy.definition().c_str(), walk.steps, walk.seed, model_.name().c_str());
}

void SimNode::advertise() {
  const ContactConfig& contact = setup_.contact;
  clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", kQueue);
  joint_pub_ = nh_.advertise<sensor_msgs::JointState>("joint_states", kQueue);
  com_pub_ = nh_.advertise<reach_trajopt::CenterOfMassState>("com_state", kQueue);
  contact_pub_ = nh_.advertise<reach_trajopt::ContactState>("contact_state", kQueue);
  wrench_pub_[0] = nh_.advertise<geometry_msgs::WrenchStamped>(
      "contact_wrench/" + contact.left_sole_frame, kQueue);
  wrench_pub_[1] = nh_.advertise<geometry_msgs::WrenchStamped>(
      "contact_wrench/" + contact.right_sole_frame, kQueue);
  step_pub_ = nh_.advertise<reach_trajopt::StepReport>("step_report", 100);
  marker_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("markers", 100);
  result_pub_ = nh_.advertise<std_msgs::String>("walk_result", 1, true);
  pubs_ = {&clock_pub_,     &joint_pub_, &com_pub_,    &contact_pub_, &wrench_pub_[0],
           &wrench_pub_[1], &step_pub_,  &marker_pub_, &result_pub_};
  if (!checks_footholds_) return;
  reach_pub_ = nh_.advertise<reach_trajopt::ReachabilityResult>("reachability_result", 100);
  reach_marker_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("reachability_markers", 100);
  traj_pub_ = nh_.advertise<reach_trajopt::TransitionTrajectory>("transition_trajectory", 100);
  traj_marker_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("transition_markers", 100);
  pubs_.insert(pubs_.end(), {&reach_pub_, &reach_marker_pub_, &traj_pub_, &traj_marker_pub_});
}

// The TVR proposals through tvr_planner_node and the checked footsteps through
// transition_ocp_node (~in_process false). Not persistent: a connection per call (a
// millisecond beside a check of seconds) finds a restarted node.
void SimNode::connectServices() {
  const SimNodeParams& p = params_;
  auto requireService = [&](const std::string& name, const char* param_name) {
    if (!ros::service::waitForService(nh_.resolveName(name), ros::Duration(p.wait_timeout)))
      throw ConfigError(
          "~in_process is false but the service '" + nh_.resolveName(name) + "' (" + param_name +
          ") did not appear within ~wait_timeout = " + std::to_string(p.wait_timeout) + " s");
  };
  if (!p.in_process) requireService(p.propose_service, "~propose_service");
  if (through_node_) requireService(p.plan_service, "~plan_service");
  plan_call_ = std::make_unique<FallbackServiceCall<reach_trajopt::PlanFootstep>>(
      nh_, p.plan_service, p.plan_retries, p.plan_timeout, "sim_node");
  propose_call_ = std::make_unique<FallbackServiceCall<reach_trajopt::ProposeFootstep>>(
      nh_, p.propose_service, p.plan_retries, p.plan_timeout, "sim_node");
  if (through_node_)
    experiment_->setFootstepPlanner(
        [this](const FootstepPlanRequest& request) { return planThroughNode(request); });
  if (!p.in_process)
    experiment_->setTvrProposer(
        [this](const TvrProposalRequest& request) { return proposeThroughNode(request); });
}

void SimNode::waitForSubscribers() {
  const SimNodeParams& p = params_;
  if (p.wait_for_subscribers <= 0 && p.wait_for_com_subscribers <= 0) return;
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(p.wait_timeout);
  auto ready = [&]() {
    for (const ros::Publisher* pub : pubs_)
      if (static_cast<int>(pub->getNumSubscribers()) < p.wait_for_subscribers) return false;
    // tvr_planner_node listens to contact_state as to com_state: with a recorder, its
    // subscription is not the first one there (a short walk's bag missed the topic once).
    const int contact_subscribers =
        std::min(p.wait_for_com_subscribers, 1 + p.wait_for_subscribers);
    if (p.wait_for_subscribers > 0 &&
        static_cast<int>(contact_pub_.getNumSubscribers()) < contact_subscribers)
      return false;
    return static_cast<int>(com_pub_.getNumSubscribers()) >= p.wait_for_com_subscribers;
  };
  while (ros::ok() && !ready() && ros::WallTime::now() < deadline) ros::WallDuration(0.05).sleep();
  if (!ready()) ROS_WARN("sim_node: starting before every subscriber connected");
  ros::WallDuration(0.5).sleep();  // let /tf's subscribers connect as well
}

ros::Time SimNode::checkStamp() const { return ros::Time(last_tick_time_ + setup_.sim.time_step); }

// The walking loop checks a step at the start of a control tick, before that tick's on_tick:
// its sim time is the last tick's plus one time step.
FootstepTransition SimNode::planThroughNode(const FootstepPlanRequest& request) {
  const FootstepTransitionPlanner* local_planner = experiment_->footstepPlanner();
  reach_trajopt::PlanFootstep::Request plan_request =
      toPlanFootstepRequestMsg(request, local_planner->config().reach, checkStamp());
  plan_request.marker_id = static_cast<uint32_t>(executed_.size() + 1);  // the step index
  const auto answer =
      plan_call_->call(plan_request, "step " + std::to_string(executed_.size() + 1));
  if (answer) {
    // A rejected request is what the in-process planner throws for it.
    if (!answer->success) throw RequestError(answer->message);
    planned_here_ = false;
    return fromPlanFootstepResponseMsg(*answer, request, model_);
  }
  planned_here_ = true;
  return local_planner->plan(request);
}

TvrProposal SimNode::proposeThroughNode(const TvrProposalRequest& request) {
  const auto answer =
      propose_call_->call(toProposeFootstepRequestMsg(request, checkStamp()),
                          "the TVR proposal of step " + std::to_string(executed_.size() + 1));
  if (answer) {
    // A rejected request is what the in-process planner throws for it.
    if (!answer->success) throw RequestError(answer->message);
    try {
      return fromProposeFootstepResponseMsg(*answer, request);
    } catch (const ReachError& e) {
      ROS_WARN("sim_node: malformed answer of '%s' (%s); proposed in process",
               propose_call_->service().c_str(), e.what());
    }
  }
  return proposeFootstep(setup_.tvr, request);
}

void SimNode::publishMarkers(const ros::Time& stamp) {
  const ContactConfig& contact = setup_.contact;
  visualization_msgs::MarkerArray a =
      footholdMarkers(planned_, executed_, contact.half_length, contact.half_width, stamp);
  a.markers.push_back(pathMarker(com_path_, kNsComPath, 0, 0.01, {0.9f, 0.2f, 0.2f, 1.0f}, stamp));
  if (!swing_path_.empty())  // the current swing, id = next step index
    a.markers.push_back(pathMarker(swing_path_, kNsSwingPath,
                                   static_cast<int>(executed_.size()) + 1, 0.005,
                                   {0.6f, 0.2f, 0.8f, 1.0f}, stamp));
  a.markers.insert(a.markers.end(), swing_paths_.markers.begin(), swing_paths_.markers.end());
  marker_pub_.publish(a);
}

void SimNode::onTick(const WalkTick& tick) {
  if (!ros::ok()) throw Shutdown{};
  const double t = tick.time;
  last_tick_time_ = t;
  if (tick.soles)
    for (size_t i = 0; i < tick.soles->size() && i < 2; ++i)
      sole_z_[i] = (*tick.soles)[i].sole_pose.translation().z();
  if (t + 1e-9 >= next_clock_) {
    rosgraph_msgs::Clock c;
    c.clock = ros::Time(t);
    clock_pub_.publish(c);
    next_clock_ += params_.clock_period;
  }
  if (tick.mode.isSingleSupport() && tick.soles)
    swing_path_.push_back(
        (*tick.soles)[static_cast<int>(tick.mode.swing())].sole_pose.translation());
  if (t + 1e-9 < next_publish_) return;
  next_publish_ += params_.publish_period;
  publishState(tick, ros::Time(t));
  if (params_.real_time_factor > 0.0) {
    const double ahead =
        t / params_.real_time_factor - (ros::WallTime::now() - wall_start_).toSec();
    if (ahead > 0.0) ros::WallDuration(ahead).sleep();
  }
}

// Every ~publish_period: /tf, joint_states, com_state, contact_state, the sole wrenches, and
// every ~marker_period the markers.
void SimNode::publishState(const WalkTick& tick, const ros::Time& stamp) {
  static const Eigen::VectorXd no_effort;
  model_.update(ws_, *tick.q, *tick.qd);
  tf_broadcaster_.sendTransform(link_tf_.compute(ws_, stamp));
  fillJointState(model_, *tick.q, *tick.qd, tick.wbc ? tick.wbc->u : no_effort, stamp, joint_msg_);
  joint_pub_.publish(joint_msg_);
  com_pub_.publish(toCenterOfMassStateMsg(tick, stamp));
  contact_pub_.publish(toContactStateMsg(tick, stamp));
  if (tick.soles)
    for (size_t i = 0; i < tick.soles->size() && i < 2; ++i)
      wrench_pub_[i].publish(toSoleWrenchMsg((*tick.soles)[i], stamp));
  com_path_.push_back(tick.com);
  if (tick.time + 1e-9 >= next_marker_) {
    next_marker_ += params_.marker_period;
    publishMarkers(stamp);
  }
}

void SimNode::onStep(const StepRecord& r) {
  ground_z_ = r.executed.z();
  step_pub_.publish(toStepReportMsg(r, setup_.walk.policy, false, ground_z_));
  planned_.emplace_back(r.planned.x(), r.planned.y(), r.executed.z());
  executed_.push_back(r.executed);
  swing_paths_.markers.push_back(pathMarker(swing_path_, kNsSwingPath, r.index, 0.005,
                                            {0.6f, 0.2f, 0.8f, 1.0f}, ros::Time(r.touchdown_time)));
  swing_path_.clear();
  publishMarkers(ros::Time(r.touchdown_time));
}

// The check's messages of a step planned here (transition_ocp_node publishes those it plans).
// The foothold lies on the ground at the stance sole's height.
void SimNode::onCheck(const StepRecord& r, const FootstepTransition& step) {
  if (!planned_here_) return;
  const ContactConfig& contact = setup_.contact;
  const ros::Time stamp = checkStamp();
  const Eigen::Vector3d foothold = checkedFoothold(r, sole_z_[static_cast<int>(opposite(r.swing))]);
  const ProposedStepMsgs msgs =
      toProposedStepMsgs(model_, contact, r, step, foothold, setup_.footsteps.reach.delta, stamp,
                         params_.reachability_samples);
  reach_pub_.publish(msgs.reachability);
  reach_marker_pub_.publish(msgs.markers);
  traj_pub_.publish(msgs.trajectory);
  const FrameId swing_sole = model_.frameId(swingFrame(contact, opposite(r.swing)));
  traj_marker_pub_.publish(transitionMarkers(step.trajectory, model_, swing_sole, r.index, stamp));
}

// A fall gets its own report (fell = true, touched_down = false), stamped at the fall: the step
// in progress when the loop recorded it, otherwise the next step's index. Then the last clock,
// the markers and the summary.
void SimNode::publishEnd(const WalkResult& result) {
  const ros::Time end_stamp(result.sim_time);
  if (result.fell) {
    StepRecord r;
    if (!result.records.empty() && !result.records.back().touched_down) {
      r = result.records.back();
    } else {
      r.index = result.steps + 1;
      if (!result.records.empty()) r.swing = opposite(result.records.back().swing);
    }
    reach_trajopt::StepReport msg = toStepReportMsg(r, setup_.walk.policy, true, ground_z_);
    msg.header.stamp = end_stamp;
    step_pub_.publish(msg);
  }
  rosgraph_msgs::Clock c;
  c.clock = end_stamp;
  clock_pub_.publish(c);
  publishMarkers(end_stamp);
  std_msgs::String summary;
  summary.data = result.summaryLine();
  result_pub_.publish(summary);
  ROS_INFO("sim_node: %s", summary.data.c_str());
}

void SimNode::run() {
  wall_start_ = ros::WallTime::now();
  WalkResult result;
  try {
    result = experiment_->run(
        [this](const WalkTick& tick) { onTick(tick); }, [this](const StepRecord& r) { onStep(r); },
        [this](const StepRecord& r, const FootstepTransition& step) { onCheck(r, step); });
  } catch (const Shutdown&) {
    ROS_WARN("sim_node: shut down during the walk");
    return;
  }
  publishEnd(result);
  ros::WallDuration(params_.linger).sleep();  // let subscribers (a recorder) receive the last
  if (!params_.exit_when_done) ros::waitForShutdown();  // keep the latched walk_result available
}

}  // namespace ros_bridge
}  // namespace reach_trajopt
