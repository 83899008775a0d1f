#include "reach_trajopt/walk/standing_pose.h"

namespace reach_trajopt {

Eigen::VectorXd standingConfiguration(const RobotModel& model, double knee_bend,
                                      const std::string& sole_frame, const LegJointNames& names) {
  if (!model.floatingBase())
    throw ModelError("standingConfiguration needs a floating-base model: " + model.source());
  if (!std::isfinite(knee_bend)) throw RequestError("standingConfiguration: non-finite knee bend");
  Eigen::VectorXd q = model.neutralConfiguration();
  q.head(6).setZero();
  for (const std::string& prefix : {names.left_prefix, names.right_prefix}) {
    q[model.jointIndex(prefix + names.hip_pitch)] = -0.5 * knee_bend;
    q[model.jointIndex(prefix + names.knee)] = knee_bend;
    q[model.jointIndex(prefix + names.ankle_pitch)] = -0.5 * knee_bend;
  }
  Workspace ws(model);
  model.update(ws, q, Eigen::VectorXd::Zero(model.nq()));
  q[2] = -model.framePose(ws, model.frameId(sole_frame)).translation().z();
  return q;
}

}  // namespace reach_trajopt
