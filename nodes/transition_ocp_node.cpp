/// transition_ocp_node: the transition optimal control problem of eq. (22)-(23) as a ROS
/// service, optionally seeded by the reachability witness, with the relaxation of an
/// unreachable foothold (the robot steps to the closest reachable point).
///   service plan_transition (reach_trajopt/PlanTransition)
///   action plan_transition_action (reach_trajopt/PlanTransition.action): plan_transition with
///   feedback from the check (slices, samples, QPs) and the OCP (gradient evaluations); a newer
///   goal or a cancel preempts the running plan (result: success false, "preempted")
///   service plan_footstep (reach_trajopt/PlanFootstep): one checked footstep of the walking
///   loop through the whole per-step pipeline (step/footstep_transition_planner.h), as the
///   in-process loop plans it (sim_node ~in_process:=false calls it); it also publishes
///   reachability_markers (MarkerArray: the check's sets, witness and foothold)
///   publishes transition_trajectory (TransitionTrajectory), transition_markers (MarkerArray:
///   the swing sole's path and landing) and, when the check ran, reachability_result
/// x_f is the kinematic feasibility solution (Sec. III-B) with the swing sole on the foothold.
/// Bad requests (NaN, wrong sizes, unknown frame, empty contact set, a foothold in the air) get
/// success = false and the reason; the node keeps serving.
/// Parameters (private): ~config (YAML with sections contact, kinematic_feasibility, reach,
/// optionally walk and ocp; default config/biped.yaml of the package), ~default_horizon [s, at
/// most 5] (t_f - t_0 when the request gives 0; default: the reach horizon), ~ground_tolerance
/// [m, >= 0], ~reachability_samples (plan_footstep's reachability_result carries the output
/// samples of every slice, at most 500 per set and slice; false: boundaries only; true).
/// Reachability workers (walk.launch workers:=N): ~workers (N reachability_nodes whose
/// check_footholds services, <~worker_prefix><i>/check_footholds for i < N, check the
/// candidates of the nearest-feasible-foothold search in parallel; 0: in this process; 0; at
/// most 64), ~worker_prefix (relative, remappable; reachability_worker_), ~worker_timeout [s
/// wall, in (0, 1e6]: the longest wait for a worker's answer and, at start, for its service;
/// 10], ~worker_retry_period [s wall, in [0, 1e6]: how long a worker that failed or timed out
/// is left out; 30]. A worker's failure
/// sends its candidates to another worker or checks them here: the plans do not change.
/// The footstep check of plan_footstep (walk.launch): ~check_service (reachability_node's
/// check_footstep, relative, remappable; "": in this process; ""), ~check_timeout [s wall, the
/// longest wait for its answer and, at start, for the service; 60]. plan_footstep's planner then
/// sends the kinematic and the reachability check of each step there and optimizes with the
/// answer; a failed or malformed call is checked here, a timed-out one too and every later one
/// (the plans do not change). plan_transition keeps checking in this process (with progress).
/// The robot is read from the `robot_description` parameter (URDF text).

#include <actionlib/server/simple_action_server.h>
#include <ros/ros.h>

#include <memory>
#include <string>
#include <vector>

#include "reach_trajopt/PlanFootstep.h"
#include "reach_trajopt/PlanTransition.h"
#include "reach_trajopt/PlanTransitionAction.h"
#include "reach_trajopt/ocp/ocp_config.h"
#include "reach_trajopt/ocp/transition_ocp.h"
#include "reach_trajopt/ros/action_goals.h"
#include "reach_trajopt/ros/conversions.h"
#include "reach_trajopt/ros/footstep_plan_msgs.h"
#include "reach_trajopt/ros/markers.h"
#include "reach_trajopt/ros/node_setup.h"
#include "reach_trajopt/ros/proposed_step_msgs.h"
#include "reach_trajopt/ros/reachability_workers.h"
#include "reach_trajopt/ros/remote_footstep_check.h"
#include "reach_trajopt/ros/service_requests.h"
#include "reach_trajopt/ros/transition_ocp_node_params.h"

