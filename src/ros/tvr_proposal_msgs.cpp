/// \file tvr_proposal_msgs.cpp
/// The propose_footstep service's conversions (see the header).

#include "reach_trajopt/ros/tvr_proposal_msgs.h"

#include <cmath>
#include <string>
#include <vector>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/ros/conversions.h"
#include "reach_trajopt/ros/footstep_plan_msgs.h"

namespace reach_trajopt {
namespace ros_bridge {

namespace {

std::vector<double> pair(const Eigen::Vector2d& v) { return {v.x(), v.y()}; }

double finiteNumber(double v, const std::string& field) { return finiteVector({v}, 1, field)[0]; }

}  // namespace

reach_trajopt::ProposeFootstep::Request toProposeFootstepRequestMsg(const TvrProposalRequest& r,
                                                                    const ros::Time& t0) {
  reach_trajopt::ProposeFootstep::Request m;
  m.header.stamp = t0;
  m.header.frame_id = kWorldFrame;
  m.com = {r.measured.p.x(), r.measured.p.y(), r.measured.pd.x(), r.measured.pd.y()};
  m.stance = pair(r.stance);
  m.swing = r.swing == Side::kLeft ? "left" : "right";
  m.time = r.time;
  m.remaining = r.remaining;
  m.x_start = r.x_start;
  m.forward_speed = r.forward_speed;
  m.y_mid = r.y_mid;
  m.com_height = r.com_height;
  m.heuristic_bounds = r.heuristic_bounds;
  return m;
}

TvrProposalRequest fromProposeFootstepRequestMsg(const reach_trajopt::ProposeFootstep::Request& m) {
  TvrProposalRequest r;
  const Eigen::VectorXd com = finiteVector(m.com, 4, "com");
  r.measured.p = com.head<2>();
  r.measured.pd = com.tail<2>();
  r.stance = finiteVector(m.stance, 2, "stance");
  if (m.swing != "left" && m.swing != "right")
    throw RequestError("swing: expected 'left' or 'right', got '" + m.swing + "'");
  r.swing = m.swing == "left" ? Side::kLeft : Side::kRight;
  r.time = finiteNumber(m.time, "time");
  r.remaining = finiteNumber(m.remaining, "remaining");
  if (r.remaining < 0.0) throw RequestError("remaining: must be >= 0");
  r.x_start = finiteNumber(m.x_start, "x_start");
  r.forward_speed = finiteNumber(m.forward_speed, "forward_speed");
  r.y_mid = finiteNumber(m.y_mid, "y_mid");
  r.com_height = finiteNumber(m.com_height, "com_height");
  if (!(r.com_height > 0.0)) throw RequestError("com_height: must be > 0");
  r.heuristic_bounds = m.heuristic_bounds;
  return r;
}

reach_trajopt::ProposeFootstep::Response toProposeFootstepResponseMsg(const TvrProposal& p) {
  reach_trajopt::ProposeFootstep::Response m;
  m.success = true;
  m.alpha_tvr = pair(p.step.alpha_tvr);
  m.alpha = pair(p.step.alpha);
  m.offset = pair(p.step.offset);
  m.com_velocity_used = pair(p.step.com_velocity_used);
  m.speed_clipped = p.step.speed_clipped;
  m.offset_clipped = p.step.offset_clipped;
  m.predicted_com = {p.input.com.p.x(), p.input.com.p.y(), p.input.com.pd.x(), p.input.com.pd.y()};
  m.p_des = pair(p.input.p_des);
  return m;
}

TvrProposal fromProposeFootstepResponseMsg(const reach_trajopt::ProposeFootstep::Response& m,
                                           const TvrProposalRequest& request) {
  TvrProposal p;
  p.step.alpha_tvr = responseVector("propose_footstep", m.alpha_tvr, 2, "alpha_tvr");
  p.step.alpha = responseVector("propose_footstep", m.alpha, 2, "alpha");
  p.step.offset = responseVector("propose_footstep", m.offset, 2, "offset");
  p.step.com_velocity_used =
      responseVector("propose_footstep", m.com_velocity_used, 2, "com_velocity_used");
  p.step.speed_clipped = m.speed_clipped;
  p.step.offset_clipped = m.offset_clipped;
  const Eigen::VectorXd com =
      responseVector("propose_footstep", m.predicted_com, 4, "predicted_com");
  p.input.com.p = com.head<2>();
  p.input.com.pd = com.tail<2>();
  p.input.p_des = responseVector("propose_footstep", m.p_des, 2, "p_des");
  p.input.stance = request.stance;
  p.input.stance_yaw = 0.0;
  p.input.swing = request.swing;
  return p;
}

}  // namespace ros_bridge
}  // namespace reach_trajopt
