#pragma once
/// \file bullet_world.h
/// The simulated robot of the paper's Sec. IV (the paper uses DART; we use Bullet's
/// Featherstone btMultiBody in double precision): the dynamics of eq. (1) with rigid,
/// frictional contacts against a static ground plane z = 0, stepped at a fixed time step.
///
/// Model: the URDF's bodies after merging fixed joints (SimBodyTree), revolute and prismatic
/// joints with their inertias, unilateral joint-limit constraints, collision boxes, spheres and
/// cylinders from <collision> (meshes do not collide), the two legs colliding with each other
/// (SimConfig::leg_self_collision; no other self-collision), no joint damping,
/// friction `mu`. Bullet integrates semi-implicitly: qd+ = qd + dt qdd(q, qd, u) (plus
/// constraint impulses), then positions from qd+. Bullet's base velocities are world-frame
/// (linear velocity of the root body's centre of mass, angular velocity); the base frame is
/// the root body's principal frame (see btMultiBody::computeAccelerations...MultiDof), which
/// the free-fall test against RobotModel confirms to ~1e-14.
///
/// Coordinates: q, qd are OUR vectors (size n_q = 6 + n_u for a floating base, order of
/// RobotModel::joints()); the quaternion base exists only inside (base_coordinates.h). Torques
/// u have size n_u in the order of the actuated joints of q.
///
/// Determinism: the same reset() and the same torques give bit-identical states (reset()
/// rebuilds every Bullet object, so no contact cache or broadphase state survives it; it costs
/// about a millisecond).
/// Not thread-safe; one world per thread.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/sim/base_coordinates.h"
#include "reach_trajopt/sim/sim_body_tree.h"
#include "reach_trajopt/sim/sim_config.h"

class btPersistentManifold;  // Bullet

namespace reach_trajopt {

class RobotModel;

/// Contact of one sole with the ground, measured from Bullet's contact manifolds after a step.
struct SoleContact {
  std::string frame;        ///< sole frame name (SimConfig::left_sole_frame / right_sole_frame)
  bool in_contact = false;  ///< the ground pushed on the sole's body during the last step
  int num_points = 0;       ///< contact points carrying a normal force
  /// Wrench exerted BY the ground ON the robot over the last step (impulse / dt), [f; tau] in
  /// the world frame, moment about the sole centre [N, Nm].
  Vector6d wrench = Vector6d::Zero();
  Eigen::Isometry3d sole_pose = Eigen::Isometry3d::Identity();  ///< sole frame in the world
};

/// A Bullet multibody world holding one robot on a flat ground (paper Sec. IV, eq. (1)).
class BulletWorld {
 public:
  /// Builds the world from a URDF. `joint_order` names the n_u actuated joints in the order of
  /// our q (after the six virtual coordinates); every revolute/prismatic URDF joint must be in
  /// it. Throws ReachError on a bad URDF, an unknown or missing joint, an unknown sole frame,
  /// or an invalid config. The robot starts at q = 0 (base at the origin), qd = 0.
  BulletWorld(const SimBodyTree& tree, const std::vector<std::string>& joint_order,
              const SimConfig& config);
  /// Convenience: the URDF file and the joint order of `model` (which must be built from the
  /// same URDF; its actuated joints are joints() minus the six virtual ones).
  static std::unique_ptr<BulletWorld> fromUrdfFile(const std::string& urdf_path,
                                                   const RobotModel& model,
                                                   const SimConfig& config);
  ~BulletWorld();
  BulletWorld(const BulletWorld&) = delete;
  BulletWorld& operator=(const BulletWorld&) = delete;

  int nq() const { return nq_; }
  int nu() const { return nu_; }
  double timeStep() const { return config_.time_step; }
  double time() const { return time_; }  ///< simulated time since the last reset [s]
  const SimConfig& config() const { return config_; }
  const SimBodyTree& bodyTree() const { return tree_; }

