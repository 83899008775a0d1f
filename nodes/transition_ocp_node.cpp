/// transition_ocp_node: the transition optimal control problem of eq. (22)-(23) as a ROS
/// service, optionally seeded by the reachability witness, with the relaxation of an
/// unreachable foothold (the robot steps to the closest reachable point).
///   service plan_transition (reach_trajopt/PlanTransition)
///   publishes transition_trajectory (TransitionTrajectory) and, when the check ran,
///   reachability_result (ReachabilityResult)
/// x_f is the kinematic feasibility solution (Sec. III-B) with the swing sole on the foothold.
/// Bad requests (NaN, wrong sizes, unknown frame, empty contact set, a foothold in the air) get
/// success = false and the reason; the node keeps serving.
/// Parameters (private): ~config (YAML with sections contact, kinematic_feasibility, reach,
/// optionally walk and ocp; default config/biped.yaml of the package), ~default_horizon [s]
/// (t_f - t_0 when the request gives 0; default: the reach horizon), ~ground_tolerance [m].
/// The robot is read from the `robot_description` parameter (URDF text).

#include <memory>
#include <string>

#include <ros/package.h>
#include <ros/ros.h>

#include "reach_trajopt/PlanTransition.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/ocp/ocp_config.h"
#include "reach_trajopt/ocp/transition_ocp.h"
#include "reach_trajopt/ros/conversions.h"
#include "reach_trajopt/ros/service_requests.h"
#include "reach_trajopt/walk/standing_pose.h"
#include "reach_trajopt/walk/walking_experiment.h"

using namespace reach_trajopt;
namespace rb = reach_trajopt::ros_bridge;

namespace {

class TransitionOcpNode {
 public:
  TransitionOcpNode(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
    std::string urdf;
    if (!nh.getParam("robot_description", urdf) || urdf.empty())
      throw ReachError("parameter 'robot_description' (URDF text) is not set");
    std::string config_path = ros::package::getPath("reach_trajopt") + "/config/biped.yaml";
    pnh.getParam("config", config_path);
    pnh.getParam("ground_tolerance", limits_.ground_tolerance);
    model_ = RobotModel::fromUrdfString(urdf, {}, "robot_description");
    const YamlSection file = YamlSection::loadFile(config_path);
    contact_ = ContactConfig::fromYaml(file.section("contact"));
    reach_config_ = ReachConfig::fromYaml(file.section("reach"));
    const TransitionOcpConfig ocp_config = file.has("ocp")
                                               ? TransitionOcpConfig::fromYaml(file.section("ocp"))
                                               : TransitionOcpConfig{};
    default_horizon_ = reach_config_.horizon;
    pnh.getParam("default_horizon", default_horizon_);
    const WalkConfig walk =
        file.has("walk") ? WalkConfig::fromYaml(file.section("walk")) : WalkConfig{};
    feasibility_ = std::make_unique<KinematicFeasibility>(
        model_, KinematicFeasibilityConfig::fromYaml(file.section("kinematic_feasibility")),
        contact_);
    analyzer_ = std::make_unique<ReachabilityAnalyzer>(model_, contact_, reach_config_);
    ocp_ = std::make_unique<TransitionOcp>(model_, ocp_config, contact_);
    standing_q_ = standingConfiguration(*model_, walk.knee_bend, contact_.left_sole_frame);
    traj_pub_ = nh.advertise<reach_trajopt::TransitionTrajectory>("transition_trajectory", 10);
    reach_pub_ = nh.advertise<reach_trajopt::ReachabilityResult>("reachability_result", 10);
    server_ = nh.advertiseService("plan_transition", &TransitionOcpNode::plan, this);
  }

