#pragma once
/// \file joint_locking.h
/// Locked joints: a URDF joint held at a given position is turned into a fixed joint whose
/// origin includes that position, before any model is built from the URDF. The robot model
/// (robot_model.h) and the simulator's body tree (sim/sim_body_tree.h) both read the URDF
/// through this, so they agree on the reduced robot. This is Pinocchio's buildReducedModel:
/// e.g. TALOS legs are talos_reduced.urdf with the arms, torso, head and grippers locked at the
/// SRDF's half_sitting (config/talos.yaml, robot.locked_joints).

#include <map>
#include <string>

namespace urdf {
class ModelInterface;
}

namespace reach_trajopt {

/// Joint name -> held position [rad for revolute and continuous, m for prismatic].
using LockedJoints = std::map<std::string, double>;

/// Replaces every joint of `locked` in `urdf` by a fixed joint with origin
/// origin * motion(position) (a rotation about, or a translation along, the joint axis).
/// \throws ModelError naming the joint and `source` when a locked joint does not exist, is
///         already fixed (or floating, planar), or its position is not finite or outside the
///         joint's limits.
void lockJoints(urdf::ModelInterface& urdf, const LockedJoints& locked, const std::string& source);

}  // namespace reach_trajopt
