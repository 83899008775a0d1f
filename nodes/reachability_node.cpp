/// reachability_node: the whole-body reachability check of the next foothold (paper Sec. III,
/// eq. (13)-(21), Prop. 1-2) as a ROS service.
///   service check_reachability (reach_trajopt/CheckReachability)
///   publishes reachability_result (ReachabilityResult) and reachability_markers (MarkerArray)
/// x_f is the kinematic feasibility solution (Sec. III-B) with the swing sole on the foothold;
/// an infeasible foothold is answered "unreachable" with the IK's reason. Bad requests (NaN,
/// wrong sizes, unknown frame, empty contact set, a foothold in the air) get success = false
/// and the reason; the node keeps serving.
/// Parameters (private): ~config (YAML with sections contact, kinematic_feasibility, reach and
/// optionally walk; default config/biped.yaml of the package), ~ground_tolerance [m, 0.02].
/// The robot is read from the `robot_description` parameter (URDF text).

#include <memory>
#include <string>

#include <ros/package.h>
#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

#include "reach_trajopt/CheckReachability.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/ros/conversions.h"
#include "reach_trajopt/ros/markers.h"
#include "reach_trajopt/ros/service_requests.h"
#include "reach_trajopt/walk/standing_pose.h"
#include "reach_trajopt/walk/walking_experiment.h"

using namespace reach_trajopt;
namespace rb = reach_trajopt::ros_bridge;

namespace {

class ReachabilityNode {
 public:
  ReachabilityNode(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
    std::string urdf;
    if (!nh.getParam("robot_description", urdf) || urdf.empty())
      throw ReachError("parameter 'robot_description' (URDF text) is not set");
    std::string config_path = ros::package::getPath("reach_trajopt") + "/config/biped.yaml";
    pnh.getParam("config", config_path);
    pnh.getParam("ground_tolerance", limits_.ground_tolerance);
    model_ = RobotModel::fromUrdfString(urdf, {}, "robot_description");
    const YamlSection file = YamlSection::loadFile(config_path);
    contact_ = ContactConfig::fromYaml(file.section("contact"));
    config_ = ReachConfig::fromYaml(file.section("reach"));
    const WalkConfig walk =
        file.has("walk") ? WalkConfig::fromYaml(file.section("walk")) : WalkConfig{};
    feasibility_ = std::make_unique<KinematicFeasibility>(
        model_, KinematicFeasibilityConfig::fromYaml(file.section("kinematic_feasibility")),
        contact_);
    analyzer_ = std::make_unique<ReachabilityAnalyzer>(model_, contact_, config_);
    standing_q_ = standingConfiguration(*model_, walk.knee_bend, contact_.left_sole_frame);
    result_pub_ = nh.advertise<reach_trajopt::ReachabilityResult>("reachability_result", 10);
    marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("reachability_markers", 10);
    server_ = nh.advertiseService("check_reachability", &ReachabilityNode::check, this);
  }

 private:
  bool check(reach_trajopt::CheckReachability::Request& req,
             reach_trajopt::CheckReachability::Response& res) {
    const ros::Time t0 = req.header.stamp;
    try {
      const rb::FootholdRequest r = rb::parseFootholdRequest(
          *model_, contact_, req.header.frame_id, req.contact_mode, req.q, req.qd, req.foothold,
          req.swing_duration, config_.horizon, standing_q_, limits_);
      ReachConfig config = config_;
      if (req.swing_duration > 0.0) {  // keep the window at the same fractions of the horizon
        const double s = r.duration / config.horizon;
        config.horizon = r.duration;
        config.window_start *= s;
        config.window_end *= s;
      }
      if (req.forward_samples > 0) config.initial_samples = static_cast<int>(req.forward_samples);
      if (req.seed > 0) config.seed = req.seed;
      config.validate();
      const KinematicFeasibilityResult ik =
          feasibility_->check(r.stance, r.stance_contact, r.target, r.q);
      const std::string swing_frame =
          r.stance == Side::kLeft ? contact_.right_sole_frame : contact_.left_sole_frame;
      if (!ik.feasible) {
        res.result = rb::reachabilityVerdictMsg(
            "unreachable", "kinematically infeasible foothold: " + ik.reason, t0);
        res.result.swing_frame = swing_frame;
        res.result.foothold = rb::toPointMsg(r.target.position);
      } else {
        ReachProblem p;
        p.mode = ContactMode::singleSupport(r.stance);
        p.q0 = r.q;
        p.qd0 = r.qd;
        p.qf = ik.q_f;
        p.qdf = ik.qd_f;
        p.footholds[static_cast<int>(r.stance)] = r.stance_contact.pose();
        p.target = r.target.pose();
        const ReachResult result = analyzer_->check(p, config);
        res.result = rb::toReachabilityResultMsg(result, r, swing_frame, config.delta, t0,
                                                 req.return_samples);
      }
      res.success = true;
      res.message = res.result.verdict + ": " + res.result.message;
      result_pub_.publish(res.result);
      marker_pub_.publish(rb::reachabilityMarkers(res.result));
    } catch (const std::exception& e) {  // a bad request: answer with the reason, keep serving
      res.success = false;
      res.message = e.what();
      res.result = rb::reachabilityVerdictMsg("error", e.what(), t0);
      ROS_WARN("check_reachability: rejected: %s", e.what());
    }
    return true;
  }

  std::shared_ptr<const RobotModel> model_;
  ContactConfig contact_;
  ReachConfig config_;
  rb::FootholdRequestLimits limits_;
  std::unique_ptr<KinematicFeasibility> feasibility_;
  std::unique_ptr<ReachabilityAnalyzer> analyzer_;
  Eigen::VectorXd standing_q_;
  ros::Publisher result_pub_, marker_pub_;
  ros::ServiceServer server_;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "reachability_node");
  ros::NodeHandle nh, pnh("~");
  try {
    ReachabilityNode node(nh, pnh);
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("reachability_node: %s", e.what());
    return 2;
  }
  return 0;
}