using namespace reach_trajopt;
namespace rb = reach_trajopt::ros_bridge;

namespace {

class TransitionOcpNode {
 public:
  TransitionOcpNode(ros::NodeHandle& nh, ros::NodeHandle& pnh)
      : s_(rb::FootholdServiceSetup::load(nh, pnh)),
        params_(rb::TransitionOcpNodeParams::read(pnh, s_.reach)) {
    startFootstepCheck(nh);
    startWorkers(nh);
    // Queues for a recorder of a walk (one message of each per step).
    traj_pub_ = nh.advertise<reach_trajopt::TransitionTrajectory>("transition_trajectory", 100);
    reach_pub_ = nh.advertise<reach_trajopt::ReachabilityResult>("reachability_result", 100);
    reach_marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("reachability_markers", 100);
    marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("transition_markers", 100);
    server_ = nh.advertiseService("plan_transition", &TransitionOcpNode::plan, this);
    footstep_server_ = nh.advertiseService("plan_footstep", &TransitionOcpNode::planFootstep, this);
    transition_action_ = std::make_unique<TransitionAction>(
        nh, "plan_transition_action",
        [this](const reach_trajopt::PlanTransitionGoalConstPtr& goal) { executeTransition(goal); },
        false);
    transition_action_->start();
  }

 private:
  // The reachability workers of the nearest-feasible search (~workers), before serving.
  void startWorkers(const ros::NodeHandle& nh) {
    const int workers = params_.workers;
    const std::string& prefix = params_.worker_prefix;
    const double timeout = params_.worker_timeout;
    if (workers == 0) return;
    std::vector<std::string> services;
    for (int i = 0; i < workers; ++i) {
      services.push_back(prefix + std::to_string(i) + "/check_footholds");
      if (!ros::service::waitForService(nh.resolveName(services.back()), ros::Duration(timeout)))
        ROS_WARN(
            "transition_ocp_node: worker service '%s' not up within ~worker_timeout; "
            "its candidates go elsewhere until it is",
            nh.resolveName(services.back()).c_str());
    }
    const KinematicFeasibility& kinematics = s_.planner->kinematics();
    workers_ = std::make_unique<rb::ReachabilityWorkerPool>(
        nh, services, timeout, params_.worker_retry_period, s_.model->nq(),
        [&kinematics](const FootholdCandidates& b) {
          return checkFootholdCandidates(kinematics, b, false);
        });
    const CandidateCheck check = [pool = workers_.get()](const FootholdCandidates& b) {
      return pool->check(b);
    };
    s_.planner->setCandidateCheck(check);
    if (footstep_planner_) footstep_planner_->setCandidateCheck(check);
    ROS_INFO("transition_ocp_node: %d reachability workers (%s0..%d)", workers, prefix.c_str(),
             workers - 1);
  }

  // plan_footstep's own planner, whose footstep check is reachability_node's (~check_service),
  // before serving.
  void startFootstepCheck(const ros::NodeHandle& nh) {
    const std::string& service = params_.check_service;
    const double timeout = params_.check_timeout;
    if (service.empty()) return;
    if (!ros::service::waitForService(nh.resolveName(service), ros::Duration(timeout)))
      ROS_WARN(
          "transition_ocp_node: '%s' (~check_service) not up within ~check_timeout; the "
          "footsteps are checked here until it is",
          nh.resolveName(service).c_str());
    footstep_planner_ =
        std::make_shared<FootstepTransitionPlanner>(s_.model, s_.contact, s_.planner->config());
    remote_check_ = std::make_unique<rb::RemoteFootstepCheck>(
        nh, service, timeout, s_.planner, s_.contact, params_.reachability_samples);
    footstep_planner_->setFootstepCheck(
        [check = remote_check_.get()](const ContactTransition& r, const ReachConfig& c,
                                      const CheckPass& pass,
                                      bool reach) { return check->check(r, c, pass, reach); });
    ROS_INFO("transition_ocp_node: plan_footstep checks its footsteps on '%s'",
             nh.resolveName(service).c_str());
  }

