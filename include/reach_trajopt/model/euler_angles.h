#pragma once
/// \file euler_angles.h
/// The floating base's orientation coordinates of RobotModel: q_b = [yaw, pitch, roll] with
/// R = Rz(yaw) Ry(pitch) Rx(roll), and the map between their rates and the angular velocity.
///
/// Angular velocity and Euler rates (ZYX): omega_world = E(yaw, pitch) [yawd; pitchd; rolld],
///   E = [ e_z | Rz(yaw) e_y | Rz(yaw) Ry(pitch) e_x ]
///     = [0 -sin(yaw) cos(yaw) cos(pitch); 0 cos(yaw) sin(yaw) cos(pitch); 1 0 -sin(pitch)],
/// singular at pitch = +-pi/2 (gimbal lock), where the rates are undefined: ReachError.

#include <Eigen/Core>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

/// Rotation R = Rz(yaw) Ry(pitch) Rx(roll); ypr = [yaw, pitch, roll] [rad].
Eigen::Matrix3d rotationFromEuler(const Eigen::Vector3d& ypr);

/// ZYX Euler angles [yaw, pitch, roll] of a rotation, pitch in [-pi/2, pi/2]. With a
/// `reference` (e.g. the previous sample), yaw and roll are shifted by multiples of 2 pi to be
/// the closest to the reference ones, so a trajectory stays continuous across +-pi.
/// Throws ReachError when R has non-finite entries.
Eigen::Vector3d eulerFromRotation(const Eigen::Matrix3d& R);
Eigen::Vector3d eulerFromRotation(const Eigen::Matrix3d& R, const Eigen::Vector3d& reference);

/// E(ypr) with omega_world = E ypr_dot [rad/s] (see the file comment).
Eigen::Matrix3d eulerRateMatrix(const Eigen::Vector3d& ypr);
/// dE/dt at (ypr, ypr_dot), so omega_dot = E ypr_ddot + Edot ypr_dot.
Eigen::Matrix3d eulerRateMatrixDot(const Eigen::Vector3d& ypr, const Eigen::Vector3d& ypr_dot);
/// ypr_dot = E^-1 omega_world. Throws ReachError at gimbal lock (|cos(pitch)| < 1e-12).
Eigen::Vector3d eulerRatesFromAngularVelocity(const Eigen::Vector3d& ypr,
                                              const Eigen::Vector3d& omega_world);

}  // namespace reach_trajopt
