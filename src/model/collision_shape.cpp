/// \file collision_shape.cpp
/// A URDF <collision> element as a CollisionShape (see the header).

#include "reach_trajopt/model/collision_shape.h"

#include <urdf_model/link.h>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

std::optional<CollisionShape> readCollisionShape(const urdf::Collision& collision,
                                                 const std::string& link,
                                                 const std::string& source) {
  if (!collision.geometry) return std::nullopt;
  CollisionShape shape;
  shape.link = link;
  const urdf::Pose& o = collision.origin;
  shape.pose.translation() = Eigen::Vector3d(o.position.x, o.position.y, o.position.z);
  shape.pose.linear() = Eigen::Quaterniond(o.rotation.w, o.rotation.x, o.rotation.y, o.rotation.z)
                            .normalized()
                            .toRotationMatrix();
  switch (collision.geometry->type) {
    case urdf::Geometry::BOX: {
      const auto& box = static_cast<const urdf::Box&>(*collision.geometry);
      shape.type = CollisionShape::Type::kBox;
      shape.size = Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z);
      break;
    }
    case urdf::Geometry::SPHERE: {
      const auto& s = static_cast<const urdf::Sphere&>(*collision.geometry);
      shape.type = CollisionShape::Type::kSphere;
      shape.size = Eigen::Vector3d(s.radius, 0.0, 0.0);
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& c = static_cast<const urdf::Cylinder&>(*collision.geometry);
      shape.type = CollisionShape::Type::kCylinder;
      shape.size = Eigen::Vector3d(c.radius, c.length, 0.0);
      break;
    }
    default:
      return std::nullopt;  // meshes: not modelled (the simulator ignores them too)
  }
  if (!(shape.size.array() >= 0.0).all() || !shape.size.allFinite())
    throw ModelError(source + ": link '" + link + "' has a collision shape of bad size");
  return shape;
}

}  // namespace reach_trajopt
