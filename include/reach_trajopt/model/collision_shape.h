#pragma once
/// \file collision_shape.h
/// The collision primitives of a URDF link (<collision>: box, sphere, cylinder; meshes are
/// skipped), read once with the model so that the simulator and the leg clearance of the
/// reachability check and the OCP use the same geometry.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>

namespace urdf {
class Collision;
}

namespace reach_trajopt {

/// A collision primitive attached to a link.
struct CollisionShape {
  enum class Type { kBox, kSphere, kCylinder };
  Type type = Type::kBox;
  std::string link;                                        ///< URDF link it came from
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< in the link's URDF frame
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< box: full sizes; sphere/cylinder: radius,
                                                   ///< length (z axis), 0 [m]
};

/// The shape of one <collision> element of `link`, its pose in the link frame; empty for a
/// mesh or a missing geometry. \throws ModelError naming `source` and the link when a size is
/// negative or not finite.
std::optional<CollisionShape> readCollisionShape(const urdf::Collision& collision,
                                                 const std::string& link,
                                                 const std::string& source);

}  // namespace reach_trajopt
