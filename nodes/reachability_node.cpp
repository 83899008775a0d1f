/// reachability_node: the whole-body reachability check of the next foothold (paper Sec. III,
/// eq. (13)-(21), Prop. 1-2) as a ROS service.
///   service check_reachability (reach_trajopt/CheckReachability)
///   publishes reachability_result (ReachabilityResult) and reachability_markers (MarkerArray)
///   action check_reachability_action (reach_trajopt/CheckReachability.action): the same check
///   with feedback after each time slice (direction, slices, samples, QPs); a newer goal or a
///   cancel preempts the running one before its next slice (result: success false, "preempted")
///   service check_footholds (reach_trajopt/CheckFootholds): the kinematic check of a batch of
///   candidate footholds, as a worker of transition_ocp_node's nearest-feasible-foothold search
///   (walk.launch workers:=N); publishes footholds_checked (std_msgs/UInt64, latched: the
///   candidates checked so far)
///   service check_footstep (reach_trajopt/CheckFootstep): the kinematic and the reachability
///   check of one footstep of the walk (step/footstep_check.h) for transition_ocp_node's
///   plan_footstep (its ~check_service, set by walk.launch): the same FootstepReachability and
///   configuration as in transition_ocp_node, the answer with what its planner uses and the
///   ReachabilityResult it publishes; publishes footsteps_checked (std_msgs/UInt64, latched:
///   the footsteps checked so far)
/// x_f is the kinematic feasibility solution (Sec. III-B) with the swing sole on the foothold;
/// an infeasible foothold is answered "unreachable" with the IK's reason. Bad requests (NaN,
/// wrong sizes, unknown frame, empty contact set, a foothold in the air) get success = false
/// and the reason; the node keeps serving.
/// Parameters (private): ~config (YAML with sections contact, kinematic_feasibility, reach and
/// optionally walk; default config/biped.yaml of the package), ~ground_tolerance [m, 0.02].
/// The robot is read from the `robot_description` parameter (URDF text).

#include <actionlib/server/simple_action_server.h>
#include <ros/ros.h>
#include <std_msgs/UInt64.h>
#include <visualization_msgs/MarkerArray.h>

#include <memory>
#include <string>

#include "reach_trajopt/CheckFootholds.h"
#include "reach_trajopt/CheckFootstep.h"
#include "reach_trajopt/CheckReachability.h"
#include "reach_trajopt/CheckReachabilityAction.h"
#include "reach_trajopt/ros/action_goals.h"
#include "reach_trajopt/ros/foothold_candidate_msgs.h"
#include "reach_trajopt/ros/footstep_check_msgs.h"
#include "reach_trajopt/ros/markers.h"
#include "reach_trajopt/ros/node_setup.h"
#include "reach_trajopt/ros/proposed_step_msgs.h"
#include "reach_trajopt/ros/service_requests.h"

using namespace reach_trajopt;
namespace rb = reach_trajopt::ros_bridge;

namespace {

class ReachabilityNode {
 public:
  ReachabilityNode(ros::NodeHandle& nh, ros::NodeHandle& pnh)
      : s_(rb::FootholdServiceSetup::load(nh, pnh)) {
    result_pub_ = nh.advertise<reach_trajopt::ReachabilityResult>("reachability_result", 10);
    marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("reachability_markers", 10);
    server_ = nh.advertiseService("check_reachability", &ReachabilityNode::check, this);
    checked_pub_ = nh.advertise<std_msgs::UInt64>("footholds_checked", 1, true);
    footholds_server_ =
        nh.advertiseService("check_footholds", &ReachabilityNode::checkFootholds, this);
    footsteps_checked_pub_ = nh.advertise<std_msgs::UInt64>("footsteps_checked", 1, true);
    footstep_server_ =
        nh.advertiseService("check_footstep", &ReachabilityNode::checkFootstep, this);
    action_ = std::make_unique<CheckAction>(
        nh, "check_reachability_action",
        [this](const reach_trajopt::CheckReachabilityGoalConstPtr& goal) { execute(goal); }, false);
    action_->start();
  }

 private:
  bool check(reach_trajopt::CheckReachability::Request& req,
             reach_trajopt::CheckReachability::Response& res) {
    return answer(req, res, {});
  }

