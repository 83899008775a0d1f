#pragma once
/// \file model_tree.h
/// The robot's kinematic tree flattened from the KDL tree into arrays the recursive algorithms
/// walk in order: one Body per degree of freedom (links joined by fixed joints are merged into
/// the body that carries them), and one Frame per URDF link. Built once by RobotModel; the
/// simulator and the ROS layer read it (link frames for TF, inertias for Bullet).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace reach_trajopt {

/// A rigid body moved by one 1-dof joint (revolute or prismatic) relative to its parent body.
/// Pose in its parent: T(q) = placement * Rot(axis, q)  or  placement * Trans(axis * q).
struct Body {
  int parent = -1;              ///< parent body index, -1 = world
  Eigen::Isometry3d placement;  ///< joint frame in the parent body frame at q = 0
  Eigen::Vector3d axis;         ///< unit joint axis in this body's frame
  bool prismatic = false;
  double mass = 0.0;               ///< [kg], fixed children included
  Eigen::Vector3d com;             ///< centre of mass in this body's frame [m]
  Eigen::Matrix3d inertia_origin;  ///< rotational inertia about the body origin [kg m^2]
  std::vector<int> support;        ///< this body and its ancestors, leaf to root
};

/// A named frame rigidly attached to a body (a URDF link, e.g. a sole).
struct Frame {
  std::string name;
  int body = -1;                ///< -1: attached to the world (fixed-base root links)
  Eigen::Isometry3d placement;  ///< frame pose in the body frame
};

struct ModelTree {
  std::vector<Body> bodies;  ///< topologically ordered: parent index < child index
  std::vector<Frame> frames;
};

}  // namespace reach_trajopt
