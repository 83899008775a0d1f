/// \file euler_angles.cpp
/// ZYX Euler angles of the floating base (see the header).

#include "reach_trajopt/model/euler_angles.h"

#include <Eigen/Geometry>
#include <cmath>
#include <sstream>

namespace reach_trajopt {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;
constexpr double kGimbalLockCos = 1e-12;

// The angle a + 2 pi k closest to `reference`.
double unwrapToward(double angle, double reference) {
  return reference + std::remainder(angle - reference, kTwoPi);
}

void requireNoGimbalLock(double pitch) {
  if (std::abs(std::cos(pitch)) < kGimbalLockCos) {
    std::ostringstream os;
    os << "base orientation at gimbal lock (pitch = " << pitch
       << " rad): Euler-angle rates are undefined";
    throw ReachError(os.str());
  }
}

}  // namespace

Eigen::Matrix3d rotationFromEuler(const Eigen::Vector3d& ypr) {
  return (Eigen::AngleAxisd(ypr[0], Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(ypr[1], Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(ypr[2], Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Vector3d eulerFromRotation(const Eigen::Matrix3d& R) {
  requireFinite("eulerFromRotation: R", R);
  // R = Rz Ry Rx: R(2,0) = -sin(pitch), R(1,0)/R(0,0) = tan(yaw), R(2,1)/R(2,2) = tan(roll).
  const double pitch = std::atan2(-R(2, 0), std::hypot(R(0, 0), R(1, 0)));
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  const double roll = std::atan2(R(2, 1), R(2, 2));
  return Eigen::Vector3d(yaw, pitch, roll);
}

Eigen::Vector3d eulerFromRotation(const Eigen::Matrix3d& R, const Eigen::Vector3d& reference) {
  requireFinite("eulerFromRotation: reference", reference);
  Eigen::Vector3d ypr = eulerFromRotation(R);
  ypr[0] = unwrapToward(ypr[0], reference[0]);
  ypr[2] = unwrapToward(ypr[2], reference[2]);
  return ypr;
}

Eigen::Matrix3d eulerRateMatrix(const Eigen::Vector3d& ypr) {
  const double cy = std::cos(ypr[0]), sy = std::sin(ypr[0]);
  const double cp = std::cos(ypr[1]), sp = std::sin(ypr[1]);
  Eigen::Matrix3d E;
  E << 0.0, -sy, cy * cp,  //
      0.0, cy, sy * cp,    //
      1.0, 0.0, -sp;
  return E;
}

Eigen::Matrix3d eulerRateMatrixDot(const Eigen::Vector3d& ypr, const Eigen::Vector3d& ypr_dot) {
  const double cy = std::cos(ypr[0]), sy = std::sin(ypr[0]);
  const double cp = std::cos(ypr[1]), sp = std::sin(ypr[1]);
  const double yd = ypr_dot[0], pd = ypr_dot[1];
  Eigen::Matrix3d Ed;
  Ed << 0.0, -cy * yd, -sy * cp * yd - cy * sp * pd,  //
      0.0, -sy * yd, cy * cp * yd - sy * sp * pd,     //
      0.0, 0.0, -cp * pd;
  return Ed;
}

Eigen::Vector3d eulerRatesFromAngularVelocity(const Eigen::Vector3d& ypr,
                                              const Eigen::Vector3d& omega_world) {
  requireNoGimbalLock(ypr[1]);
  const double cy = std::cos(ypr[0]), sy = std::sin(ypr[0]);
  const double cp = std::cos(ypr[1]), sp = std::sin(ypr[1]);
  // Closed-form E^-1: the x, y rows give roll_dot and pitch_dot, the z row then yaw_dot.
  const double roll_dot = (cy * omega_world[0] + sy * omega_world[1]) / cp;
  const double pitch_dot = -sy * omega_world[0] + cy * omega_world[1];
  const double yaw_dot = omega_world[2] + sp * roll_dot;
  return Eigen::Vector3d(yaw_dot, pitch_dot, roll_dot);
}

}  // namespace reach_trajopt