  /// Rebuilds the world and sets the state (our coordinates). Time restarts at 0.
  /// Throws ReachError on wrong sizes, non-finite entries or gimbal lock (pitch = +-pi/2).
  void reset(const Eigen::Ref<const Eigen::VectorXd>& q,
             const Eigen::Ref<const Eigen::VectorXd>& qd);
  /// A push: adds `delta` [m/s] (world) to the floating base's linear velocity, the joint
  /// velocities and the base's angular velocity kept, so that every link's velocity and the
  /// CoM's change by `delta` at once (an impulse through the CoM). Then qd() describes the new
  /// state. Throws ReachError on a fixed-base robot or a non-finite delta.
  void pushBase(const Eigen::Vector3d& delta);
  /// Advances one time step with joint torques u (size n_u) [Nm or N], held over the step and
  /// saturated at the URDF effort limits when config().clamp_torques. Then q(), qd(),
  /// soleContacts() and nonFootContacts() describe the new state. Throws ReachError on a
  /// wrong size or a non-finite u, or when the simulation diverges (non-finite state).
  void step(const Eigen::Ref<const Eigen::VectorXd>& u);

  const Eigen::VectorXd& q() const { return q_; }    ///< size n_q [m, rad]
  const Eigen::VectorXd& qd() const { return qd_; }  ///< size n_q [m/s, rad/s]
  /// The two soles, left first, measured over the last step.
  const std::vector<SoleContact>& soleContacts() const { return soles_; }
  /// URDF links other than the soles' bodies that touched the ground during the last step
  /// (fall detection), in body order, no duplicates.
  const std::vector<std::string>& nonFootContacts() const { return non_foot_contacts_; }
  /// Pairs of URDF links of the two legs that touched each other during the last step, as
  /// "<link>/<link>" (sorted names), no duplicates; empty without leg self-collision.
  const std::vector<std::string>& legContacts() const { return leg_contacts_; }
  /// Per body of bodyTree(): 0 left leg, 1 right leg, -1 neither (no leg self-collision).
  const std::vector<int>& bodyLegs() const { return body_leg_; }

  /// Gravity [m/s^2], world frame; takes effect at the next step.
  void setGravity(const Eigen::Vector3d& gravity);
  /// Adds or removes the ground; takes effect at the next step.
  void setContactsEnabled(bool enabled);

  /// The base body's state as Bullet holds it (root body's principal frame, world twist) and
  /// its pose in the root link frame: for checks of base_coordinates against Bullet.
  BaseBodyState baseBodyState() const;
  const BaseCoordinates& baseCoordinates() const { return base_coords_; }
  /// World pose of a URDF link or fixed frame as Bullet has it now.
  Eigen::Isometry3d framePose(const std::string& link) const;

 private:
  struct Bullet;  // every Bullet object, rebuilt by reset()
  void build();
  void applyState(const Eigen::Ref<const Eigen::VectorXd>& q,
                  const Eigen::Ref<const Eigen::VectorXd>& qd);
  void readState();
  /// No contact on any sole or link; the soles' poses from the current state.
  void clearContacts();
  void measureContacts();
  void findLegs();
  void recordLegContact(const btPersistentManifold& manifold, int body0, int body1);

  SimBodyTree tree_;
  SimConfig config_;
  bool floating_;
  int nq_ = 0;
  int nu_ = 0;
  std::vector<int> body_to_q_;  ///< per body: index in q (-1 for the root)
  Eigen::VectorXd effort_max_;  ///< size n_u
  BaseCoordinates base_coords_;
  int sole_body_[2] = {0, 0};
  Eigen::Isometry3d sole_in_principal_[2];  ///< sole frame in its body's principal frame

  long steps_ = 0;     ///< steps since the last reset
  double time_ = 0.0;  ///< steps_ * time_step (no accumulated round-off)
  Eigen::VectorXd q_, qd_;
  std::vector<SoleContact> soles_;
  std::vector<std::string> non_foot_contacts_;
  std::vector<std::string> leg_contacts_;
  std::vector<int> body_leg_;  ///< per body: 0 left leg, 1 right leg, -1 neither
  std::unique_ptr<Bullet> bt_;
};

}  // namespace reach_trajopt
