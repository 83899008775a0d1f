#pragma once
/// \file base_coordinates.h
/// The simulator's edge: conversions between a simulator's floating-base state (a body frame B
/// rigidly attached to the root link, its position, quaternion, and world-frame linear and
/// angular velocity, as Bullet's btMultiBody stores its base) and our six virtual coordinates
/// q_b = [x, y, z, yaw, pitch, roll] (robot_model.h), where (x, y, z) is the root link's
/// origin and its orientation is R = Rz(yaw) Ry(pitch) Rx(roll), with their time derivatives.
///
/// The Euler-angle maps themselves are the model's (model/euler_angles.h).
/// Nothing else in the library sees quaternions; this file is used only at the simulator edge.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/model/euler_angles.h"

namespace reach_trajopt {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// A simulator's floating base: body frame B (for Bullet, the root body's centre of mass with
/// its principal axes) in the world, velocities in world coordinates.
struct BaseBodyState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();               ///< origin of B [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< B -> world
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();        ///< of B's origin, world [m/s]
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();       ///< world [rad/s]
};

/// B's accelerations, world coordinates: d/dt of BaseBodyState's velocities.
struct BaseBodyAcceleration {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();   ///< classical acceleration of B's origin
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();  ///< omega_dot [rad/s^2]
};

/// Converts between a BaseBodyState and our virtual coordinates. `root_to_body` is the
/// constant pose of B in the root link's frame (rotation R_rb, offset c [m]).
class BaseCoordinates {
 public:
  explicit BaseCoordinates(const Eigen::Isometry3d& root_to_body = Eigen::Isometry3d::Identity());

  const Eigen::Isometry3d& rootToBody() const { return root_to_body_; }

  /// Our (q_b, qd_b), each size 6: [x, y, z, yaw, pitch, roll] and their rates. With a
  /// `reference_ypr`, yaw and roll are unwrapped toward it (see eulerFromRotation).
  /// Throws ReachError at gimbal lock or on non-finite input.
  void toVirtual(const BaseBodyState& body, Eigen::Ref<Vector6d> q_b,
                 Eigen::Ref<Vector6d> qd_b) const;
  void toVirtual(const BaseBodyState& body, const Eigen::Vector3d& reference_ypr,
                 Eigen::Ref<Vector6d> q_b, Eigen::Ref<Vector6d> qd_b) const;
  /// The simulator's base state of our (q_b, qd_b). Throws ReachError on non-finite input.
  BaseBodyState fromVirtual(const Eigen::Ref<const Vector6d>& q_b,
                            const Eigen::Ref<const Vector6d>& qd_b) const;

  /// Our qdd_b at the state (q_b, qd_b) from B's world accelerations (exact, no dt involved):
  ///   ypr_ddot = E^-1 (omega_dot - Edot ypr_dot),
  ///   p_ddot = a_B - omega_dot x r - omega x (omega x r),  r = R c.
  Vector6d accelerationToVirtual(const Eigen::Ref<const Vector6d>& q_b,
                                 const Eigen::Ref<const Vector6d>& qd_b,
                                 const BaseBodyAcceleration& acc) const;
  /// The inverse map: B's world accelerations from our (q_b, qd_b, qdd_b).
  BaseBodyAcceleration accelerationFromVirtual(const Eigen::Ref<const Vector6d>& q_b,
                                               const Eigen::Ref<const Vector6d>& qd_b,
                                               const Eigen::Ref<const Vector6d>& qdd_b) const;

 private:
  Eigen::Isometry3d root_to_body_;
};

}  // namespace reach_trajopt
