#include "reach_trajopt/sim/base_coordinates.h"

#include <cmath>

namespace reach_trajopt {

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
