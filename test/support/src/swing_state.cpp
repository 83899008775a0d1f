/// \file swing_state.cpp
/// A mid-swing single-support state (see the header).

#include "reach_trajopt/testing/swing_state.h"

#include <Eigen/LU>
#include <Eigen/QR>
#include <vector>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

RobotState swingState(std::shared_ptr<const RobotModel> model,
                      const KinematicFeasibilityConfig& kf_config, const ContactConfig& contact,
                      Side stance, const FlatContact& stance_contact,
                      const Eigen::Vector3d& swing_position, double swing_yaw,
                      const Eigen::Vector3d& swing_velocity, const Eigen::VectorXd& q_init) {
  requireFinite("swingState: swing_position", swing_position);
  requireFinite("swingState: swing_velocity", swing_velocity);
  // The IK puts the pelvis at pelvis_height above the mean sole height: lower it by half the
  // swing height so the pelvis stays where it is when both soles are on the ground.
  KinematicFeasibilityConfig cfg = kf_config;
  cfg.pelvis_height -= 0.5 * (swing_position.z() - stance_contact.position.z());
  const KinematicFeasibility kf(model, cfg, contact);
  FlatContact swing;
  swing.position = swing_position;
  swing.yaw = swing_yaw;
  const KinematicFeasibilityResult r = kf.check(stance, stance_contact, swing, q_init);
  if (!r.feasible) throw ReachError("swingState: the swing pose is infeasible: " + r.reason);
  const RobotModel& m = *model;
  RobotState s;
  s.q = r.q_f;
  s.qd = Eigen::VectorXd::Zero(m.nq());
  Workspace ws(m);
  m.update(ws, s.q, s.qd);
  const FrameId sw = m.frameId(contact.soleFrame(opposite(stance)));
  Matrix6Xd J(6, m.nq());
  m.frameJacobian(ws, sw, J);
  // The swing leg: actuated columns that move the swing sole.
  std::vector<int> cols;
  for (int i = m.nq() - m.nu(); i < m.nq(); ++i)
    if (J.col(i).norm() > 0.0) cols.push_back(i);
  const int k = static_cast<int>(cols.size());
  Eigen::MatrixXd Js(6, k);
  for (int c = 0; c < k; ++c) Js.col(c) = J.col(cols[c]);
  Vector6d v = Vector6d::Zero();
  v.head<3>() = swing_velocity;
  const Eigen::VectorXd qd_leg = Js.completeOrthogonalDecomposition().solve(v);
  if ((Js * qd_leg - v).norm() > 1e-9 * (1.0 + v.norm()))
    throw ReachError("swingState: the swing leg cannot produce the requested sole velocity");
  for (int c = 0; c < k; ++c) s.qd[cols[c]] = qd_leg[c];
  return s;
}

}  // namespace reach_trajopt
