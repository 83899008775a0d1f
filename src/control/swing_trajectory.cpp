#include "reach_trajopt/control/swing_trajectory.h"

#include <cmath>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {
namespace {
constexpr double kLateDescentSpeed = 0.2;  // [m/s] after the nominal end, until contact
}

SwingTrajectory::SwingTrajectory(const Eigen::Vector3d& start, const Eigen::Vector3d& target,
                                 double duration, double apex_height, double touchdown_depth)
    : start_(start),
      target_(target),
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

void SwingTrajectory::retarget(const Eigen::Vector3d& target) {
  requireFinite("SwingTrajectory: target", target);
  target_ = target;
}

SwingSample SwingTrajectory::sample(double t) const {
  const Eigen::Vector3d end = target_ - Eigen::Vector3d(0, 0, depth_);
  SwingSample out;
  if (t >= duration_) {
    out.position = end - Eigen::Vector3d(0, 0, kLateDescentSpeed * (t - duration_));
    out.velocity = Eigen::Vector3d(0, 0, -kLateDescentSpeed);
    out.acceleration.setZero();
    return out;
  }
  const double T = duration_;
  const double s = std::max(0.0, t) / T;
  // Minimum-jerk blend and its derivatives (per second).
  const double b = s * s * s * (10 - 15 * s + 6 * s * s);
  const double bd = 30 * s * s * (1 - s) * (1 - s) / T;
  const double bdd = 60 * s * (1 - s) * (1 - 2 * s) / (T * T);
  // Bump 64 h s^3 (1-s)^3.
  const double u = s * (1 - s);
  const double z = 64 * apex_ * u * u * u;
  const double zd = 64 * apex_ * 3 * u * u * (1 - 2 * s) / T;
  const double zdd = 64 * apex_ * (6 * u * (1 - 2 * s) * (1 - 2 * s) - 6 * u * u) / (T * T);
  out.position = start_ + b * (end - start_) + Eigen::Vector3d(0, 0, z);
  out.velocity = bd * (end - start_) + Eigen::Vector3d(0, 0, zd);
  out.acceleration = bdd * (end - start_) + Eigen::Vector3d(0, 0, zdd);
  return out;
}

}  // namespace reach_trajopt
