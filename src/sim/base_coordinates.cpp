#include "reach_trajopt/sim/base_coordinates.h"

#include <cmath>

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

BaseCoordinates::BaseCoordinates(const Eigen::Isometry3d& root_to_body)
    : root_to_body_(root_to_body) {
  requireFinite("BaseCoordinates: root_to_body", root_to_body.matrix());
}

void BaseCoordinates::toVirtual(const BaseBodyState& body, Eigen::Ref<Vector6d> q_b,
                                Eigen::Ref<Vector6d> qd_b) const {
  toVirtual(body, Eigen::Vector3d::Zero(), q_b, qd_b);
}

void BaseCoordinates::toVirtual(const BaseBodyState& body, const Eigen::Vector3d& reference_ypr,
                                Eigen::Ref<Vector6d> q_b, Eigen::Ref<Vector6d> qd_b) const {
  requireFinite("base position", body.position);
  requireFinite("base orientation", body.orientation.coeffs());
  requireFinite("base linear velocity", body.linear_velocity);
  requireFinite("base angular velocity", body.angular_velocity);
  const Eigen::Matrix3d R_body = body.orientation.normalized().toRotationMatrix();
  const Eigen::Matrix3d R_root = R_body * root_to_body_.linear().transpose();
  const Eigen::Vector3d r = R_root * root_to_body_.translation();  // root origin -> B, world
  const Eigen::Vector3d ypr = eulerFromRotation(R_root, reference_ypr);
  q_b.head<3>() = body.position - r;
  q_b.tail<3>() = ypr;
  qd_b.head<3>() = body.linear_velocity - body.angular_velocity.cross(r);
  qd_b.tail<3>() = eulerRatesFromAngularVelocity(ypr, body.angular_velocity);
}

BaseBodyState BaseCoordinates::fromVirtual(const Eigen::Ref<const Vector6d>& q_b,
                                           const Eigen::Ref<const Vector6d>& qd_b) const {
  requireFinite("virtual base coordinates q", q_b);
  requireFinite("virtual base velocities qd", qd_b);
  const Eigen::Vector3d ypr = q_b.tail<3>();
  const Eigen::Matrix3d R_root = rotationFromEuler(ypr);
  const Eigen::Vector3d r = R_root * root_to_body_.translation();
  BaseBodyState body;
  body.position = q_b.head<3>() + r;
  body.orientation = Eigen::Quaterniond(R_root * root_to_body_.linear()).normalized();
  body.angular_velocity = eulerRateMatrix(ypr) * qd_b.tail<3>();
  body.linear_velocity = qd_b.head<3>() + body.angular_velocity.cross(r);
  return body;
}

Vector6d BaseCoordinates::accelerationToVirtual(const Eigen::Ref<const Vector6d>& q_b,
                                                const Eigen::Ref<const Vector6d>& qd_b,
                                                const BaseBodyAcceleration& acc) const {
  const Eigen::Vector3d ypr = q_b.tail<3>();
  const Eigen::Vector3d ypr_dot = qd_b.tail<3>();
  const Eigen::Vector3d omega = eulerRateMatrix(ypr) * ypr_dot;
  const Eigen::Vector3d r = rotationFromEuler(ypr) * root_to_body_.translation();
  Vector6d qdd_b;
  qdd_b.head<3>() = acc.linear - acc.angular.cross(r) - omega.cross(omega.cross(r));
  qdd_b.tail<3>() =
      eulerRatesFromAngularVelocity(ypr, acc.angular - eulerRateMatrixDot(ypr, ypr_dot) * ypr_dot);
  return qdd_b;
}

BaseBodyAcceleration BaseCoordinates::accelerationFromVirtual(
    const Eigen::Ref<const Vector6d>& q_b, const Eigen::Ref<const Vector6d>& qd_b,
    const Eigen::Ref<const Vector6d>& qdd_b) const {
  const Eigen::Vector3d ypr = q_b.tail<3>();
  const Eigen::Vector3d ypr_dot = qd_b.tail<3>();
  const Eigen::Vector3d omega = eulerRateMatrix(ypr) * ypr_dot;
  const Eigen::Vector3d r = rotationFromEuler(ypr) * root_to_body_.translation();
  BaseBodyAcceleration acc;
  acc.angular = eulerRateMatrix(ypr) * qdd_b.tail<3>() + eulerRateMatrixDot(ypr, ypr_dot) * ypr_dot;
  acc.linear = qdd_b.head<3>() + acc.angular.cross(r) + omega.cross(omega.cross(r));
  return acc;
}

}  // namespace reach_trajopt
