/// \file transition_tracking.cpp
/// Swing references from an OCP trajectory (see the header).

#include "reach_trajopt/control/transition_tracking.h"

#include <algorithm>
#include <cmath>

#include "reach_trajopt/control/minimum_jerk.h"

namespace reach_trajopt {

void trackTransition(const RobotModel& m, Workspace& ws, Matrix6Xd& J, FrameId id,
                     const TransitionResult& tracked, double tt, const TouchdownAim& aim,
                     WbcReference& ref) {
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
  // The last `aim.blend` seconds lower the sole to `aim.depth` below the trajectory's
  // landing, so that it touches down by contact on time.
  const double blend = std::min(aim.blend, tracked.time[last]);
  if (blend > 0.0) {
    const MinimumJerkBlend b = minimumJerk(tt, tracked.time[last] - blend, blend);
    ref.swing_position.z() -= aim.depth * b.b;
    ref.swing_velocity.z() -= aim.depth * b.bd;
    ref.swing_acceleration.z() -= aim.depth * b.bdd;
  }
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
