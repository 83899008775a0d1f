#pragma once
/// \file sim_body_tree.h
/// The rigid bodies a multibody simulator moves, read from a URDF: links joined by fixed
/// joints are merged into their parent (masses, centres of mass and inertias combined, eq. of
/// the parallel-axis theorem), so each body ends in one revolute or prismatic joint (or is the
/// root). Every body gets a "principal frame": its centre of mass with the principal axes of
/// its inertia, the frame Featherstone's btMultiBody expects. Bullet-free, so it is testable.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "reach_trajopt/model/collision_shape.h"
#include "reach_trajopt/model/joint_locking.h"

namespace reach_trajopt {

/// A collision primitive of a body (URDF <collision>; model/collision_shape.h); its pose is in
/// the body's URDF frame.
using SimShape = CollisionShape;

/// One rigid body: a URDF link (the body's "URDF frame") and its fixed descendants.
struct SimBody {
  enum class JointType { kNone, kRevolute, kPrismatic };
  std::string name;                ///< the URDF link starting the body
  std::vector<std::string> links;  ///< all merged URDF links, `name` first
  int parent = -1;                 ///< index in SimBodyTree::bodies (-1: root)
  std::string joint;               ///< URDF joint to the parent ("" for the root)
  JointType joint_type = JointType::kNone;
  /// Pose of this body's URDF frame in the parent body's URDF frame at joint position 0.
  Eigen::Isometry3d parent_to_body = Eigen::Isometry3d::Identity();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();          ///< unit joint axis, body's URDF frame
  double q_min = -std::numeric_limits<double>::infinity();  ///< [rad or m]
  double q_max = std::numeric_limits<double>::infinity();
  double effort_max = std::numeric_limits<double>::infinity();  ///< [Nm or N]

  double mass = 0.0;                                  ///< [kg]
  Eigen::Vector3d com = Eigen::Vector3d::Zero();      ///< in the body's URDF frame [m]
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< about the com, URDF frame [kg m^2]
  /// Principal frame (com, principal axes) in the body's URDF frame; the inertia there is
  /// diag(principal_inertia).
  Eigen::Isometry3d principal = Eigen::Isometry3d::Identity();
  Eigen::Vector3d principal_inertia = Eigen::Vector3d::Zero();
  std::vector<SimShape> shapes;
};

/// The merged body tree of a URDF, parents before children.
struct SimBodyTree {
  std::string source;         ///< file name or "<string>", for error messages
  bool floating_base = true;  ///< false when the URDF root link is called "world"
  std::vector<SimBody> bodies;
  /// Every URDF link: its body and its pose in that body's URDF frame.
  std::map<std::string, std::pair<int, Eigen::Isometry3d>> frames;

  /// Parses and merges. Throws ReachError naming the source on a missing or malformed file, a
  /// floating or planar joint, or a revolute/prismatic joint without limits.
  /// `locked`: joints turned into fixed ones first (model/joint_locking.h), as in the model.
  static SimBodyTree fromUrdfFile(const std::string& path, const LockedJoints& locked = {});
  static SimBodyTree fromUrdfString(const std::string& xml, const std::string& source,
                                    const LockedJoints& locked = {});

  /// Body index and pose in its URDF frame of a URDF link; throws ReachError when unknown.
  const std::pair<int, Eigen::Isometry3d>& frame(const std::string& link) const;
  double totalMass() const;
};

}  // namespace reach_trajopt