  bool plan(reach_trajopt::PlanTransition::Request& req,
            reach_trajopt::PlanTransition::Response& res) {
    return answerTransition(req, res, {});
  }

  // plan_transition_action: the service's plan with feedback from the check and the OCP; a
  // newer goal or a cancel preempts it at its next progress report.
  void executeTransition(const reach_trajopt::PlanTransitionGoalConstPtr& goal) {
    const auto req = rb::serviceRequestOf<reach_trajopt::PlanTransition::Request>(*goal);
    bool cancelled = false;
    auto wanted = [&] {
      return !(cancelled = transition_action_->isPreemptRequested() || !ros::ok());
    };
    FootstepPlanProgress progress;
    uint32_t pass = 1;
    progress.pass = [&](int p) { pass = static_cast<uint32_t>(p); };
    progress.check = [&](const ReachProgress& p) {
      if (!wanted()) return false;
      reach_trajopt::PlanTransitionFeedback f;
      f.stage = "check";
      f.check_pass = pass;
      rb::fillCheckFeedback(p, f);
      transition_action_->publishFeedback(f);
      return true;
    };
    progress.ocp = [&](const OcpProgress& p) {
      if (!wanted()) return false;
      reach_trajopt::PlanTransitionFeedback f;
      f.stage = "ocp";
      f.check_pass = pass;
      f.relaxed = p.relaxed;
      f.ocp_evaluations = static_cast<uint32_t>(p.evaluations);
      transition_action_->publishFeedback(f);
      return true;
    };
    rb::finishGoalWithAnswer<reach_trajopt::PlanTransition::Response,
                             reach_trajopt::PlanTransitionResult>(
        *transition_action_, cancelled, [&](auto& res) { answerTransition(req, res, progress); },
        [](const auto& res, auto& result) {
          result.reachability = res.reachability;
          result.trajectory = res.trajectory;
        });
  }

  // One plan_transition request, for the service and the action (with its progress).
  bool answerTransition(const reach_trajopt::PlanTransition::Request& req,
                        reach_trajopt::PlanTransition::Response& res,
                        const FootstepPlanProgress& progress) {
    const ros::Time t0 = req.header.stamp;
    res.reachability = rb::reachabilityVerdictMsg("not_checked", "", t0);
    return rb::answerOrReject(
        "plan_transition",
        [&] {
          const ContactTransition r = rb::parseFootholdRequest(
              *s_.model, s_.contact, req.header.frame_id, req.contact_mode, req.q, req.qd,
              req.foothold, req.swing_duration, params_.default_horizon, s_.standing_q, s_.limits);
          FootstepPlanRequest step_request(r);
          step_request.make_contact_consistent = false;  // x_0 as requested
          step_request.check_reachability = req.check_reachability;
          step_request.reach = rb::reachConfigForDuration(s_.reach, r.horizon);
          step_request.ocp_policy = req.allow_relaxation ? OcpPolicy::kAuto : OcpPolicy::kStrict;
          step_request.on_infeasible = req.allow_relaxation
                                           ? InfeasibleFootholdPolicy::kRelaxTowardTarget
                                           : InfeasibleFootholdPolicy::kReject;
          const FootstepTransition step = s_.planner->plan(step_request, progress);
          if (req.check_reachability && step.kinematically_feasible) {
            res.reachability = rb::toReachabilityResultMsg(step.check.reach, r,
                                                           rb::swingFrame(s_.contact, r.stance),
                                                           step_request.reach->delta, t0, false);
            rb::applyPlannerVerdict(step, res.reachability);
            reach_pub_.publish(res.reachability);
          }
          const TransitionResult& result = step.trajectory;
          res.trajectory = rb::toTransitionTrajectoryMsg(
              result, *s_.model, {s_.contact.left_sole_frame, s_.contact.right_sole_frame}, t0);
          res.success = true;
          res.message = res.trajectory.status + ": " + res.trajectory.message;
          traj_pub_.publish(res.trajectory);
          marker_pub_.publish(rb::transitionMarkers(
              result, *s_.model, s_.model->frameId(rb::swingFrame(s_.contact, r.stance)), 0, t0));
        },
        [&](const std::string& reason) {
          res.success = false;
          res.message = reason;
          res.trajectory = rb::errorTrajectoryMsg(reason, t0);
        });
  }

