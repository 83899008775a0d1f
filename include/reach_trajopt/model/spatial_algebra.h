#pragma once
/// \file spatial_algebra.h
/// The world-frame spatial algebra shared by the analytic derivatives (rnea_derivatives.h,
/// kinematic_derivatives.h): motion vectors [angular; linear] about the world origin, the cross
/// products of motion on motion and on force (Featherstone, Rigid Body Dynamics Algorithms,
/// 2008, Sec. 2.9), and one body's world pose and joint motion axis S from its parent's.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "reach_trajopt/model/model_tree.h"
#include "reach_trajopt/model/robot_model.h"

namespace reach_trajopt {

/// [x]: the cross-product matrix, [x] y = x x y.
inline Eigen::Matrix3d skew(const Eigen::Vector3d& x) {
  Eigen::Matrix3d m;
  m << 0.0, -x.z(), x.y(), x.z(), 0.0, -x.x(), -x.y(), x.x(), 0.0;
  return m;
}

/// m1 x m2 (motion on motion).
inline Vector6d crossMotion(const Vector6d& m1, const Vector6d& m2) {
  Vector6d r;
  r.head<3>() = m1.head<3>().cross(m2.head<3>());
  r.tail<3>() = m1.head<3>().cross(m2.tail<3>()) + m1.tail<3>().cross(m2.head<3>());
  return r;
}

/// m x* f (motion on force).
inline Vector6d crossForce(const Vector6d& m, const Vector6d& f) {
  Vector6d r;
  r.head<3>() = m.head<3>().cross(f.head<3>()) + m.tail<3>().cross(f.tail<3>());
  r.tail<3>() = m.head<3>().cross(f.tail<3>());
  return r;
}

/// Body `i` of the tree at joint position `q` [rad or m]: its world rotation and origin into
/// R_world[i], p_world[i] from its parent's entries (set before: bodies are ordered parent
/// first), and its joint's world motion axis S = [axis; p x axis] (revolute) or [0; axis]
/// (prismatic). R_world and p_world: indexable containers of Matrix3d and Vector3d.
template <class Rotations, class Origins>
void bodyWorldMotion(const Body& b, int i, double q, Rotations& R_world, Origins& p_world,
                     Vector6d& S) {
  Eigen::Matrix3d R;
  Eigen::Vector3d p;
  if (b.prismatic) {
    R = b.placement.linear();
    p = b.placement.translation() + b.placement.linear() * (b.axis * q);
  } else {
    R = b.placement.linear() * Eigen::AngleAxisd(q, b.axis).toRotationMatrix();
    p = b.placement.translation();
  }
  if (b.parent < 0) {
    R_world[i] = R;
    p_world[i] = p;
  } else {
    R_world[i] = R_world[b.parent] * R;
    p_world[i] = p_world[b.parent] + R_world[b.parent] * p;
  }
  const Eigen::Vector3d axis = R_world[i] * b.axis;
  if (b.prismatic) {
    S.head<3>().setZero();
    S.tail<3>() = axis;
  } else {
    S.head<3>() = axis;
    S.tail<3>() = p_world[i].cross(axis);
  }
}

}  // namespace reach_trajopt