  // The check of one request, for the service and the action (with its progress).
  bool answer(const reach_trajopt::CheckReachability::Request& req,
              reach_trajopt::CheckReachability::Response& res,
              const ReachProgressCallback& progress) {
    const ros::Time t0 = req.header.stamp;
    return rb::answerOrReject(
        "check_reachability",
        [&] {
          const ContactTransition r = rb::parseFootholdRequest(
              *s_.model, s_.contact, req.header.frame_id, req.contact_mode, req.q, req.qd,
              req.foothold, req.swing_duration, s_.reach.horizon, s_.standing_q, s_.limits);
          // The window stays at the same fractions of the horizon (a no-op for duration 0).
          ReachConfig config = rb::reachConfigForDuration(s_.reach, r.horizon);
          if (req.forward_samples > static_cast<uint32_t>(ReachLimits::kMaxInitialSamples))
            throw RequestError("forward_samples " + std::to_string(req.forward_samples) +
                               " is over the limit of " +
                               std::to_string(ReachLimits::kMaxInitialSamples));
          if (req.backward_samples > 0 && req.backward_samples != req.forward_samples)
            throw RequestError(
                "backward_samples: both directions draw initial_samples; set "
                "forward_samples only (or equal)");
          if (req.forward_samples > 0)
            config.budgets.full.initial_samples = static_cast<int>(req.forward_samples);
          if (req.seed > 0) config.seed = req.seed;
          config.validate();
          config.requireResourcesWithinLimits(s_.model->nq());  // reject before the IK runs
          const KinematicFeasibilityResult ik =
              s_.planner->kinematics().check(r.stance, r.stance_contact, r.target, r.q0);
          const std::string& swing_frame = rb::swingFrame(s_.contact, r.stance);
          if (!ik.feasible) {
            res.result = rb::infeasibleFootholdMsg(ik.reason, swing_frame, r.target.position, t0);
          } else {
            const ReachResult result =
                s_.planner->analyzer().check(footstepProblem(r, ik.q_f, ik.qd_f), config, progress);
            res.result = rb::toReachabilityResultMsg(result, r, swing_frame, config.delta, t0,
                                                     req.return_samples);
          }
          res.success = true;
          res.message = res.result.verdict + ": " + res.result.message;
          result_pub_.publish(res.result);
          marker_pub_.publish(rb::reachabilityMarkers(res.result));
        },
        [&](const std::string& reason) {
          res.success = false;
          res.message = reason;
          res.result = rb::reachabilityVerdictMsg("error", reason, t0);
        });
  }

  // check_reachability_action: the service's check with feedback after each slice; a newer
  // goal or a cancel preempts it before its next slice.
  void execute(const reach_trajopt::CheckReachabilityGoalConstPtr& goal) {
    const auto req = rb::serviceRequestOf<reach_trajopt::CheckReachability::Request>(*goal);
    bool cancelled = false;
    const ReachProgressCallback progress = [&](const ReachProgress& p) {
      if (action_->isPreemptRequested() || !ros::ok()) return !(cancelled = true);
      reach_trajopt::CheckReachabilityFeedback f;
      rb::fillCheckFeedback(p, f);
      action_->publishFeedback(f);
      return true;
    };
    rb::finishGoalWithAnswer<reach_trajopt::CheckReachability::Response,
                             reach_trajopt::CheckReachabilityResult>(
        *action_, cancelled, [&](auto& res) { answer(req, res, progress); },
        [](const auto& res, auto& result) { result.result = res.result; });
  }

  bool checkFootholds(reach_trajopt::CheckFootholds::Request& req,
                      reach_trajopt::CheckFootholds::Response& res) {
    return rb::answerOrReject(
        "check_footholds",
        [&] {
          const FootholdCandidates batch = rb::fromCheckFootholdsRequestMsg(req, s_.model->nq());
          res = rb::toCheckFootholdsResponseMsg(
              checkFootholdCandidates(s_.planner->kinematics(), batch, false), req.request_id);
          std_msgs::UInt64 count;
          count.data = checked_ += batch.candidates.size();
          checked_pub_.publish(count);
        },
        [&](const std::string& reason) {
          res = rb::rejectedResponse<reach_trajopt::CheckFootholds::Response>(reason);
          res.request_id = req.request_id;
        });
  }

  // One footstep of the walk, checked as transition_ocp_node's planner checks it in process.
  bool checkFootstep(reach_trajopt::CheckFootstep::Request& req,
                     reach_trajopt::CheckFootstep::Response& res) {
    return rb::answerOrReject(
        "check_footstep",
        [&] {
          const rb::FootstepCheckCall call =
              rb::fromCheckFootstepRequestMsg(req, s_.model->nq(), s_.reach);
          const FootstepCheckResult check =
              reach_trajopt::checkFootstep(s_.planner->footstepReachability(), call.request,
                                           call.reach, call.pass, call.reachability);
          res = rb::toCheckFootstepResponseMsg(
              check, rb::checkedFootstepMsg(check, rb::swingFrame(s_.contact, call.request.stance),
                                            call.request.target.position, call.reach.delta,
                                            req.header.stamp, call.samples));
          std_msgs::UInt64 count;
          count.data = ++footsteps_checked_;
          footsteps_checked_pub_.publish(count);
        },
        [&](const std::string& reason) {
          res = rb::rejectedResponse<reach_trajopt::CheckFootstep::Response>(reason);
        });
  }

  using CheckAction = actionlib::SimpleActionServer<reach_trajopt::CheckReachabilityAction>;
  const rb::FootholdServiceSetup s_;
  std::unique_ptr<CheckAction> action_;  ///< its goals run on the action server's thread
  ros::Publisher result_pub_, marker_pub_, checked_pub_, footsteps_checked_pub_;
  ros::ServiceServer server_, footholds_server_, footstep_server_;
  uint64_t checked_ = 0;            ///< candidates checked by check_footholds
  uint64_t footsteps_checked_ = 0;  ///< footsteps checked by check_footstep
};

}  // namespace

int main(int argc, char** argv) {
  return rb::runServiceNode<ReachabilityNode>(argc, argv, "reachability_node");
}
