#include "reach_trajopt/control/swing_trajectory.h"

#include <algorithm>
#include <cmath>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/control/minimum_jerk.h"

namespace reach_trajopt {
namespace {
constexpr double kLateDescentSpeed = 0.2;  // [m/s] after the nominal end, until contact
}

SwingTrajectory::SwingTrajectory(const Eigen::Vector3d& start, const Eigen::Vector3d& target,
                                 double duration, double apex_height, double touchdown_depth)
    : start_(start),
      target_(target),
      first_target_(target),
      duration_(duration),
      apex_(apex_height),
      depth_(touchdown_depth) {
  requireFinite("SwingTrajectory: start", start);
  requireFinite("SwingTrajectory: target", target);
  if (!(duration > 0.0) || !std::isfinite(duration))
    throw RequestError("SwingTrajectory: duration must be > 0 s");
  if (!(apex_height >= 0.0) || !(touchdown_depth >= 0.0))
    throw RequestError("SwingTrajectory: apex height and touchdown depth must be >= 0 m");
}

void SwingTrajectory::retarget(const Eigen::Vector3d& target, double t) {
  requireFinite("SwingTrajectory: target", target);
  if (!std::isfinite(t)) throw RequestError("SwingTrajectory: retarget time must be finite");
  if (t <= 0.0 && corrections_.empty()) {
    first_target_ = target;  // nothing moved yet: the blend from lift-off goes there
  } else if (t >= duration_) {
    first_target_ += target - target_;  // no time left to blend: straight to it
  } else {
    corrections_.push_back({t, target - target_});
  }
  target_ = target;
}

SwingSample SwingTrajectory::sample(double t) const {
  const Eigen::Vector3d depth(0, 0, depth_);
  SwingSample out;
  if (t >= duration_) {
    out.position = target_ - depth - Eigen::Vector3d(0, 0, kLateDescentSpeed * (t - duration_));
    out.velocity = Eigen::Vector3d(0, 0, -kLateDescentSpeed);
    out.acceleration.setZero();
    return out;
  }
  const double T = duration_;
  const double s = std::max(0.0, t) / T;
  const MinimumJerkBlend m = minimumJerk(t, 0.0, T);
  // Bump 64 h s^3 (1-s)^3.
  const double u = s * (1 - s);
  const double z = 64 * apex_ * u * u * u;
  const double zd = 64 * apex_ * 3 * u * u * (1 - 2 * s) / T;
  const double zdd = 64 * apex_ * (6 * u * (1 - 2 * s) * (1 - 2 * s) - 6 * u * u) / (T * T);
  const Eigen::Vector3d end = first_target_ - depth;
  out.position = start_ + m.b * (end - start_) + Eigen::Vector3d(0, 0, z);
  out.velocity = m.bd * (end - start_) + Eigen::Vector3d(0, 0, zd);
  out.acceleration = m.bdd * (end - start_) + Eigen::Vector3d(0, 0, zdd);
  for (const Correction& c : corrections_) {
    const MinimumJerkBlend mc = minimumJerk(t, c.time, T - c.time);
    out.position += mc.b * c.change;
    out.velocity += mc.bd * c.change;
    out.acceleration += mc.bdd * c.change;
  }
  return out;
}

}  // namespace reach_trajopt