 private:
  bool plan(reach_trajopt::PlanTransition::Request& req,
            reach_trajopt::PlanTransition::Response& res) {
    const ros::Time t0 = req.header.stamp;
    res.reachability = rb::reachabilityVerdictMsg("not_checked", "", t0);
    try {
      const rb::FootholdRequest r = rb::parseFootholdRequest(
          *model_, contact_, req.header.frame_id, req.contact_mode, req.q, req.qd, req.foothold,
          req.swing_duration, default_horizon_, standing_q_, limits_);
      const KinematicFeasibilityResult ik =
          feasibility_->check(r.stance, r.stance_contact, r.target, r.q);
      const std::string swing_frame =
          r.stance == Side::kLeft ? contact_.right_sole_frame : contact_.left_sole_frame;
      TransitionRequest ocp;
      ocp.stance = r.stance;
      ocp.stance_pose = r.stance_contact.pose();
      ocp.swing_target = r.target.pose();
      ocp.horizon = r.duration;
      ocp.q0 = r.q;
      ocp.qd0 = r.qd;
      ocp.qf = ik.q_f;
      ocp.qdf = ik.qd_f;
      ocp.relaxation = req.allow_relaxation ? RelaxationMode::kAuto : RelaxationMode::kStrict;
      if (!ik.feasible) {
        if (!req.allow_relaxation)
          throw ReachError("kinematically infeasible foothold (" + ik.reason +
                           ") and allow_relaxation is false");
        ocp.relaxation = RelaxationMode::kRelaxed;  // land as close as the OCP can
      }
      if (req.check_reachability && ik.feasible) {
        ReachConfig config = reach_config_;
        const double s = r.duration / config.horizon;
        config.horizon = r.duration;
        config.window_start *= s;
        config.window_end *= s;
        ReachProblem p;
        p.mode = ContactMode::singleSupport(r.stance);
        p.q0 = r.q;
        p.qd0 = r.qd;
        p.qf = ik.q_f;
        p.qdf = ik.qd_f;
        p.footholds[static_cast<int>(r.stance)] = ocp.stance_pose;
        p.target = ocp.swing_target;
        const ReachResult check = analyzer_->check(p, config);
        res.reachability =
            rb::toReachabilityResultMsg(check, r, swing_frame, config.delta, t0, false);
        reach_pub_.publish(res.reachability);
        if (check.witness.valid) {  // seed the OCP with the witness path x_0 -> x_f
          ocp.seed.time = Eigen::Map<const Eigen::VectorXd>(
              check.witness.time.data(), static_cast<Eigen::Index>(check.witness.time.size()));
          ocp.seed.q = check.witness.q;
        }
      }
      const TransitionResult result = ocp_->solve(ocp);
      res.trajectory = rb::toTransitionTrajectoryMsg(
          result, *model_, {contact_.left_sole_frame, contact_.right_sole_frame}, t0);
      res.success = true;
      res.message = res.trajectory.status + ": " + res.trajectory.message;
      traj_pub_.publish(res.trajectory);
    } catch (const std::exception& e) {  // a bad request: answer with the reason, keep serving
      res.success = false;
      res.message = e.what();
      res.trajectory.header.stamp = t0;
      res.trajectory.header.frame_id = rb::kWorldFrame;
      res.trajectory.status = "error";
      res.trajectory.message = e.what();
      ROS_WARN("plan_transition: rejected: %s", e.what());
    }
    return true;
  }

  std::shared_ptr<const RobotModel> model_;
  ContactConfig contact_;
  ReachConfig reach_config_;
  double default_horizon_ = 0.08;
  rb::FootholdRequestLimits limits_;
  std::unique_ptr<KinematicFeasibility> feasibility_;
  std::unique_ptr<ReachabilityAnalyzer> analyzer_;
  std::unique_ptr<TransitionOcp> ocp_;
  Eigen::VectorXd standing_q_;
  ros::Publisher traj_pub_, reach_pub_;
  ros::ServiceServer server_;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "transition_ocp_node");
  ros::NodeHandle nh, pnh("~");
  try {
    TransitionOcpNode node(nh, pnh);
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("transition_ocp_node: %s", e.what());
    return 2;
  }
  return 0;
}
