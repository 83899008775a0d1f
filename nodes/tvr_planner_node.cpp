/// tvr_planner_node: the next contact location from the CoM state, by the TVR planner of
/// eq. (11) (docs/method.md Sec. 3 sign convention). At every switch into single support seen on
/// `com_state`, the measured CoM state is predicted to the nominal touchdown with the LIPM about
/// the stance sole (eq. 9-10), eq. (11) gives the foothold, and a ContactPlan (SS then DS) is
/// published on `contact_plan`.
///   subscribes: com_state (CenterOfMassState), contact_state (ContactState: sole poses)
///   publishes:  contact_plan (ContactPlan)
/// The walking loop's proposals (sim_node ~in_process false): the stateless service
/// propose_footstep (reach_trajopt/ProposeFootstep, planner/tvr_proposal.h), eq. (11) from the
/// request's measured CoM state with the request's LIPM height and bounds switch and ~config's
/// planner section (the same bits as the loop's own planner); publishes footsteps_proposed
/// (std_msgs/UInt64, latched: the proposals answered so far).
/// Parameters (private): ~config (YAML with sections planner and walk; default
/// config/biped.yaml of the package), ~policy (a walking policy, walk/walking_policy.h: its bounds
/// part switches the heuristic bounds), ~forward_speed [m/s] (desired CoM speed along x, drives
/// p_des of eq. 11). The LIPM height is the CoM height measured at the first message, as in the
/// walking loop.

#include <ros/package.h>
#include <ros/ros.h>
#include <std_msgs/UInt64.h>

#include <memory>
#include <string>

#include "reach_trajopt/ProposeFootstep.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/planner/tvr_proposal.h"
#include "reach_trajopt/ros/conversions.h"
#include "reach_trajopt/ros/node_setup.h"
#include "reach_trajopt/ros/tvr_proposal_msgs.h"
#include "reach_trajopt/walk/walking_experiment.h"

using namespace reach_trajopt;
namespace rb = reach_trajopt::ros_bridge;

namespace {

/// Plans one step per single-support phase from the latest messages.
class TvrPlannerNode {
 public:
  TvrPlannerNode(ros::NodeHandle& nh, const TvrConfig& tvr, const WalkConfig& walk)
      : tvr_(tvr), proposal_config_(tvr), walk_(walk) {
    plan_pub_ = nh.advertise<reach_trajopt::ContactPlan>("contact_plan", 10);
    proposed_pub_ = nh.advertise<std_msgs::UInt64>("footsteps_proposed", 1, true);
    propose_server_ =
        nh.advertiseService("propose_footstep", &TvrPlannerNode::proposeFootstep, this);
    // A switch into single support is seen only if no com_state message in between is dropped:
    // the simulation may publish faster than real time, in bursts, while this node waits for the
    // CPU (a queue of 10 lost the switch of a step under load). 10 s of sim time at 100 Hz.
    constexpr uint32_t kStateQueue = 1000;
    contact_sub_ = nh.subscribe("contact_state", kStateQueue, &TvrPlannerNode::onContact, this);
    com_sub_ = nh.subscribe("com_state", kStateQueue, &TvrPlannerNode::onCom, this);
  }

 private:
  // One proposal of the walking loop, from the request alone.
  bool proposeFootstep(reach_trajopt::ProposeFootstep::Request& req,
                       reach_trajopt::ProposeFootstep::Response& res) {
    return rb::answerOrReject(
        "propose_footstep",
        [&] {
          res = rb::toProposeFootstepResponseMsg(reach_trajopt::proposeFootstep(
              proposal_config_, rb::fromProposeFootstepRequestMsg(req)));
          std_msgs::UInt64 count;
          count.data = ++proposed_;
          proposed_pub_.publish(count);
        },
        [&](const std::string& reason) {
          res = rb::rejectedResponse<reach_trajopt::ProposeFootstep::Response>(reason);
        });
  }

  void onContact(const reach_trajopt::ContactState::ConstPtr& msg) { contact_ = msg; }

  void onCom(const reach_trajopt::CenterOfMassState::ConstPtr& msg) {
    try {
      if (!planner_) {
        tvr_.com_height = msg->position.z;  // the LIPM height is the measured CoM height
        planner_ = std::make_unique<TvrPlanner>(tvr_);
        com0_x_ = msg->position.x;
        start_time_ = msg->header.stamp.toSec();
      }
      const ContactMode mode = ContactMode::fromName(msg->contact_mode);
      const bool entering = mode.isSingleSupport() && mode != last_mode_;
      last_mode_ = mode;
      if (!entering || !contact_) return;
      plan(*msg, mode);
    } catch (const std::exception& e) {
      ROS_ERROR_THROTTLE(1.0, "tvr_planner_node: %s", e.what());
    }
  }

  void plan(const reach_trajopt::CenterOfMassState& com, const ContactMode& mode) {
    const Side stance = mode.stance();
    Eigen::Vector3d soles[2];
    if (contact_->sole_poses.size() != 2)
      throw RequestError("contact_state must carry the two sole poses (left, right)");
    for (int i = 0; i < 2; ++i) soles[i] = rb::fromPointMsg(contact_->sole_poses[i].position);
    LipmState now;
    now.p = rb::fromPointMsg(com.position).head<2>();
    now.pd = rb::fromVector3Msg(com.velocity).head<2>();
    const double t = com.header.stamp.toSec() - start_time_;
    const double T = walk_.single_support_duration;
    TvrInput in;
    const TvrStep step = planner_->planFromMeasured(
        now, soles[static_cast<int>(stance)].head<2>(), opposite(stance), t, T, com0_x_,
        walk_.forward_speed, 0.5 * (soles[0].y() + soles[1].y()), &in);
    plan_pub_.publish(rb::toContactPlanMsg(in, step, T, walk_.double_support_duration,
                                           soles[static_cast<int>(stance)].z(), com.header.stamp));
  }

  TvrConfig tvr_;
  const TvrConfig proposal_config_;  ///< ~config's planner section (propose_footstep)
  WalkConfig walk_;
  uint64_t proposed_ = 0;  ///< proposals answered by propose_footstep
  std::unique_ptr<TvrPlanner> planner_;
  ContactMode last_mode_ = ContactMode::doubleSupport();
  double com0_x_ = 0.0, start_time_ = 0.0;
  reach_trajopt::ContactState::ConstPtr contact_;
  ros::Publisher plan_pub_, proposed_pub_;
  ros::Subscriber contact_sub_, com_sub_;
  ros::ServiceServer propose_server_;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "tvr_planner_node");
  ros::NodeHandle nh, pnh("~");
  try {
    std::string config_path = ros::package::getPath("reach_trajopt") + "/config/biped.yaml";
    pnh.getParam("config", config_path);
    const YamlSection file = YamlSection::loadFile(config_path);
    TvrConfig tvr = TvrConfig::fromYaml(file.section("planner"));
    WalkConfig walk = file.has("walk") ? WalkConfig::fromYaml(file.section("walk")) : WalkConfig{};
    std::string policy;
    if (pnh.getParam("policy", policy)) walk.policy = WalkingPolicy::parse(policy);
    pnh.getParam("forward_speed", walk.forward_speed);
    walk.validate();
    tvr.heuristic_bounds = walk.policy.heuristic_bounds;
    TvrPlannerNode node(nh, tvr, walk);
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("tvr_planner_node: %s", e.what());
    return 2;
  }
  return 0;
}
