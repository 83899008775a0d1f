#include "reach_trajopt/walk/standing_pose.h"

#include <algorithm>
#include <cmath>

namespace reach_trajopt {

Eigen::VectorXd standingConfiguration(const RobotModel& model, double knee_bend,
                                      const std::string& sole_frame, const RobotConfig& robot) {
  if (!model.floatingBase())
    throw ModelError("standingConfiguration needs a floating-base model: " + model.source());
  if (!std::isfinite(knee_bend)) throw RequestError("standingConfiguration: non-finite knee bend");
  // Every joint at 0, or the nearest limit when 0 is outside them.
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.nq())
                          .cwiseMax(model.positionLowerLimits())
                          .cwiseMin(model.positionUpperLimits());
  q.head(6).setZero();
  robot.checkJoints(model);
  for (const Side side : {Side::kLeft, Side::kRight}) {
    const LegJoints leg = robot.leg(side);
    for (const std::string* zero : {&leg.hip_yaw, &leg.hip_roll, &leg.ankle_roll})
      if (!zero->empty()) q[model.jointIndex(*zero)] = 0.0;
    q[model.jointIndex(leg.hip_pitch)] = -0.5 * knee_bend;
    q[model.jointIndex(leg.knee)] = knee_bend;
    q[model.jointIndex(leg.ankle_pitch)] = -0.5 * knee_bend;
  }
  Workspace ws(model);
  model.update(ws, q, Eigen::VectorXd::Zero(model.nq()));
  q[2] = -model.framePose(ws, model.frameId(sole_frame)).translation().z();
  return q;
}

}  // namespace reach_trajopt
