/// \file transition_tracking.cpp
/// Swing references from an OCP trajectory (see the header).

#include "reach_trajopt/control/transition_tracking.h"

#include <algorithm>
#include <cmath>

namespace reach_trajopt {

void trackTransition(const RobotModel& m, Workspace& ws, Matrix6Xd& J, FrameId id,
                     const TransitionResult& tracked, double tt, WbcReference& ref) {
  constexpr double kDescent = 0.2;  // past the horizon: keep descending [m/s]
  const int last = static_cast<int>(tracked.time.size()) - 1;
  const int k = std::min(last, static_cast<int>(std::lround(tt / tracked.dt)));
  m.update(ws, tracked.q.col(k), tracked.qd.col(k));
  m.frameJacobian(ws, id, J);
  const Eigen::Isometry3d T = m.framePose(ws, id);
  ref.swing_position = T.translation();
  ref.swing_rotation = T.linear();
  ref.swing_velocity = (J * tracked.qd.col(k)).head<3>();
  ref.swing_acceleration = (J * tracked.qdd.col(k) + m.frameJdotQd(ws, id)).head<3>();
  if (tt > tracked.time[last]) {
    ref.swing_position.z() -= kDescent * (tt - tracked.time[last]);
    ref.swing_velocity = Eigen::Vector3d(0, 0, -kDescent);
    ref.swing_acceleration.setZero();
  } else {
    ref.q_ff = tracked.q.col(k);
    ref.qd_ff = tracked.qd.col(k);
    ref.qdd_ff = tracked.qdd.col(k);
  }
}

}  // namespace reach_trajopt
