/// \file transition_tracking.cpp
/// Swing references from an OCP trajectory (see the header).

#include "reach_trajopt/control/transition_tracking.h"

#include <algorithm>
#include <cmath>

#include "reach_trajopt/control/swing_trajectory.h"

namespace reach_trajopt {

void trackTransition(const RobotModel& m, Workspace& ws, Matrix6Xd& J, FrameId id,
                     const TransitionResult& tracked, double tt, double touchdown_depth,
                     WbcReference& ref) {
  const int last = static_cast<int>(tracked.time.size()) - 1;
  const int k = std::min(last, static_cast<int>(std::lround(tt / tracked.dt)));
  m.update(ws, tracked.q.col(k), tracked.qd.col(k));
  m.frameJacobian(ws, id, J);
  const Eigen::Isometry3d T = m.framePose(ws, id);
  ref.swing_position = T.translation();
  ref.swing_rotation = T.linear();
  ref.swing_velocity = (J * tracked.qd.col(k)).head<3>();
  ref.swing_acceleration = (J * tracked.qdd.col(k) + m.frameJdotQd(ws, id)).head<3>();
  const double horizon = tracked.time[last];
  if (tt > horizon) {
    ref.swing_position.z() -=
        touchdown_depth + kLateTouchdownDescentSpeed * (tt - tracked.time[last]);
    ref.swing_velocity = Eigen::Vector3d(0, 0, -kLateTouchdownDescentSpeed);
    ref.swing_acceleration.setZero();
  } else {
    // The OCP lands the sole on the ground at the horizon with zero velocity; the reference
    // goes touchdown_depth below it by a minimum-jerk blend, so that contact is made by the
    // ground, not after the horizon by the late descent.
    if (horizon > 0.0) {
      const MinimumJerkBlend d = minimumJerkBlend(tt, 0.0, horizon);
      ref.swing_position.z() -= touchdown_depth * d.b;
      ref.swing_velocity.z() -= touchdown_depth * d.bd;
      ref.swing_acceleration.z() -= touchdown_depth * d.bdd;
    }
    ref.q_ff = tracked.q.col(k);
    ref.qd_ff = tracked.qd.col(k);
    ref.qdd_ff = tracked.qdd.col(k);
  }
}

}  // namespace reach_trajopt
