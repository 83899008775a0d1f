/// \file joint_locking.cpp
/// Locked joints become fixed joints (see the header).

#include "reach_trajopt/model/joint_locking.h"

#include <urdf_model/model.h>

#include <Eigen/Geometry>
#include <cmath>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

namespace {

/// The joint's motion at `position` in its own frame, as a urdf::Pose.
urdf::Pose jointMotion(const urdf::Joint& joint, double position) {
  const Eigen::Vector3d axis =
      Eigen::Vector3d(joint.axis.x, joint.axis.y, joint.axis.z).normalized();
  urdf::Pose motion;
  if (joint.type == urdf::Joint::PRISMATIC) {
    const Eigen::Vector3d p = position * axis;
    motion.position = urdf::Vector3(p.x(), p.y(), p.z());
  } else {
    const Eigen::Quaterniond r(Eigen::AngleAxisd(position, axis));
    motion.rotation = urdf::Rotation(r.x(), r.y(), r.z(), r.w());
  }
  return motion;
}

/// a * b of two urdf poses.
urdf::Pose compose(const urdf::Pose& a, const urdf::Pose& b) {
  urdf::Pose out;
  out.rotation = a.rotation * b.rotation;
  const urdf::Vector3 t = a.rotation * b.position;
  out.position = urdf::Vector3(a.position.x + t.x, a.position.y + t.y, a.position.z + t.z);
  return out;
}

}  // namespace

void lockJoints(urdf::ModelInterface& urdf, const LockedJoints& locked, const std::string& source) {
  for (const auto& [name, position] : locked) {
    const auto it = urdf.joints_.find(name);
    if (it == urdf.joints_.end() || !it->second)
      throw ModelError("locked joint '" + name + "' does not exist in " + source);
    urdf::Joint& joint = *it->second;
    const bool movable = joint.type == urdf::Joint::REVOLUTE ||
                         joint.type == urdf::Joint::CONTINUOUS ||
                         joint.type == urdf::Joint::PRISMATIC;
    if (!movable)
      throw ModelError("locked joint '" + name + "' in " + source +
                       " is not revolute, continuous or prismatic (a fixed joint needs no lock)");
    if (!std::isfinite(position))
      throw ModelError("locked joint '" + name + "': non-finite position");
    if (joint.type != urdf::Joint::CONTINUOUS && joint.limits &&
        (position < joint.limits->lower - 1e-12 || position > joint.limits->upper + 1e-12))
      throw ModelError("locked joint '" + name + "': position " + std::to_string(position) +
                       " outside its limits [" + std::to_string(joint.limits->lower) + ", " +
                       std::to_string(joint.limits->upper) + "] in " + source);
    if (Eigen::Vector3d(joint.axis.x, joint.axis.y, joint.axis.z).norm() == 0.0)
      throw ModelError("locked joint '" + name + "' has a zero axis in " + source);
    joint.parent_to_joint_origin_transform =
        compose(joint.parent_to_joint_origin_transform, jointMotion(joint, position));
    joint.type = urdf::Joint::FIXED;
  }
}

}  // namespace reach_trajopt