  // One footstep of a walk: the loop's request, planned as in process; the messages of the
  // check and the OCP published as sim_node publishes them in process.
  bool planFootstep(reach_trajopt::PlanFootstep::Request& req,
                    reach_trajopt::PlanFootstep::Response& res) {
    const ros::Time t0 = req.header.stamp;
    return rb::answerOrReject(
        "plan_footstep",
        [&] {
          const FootstepPlanRequest request =
              rb::fromPlanFootstepRequestMsg(req, s_.model->nq(), s_.reach);
          if (remote_check_) remote_check_->beginStep(t0);
          const FootstepTransition step =
              (footstep_planner_ ? *footstep_planner_ : *s_.planner).plan(request);
          res = rb::toPlanFootstepResponseMsg(step, *s_.model, s_.contact, t0);
          // The four check topics of every planned step, as sim_node publishes them when it
          // plans in process (also for a kinematic-only check); the check's result as built
          // where it ran.
          StepRecord record;  // what the messages need of the walk's record: the swing side
          record.swing = opposite(request.stance);
          const rb::ProposedStepMsgs msgs =
              remote_check_ ? rb::toProposedStepMsgs(*s_.model, s_.contact, step,
                                                     remote_check_->checkedMessage(), t0)
                            : rb::toProposedStepMsgs(*s_.model, s_.contact, record, step,
                                                     request.target.position, request.reach->delta,
                                                     t0, params_.reachability_samples);
          reach_pub_.publish(msgs.reachability);
          reach_marker_pub_.publish(msgs.markers);
          traj_pub_.publish(msgs.trajectory);
          marker_pub_.publish(
              rb::transitionMarkers(step.trajectory, *s_.model,
                                    s_.model->frameId(rb::swingFrame(s_.contact, request.stance)),
                                    static_cast<int>(req.marker_id), t0));
        },
        [&](const std::string& reason) {
          res = rb::rejectedResponse<reach_trajopt::PlanFootstep::Response>(reason);
          res.trajectory = rb::errorTrajectoryMsg(reason, t0);
        });
  }

  using TransitionAction = actionlib::SimpleActionServer<reach_trajopt::PlanTransitionAction>;
  const rb::FootholdServiceSetup s_;
  const rb::TransitionOcpNodeParams params_;             ///< checked before any wait for a service
  std::unique_ptr<TransitionAction> transition_action_;  ///< goals run on its own thread
  std::unique_ptr<rb::ReachabilityWorkerPool> workers_;  ///< none: ~workers 0
  /// plan_footstep's planner and its footstep check on reachability_node; none: ~check_service
  /// empty (s_.planner plans).
  std::shared_ptr<FootstepTransitionPlanner> footstep_planner_;
  std::unique_ptr<rb::RemoteFootstepCheck> remote_check_;
  ros::Publisher traj_pub_, reach_pub_, reach_marker_pub_, marker_pub_;
  ros::ServiceServer server_, footstep_server_;
};

}  // namespace

int main(int argc, char** argv) {
  return rb::runServiceNode<TransitionOcpNode>(argc, argv, "transition_ocp_node");
}
