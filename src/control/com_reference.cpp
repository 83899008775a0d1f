/// \file com_reference.cpp
/// The LIPM CoM reference of the walking loop (see the header).

#include "reach_trajopt/control/com_reference.h"

#include <cmath>

namespace reach_trajopt {

LipmComReference::LipmComReference(const Lipm& lipm, const Eigen::Vector3d& standing_com)
    : lipm_(lipm), standing_com_(standing_com) {}

void LipmComReference::startSingleSupport(const LipmState& com, const Eigen::Vector2d& stance) {
  com_ = com;
  pivot_from_ = pivot_to_ = stance;
}

void LipmComReference::startDoubleSupport(const LipmState& com, const Eigen::Vector2d& from,
                                          const Eigen::Vector2d& to) {
  com_ = com;
  pivot_from_ = from;
  pivot_to_ = to;
}

void LipmComReference::advance(double dt, double transfer, WbcReference& ref) {
  const Eigen::Vector2d pivot = (1.0 - transfer) * pivot_from_ + transfer * pivot_to_;
  const Eigen::Vector2d acc = lipm_.acceleration(com_.p, pivot);
  ref.com_acceleration = Eigen::Vector3d(acc.x(), acc.y(), 0.0);
  com_.p += dt * com_.pd + 0.5 * dt * dt * acc;
  com_.pd += dt * acc;
  fill(ref);
}

void LipmComReference::steerCapturePoint(double dt, const Eigen::Vector2d& target, double gain,
                                         const Eigen::Vector2d& support_min,
                                         const Eigen::Vector2d& support_max, WbcReference& ref) {
  const double omega = lipm_.omega();
  const Eigen::Vector2d xi = com_.p + com_.pd / omega;
  Eigen::Vector2d pivot = xi;
  for (int axis = 0; axis < 2; ++axis)
    if (std::isfinite(target[axis])) pivot[axis] += (gain / omega) * (xi[axis] - target[axis]);
  pivot = pivot.cwiseMax(support_min).cwiseMin(support_max);
  pivot_from_ = pivot_to_ = pivot;
  advance(dt, 1.0, ref);
}

void LipmComReference::hold(WbcReference& ref) {
  ref.com_acceleration.setZero();
  com_.p = standing_com_.head<2>();
  com_.pd.setZero();
  fill(ref);
}

void LipmComReference::fill(WbcReference& ref) const {
  ref.com_position = Eigen::Vector3d(com_.p.x(), com_.p.y(), standing_com_.z());
  ref.com_velocity = Eigen::Vector3d(com_.pd.x(), com_.pd.y(), 0.0);
}

}  // namespace reach_trajopt
