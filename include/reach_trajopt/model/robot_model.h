#pragma once
/// \file robot_model.h
/// The multi-body robot of eq. (1)-(3): M(q) qdd + b(q, qd) = S^T u + sum_i J_i^T lambda_i.
///
/// A URDF is read through urdfdom into a KDL tree (kdl_parser). When the URDF root is free
/// (its root link is not called "world"), six virtual joints x, y, z, yaw, pitch, roll
/// (R = Rz Ry Rx) are inserted in front of it, so q and qd are plain vectors of size
/// n_q = 6 + n_u and Euler integration q+ = q + dt qd is consistent. This is the same
/// coordinate choice as a Pinocchio composite root joint (PX, PY, PZ, RZ, RY, RX).
///
/// How URDF elements map onto the model (checked against Pinocchio on every robot of
/// example-robot-data and on random URDF trees, test/oracle/test_model_*.py):
///  - Links joined by `fixed` joints are merged into the moving body that carries them; the
///    fixed joints' rotations go into the next joint's placement and axis (the axis is the
///    URDF axis in the child link's frame) and into the merged inertias.
///  - Inertias are read from urdfdom, their <inertial> origin (xyz and rpy) included; a link
///    with mass 0 still contributes its rotational inertia (as in Pinocchio); the root link's
///    inertia counts when the base floats.
///  - Axes are normalized (as urdfdom's consumers and Pinocchio do).
///  - `continuous` joints are one unbounded angle in q (Pinocchio uses cos, sin: convert).
///  - `mimic` tags are ignored: a mimic joint is an independent degree of freedom, as in KDL and
///    in Pinocchio's buildModelFromUrdf (its default, mimic = false).
///  - Limits: position limits as in the URDF (urdfdom rejects a revolute or prismatic joint
///    without <limit>; lower/upper left out read as 0); a velocity or effort limit that is
///    missing or 0 means unlimited (+inf). `planar` and `floating` joints are rejected.
///
/// The dynamics are computed on the KDL tree's structure with the composite rigid body
/// algorithm (M) and recursive Newton-Euler (b); KDL's own solvers work chain by chain and are
/// several times slower on a branched robot. Conventions everywhere:
///  - Jacobians are 6 x n_q at a frame's origin, rows [linear; angular] in world orientation
///    (KDL twists are [linear; angular] as well; Pinocchio calls this LOCAL_WORLD_ALIGNED).
///  - Jdot*qd is the drift of the classical acceleration of the frame origin, i.e.
///    d/dt (J qd) = J qdd + Jdot*qd exactly, rows [linear; angular].
///  - SI units: metres, radians, kilograms, newtons, newton-metres.
///
/// The model is read-only after construction; every thread owns a Workspace for its buffers.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/model/collision_shape.h"
#include "reach_trajopt/model/joint_locking.h"

namespace reach_trajopt {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6Xd = Eigen::Matrix<double, 6, Eigen::Dynamic>;

/// Index of a frame of the model (a link or a fixed frame such as a sole), from frameId().
using FrameId = int;

/// One degree of freedom of the model, in the order of q.
struct JointInfo {
  std::string name;
  bool is_virtual = false;  ///< one of the six floating-base coordinates
  bool is_prismatic = false;
  /// URDF `continuous`: one unbounded angle [rad] (Pinocchio stores cos, sin instead).
  bool is_continuous = false;
  double q_min = 0.0;       ///< position lower limit [m or rad] (-inf when unlimited)
  double q_max = 0.0;       ///< position upper limit [m or rad] (+inf when unlimited)
  double qd_max = 0.0;      ///< |velocity| limit [m/s or rad/s] (+inf when unlimited)
  double effort_max = 0.0;  ///< |force/torque| limit [N or Nm] (0 for virtual joints)
};

/// How to load a URDF.
struct ModelOptions {
  enum class Base { kAuto, kFloating, kFixed };
  /// kAuto: floating unless the URDF's root link is named "world".
  Base base = Base::kAuto;
  /// Gravity in the world frame [m/s^2].
  Eigen::Vector3d gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
  /// Joints held at these positions and removed from q (joint_locking.h), like Pinocchio's
  /// buildReducedModel; their links stay as frames, their masses in the carrying body.
  LockedJoints locked_joints;
};

class Workspace;
struct ModelTree;  // the flattened KDL tree, private to the implementation

/// The robot model: structure, limits, kinematics and rigid-body dynamics of eq. (1).
class RobotModel {
 public:
  /// Loads a URDF file. Throws ReachError naming the file when it is missing or malformed.
  static std::shared_ptr<const RobotModel> fromUrdfFile(const std::string& path,
                                                        const ModelOptions& options = {});
  /// Loads a URDF from its XML text; `source` names it in error messages.
  static std::shared_ptr<const RobotModel> fromUrdfString(const std::string& xml,
                                                          const ModelOptions& options = {},
                                                          const std::string& source = "<string>");
  ~RobotModel();
  RobotModel(const RobotModel&) = delete;
  RobotModel& operator=(const RobotModel&) = delete;

  const std::string& name() const { return name_; }
  const std::string& source() const { return source_; }
  bool floatingBase() const { return floating_base_; }
  int nq() const { return static_cast<int>(joints_.size()); }  ///< = n_v, positions = velocities
  int nu() const { return nq() - (floating_base_ ? 6 : 0); }   ///< actuated joints
  const std::vector<JointInfo>& joints() const { return joints_; }
  /// Index in q of the joint called `name`; throws ReachError when unknown.
  int jointIndex(const std::string& name) const;
  Eigen::VectorXd positionLowerLimits() const;
  Eigen::VectorXd positionUpperLimits() const;
  Eigen::VectorXd velocityLimits() const;  ///< |qd| bounds, size n_q
  Eigen::VectorXd effortLimits() const;    ///< |u| bounds, size n_u (actuated joints only)
  /// Selection matrix S (n_u x n_q) of eq. (1): u acts on the actuated coordinates.
  Eigen::MatrixXd selectionMatrix() const;
  double totalMass() const { return total_mass_; }  ///< [kg]
  const Eigen::Vector3d& gravity() const { return gravity_; }
  /// The joints locked when the model was built (ModelOptions::locked_joints), so a simulator
  /// built from the same URDF can lock them too.
  const LockedJoints& lockedJoints() const { return locked_joints_; }

  /// Frame of a link or fixed frame by name; throws ReachError("unknown frame 'x' in <src>").
  FrameId frameId(const std::string& name) const;
  bool hasFrame(const std::string& name) const;
  const std::vector<std::string>& frameNames() const { return frame_names_; }
  /// Links that carry mass or collision geometry, in tree order (for TF and the simulator).
  const std::vector<std::string>& linkNames() const { return link_names_; }
  /// The links' collision primitives (box, sphere, cylinder; meshes skipped), poses in their
  /// link's frame, in tree order.
  const std::vector<CollisionShape>& collisionShapes() const { return collision_shapes_; }
  /// Parent link of a link ("" for the root link).
  const std::string& parentLink(const std::string& link) const;

  /// A configuration in the middle of the joint limits (virtual coordinates zero).
  Eigen::VectorXd neutralConfiguration() const;

  // ---- Computations; each takes the caller's Workspace ------------------------------------

  /// Forward kinematics at (q, qd): poses, velocities and velocity-product accelerations of
  /// every body. Call it before any of the queries below. Throws ReachError on wrong sizes
  /// or non-finite entries.
  /// \param[in] q   configuration, size n_q [m, rad]
  /// \param[in] qd  velocity, size n_q [m/s, rad/s]
  void update(Workspace& ws, const Eigen::Ref<const Eigen::VectorXd>& q,
              const Eigen::Ref<const Eigen::VectorXd>& qd) const;
  /// The same for a new velocity at the configuration of the last update(): the poses are
  /// kept and only the velocities and velocity-product accelerations recomputed (the same
  /// arithmetic, so the same bits as update(q, qd)). Cheaper by the pose pass (one sin/cos
  /// and two 3 x 3 products per body). Throws ReachError before any update() or on a wrong
  /// size or non-finite qd.
  void updateVelocity(Workspace& ws, const Eigen::Ref<const Eigen::VectorXd>& qd) const;

  /// Pose of a frame in the world (after update()).
  Eigen::Isometry3d framePose(const Workspace& ws, FrameId frame) const;
  /// 6 x n_q Jacobian of a frame at its origin, world orientation, [linear; angular].
  void frameJacobian(const Workspace& ws, FrameId frame, Eigen::Ref<Matrix6Xd> J) const;
  /// Jdot*qd of a frame, [linear; angular] (classical acceleration drift of the origin).
  Vector6d frameJdotQd(const Workspace& ws, FrameId frame) const;
  /// Spatial velocity of a frame, [linear; angular] of its origin, world orientation.
  Vector6d frameVelocity(const Workspace& ws, FrameId frame) const;

  /// Joint-space mass matrix M(q) of eq. (1), n_q x n_q, symmetric (CRBA).
  void massMatrix(Workspace& ws, Eigen::Ref<Eigen::MatrixXd> M) const;
  /// Bias b(q, qd) of eq. (1): Coriolis, centrifugal and gravity terms, size n_q (RNEA).
  void bias(Workspace& ws, Eigen::Ref<Eigen::VectorXd> b) const;
  /// Inverse dynamics M qdd + b (RNEA), size n_q.
  void inverseDynamics(Workspace& ws, const Eigen::Ref<const Eigen::VectorXd>& qdd,
                       Eigen::Ref<Eigen::VectorXd> tau) const;

  /// Centre of mass in the world [m].
  Eigen::Vector3d centerOfMass(const Workspace& ws) const;
  /// Jc_dot*qd: the CoM acceleration when qdd = 0 (after update()), world frame [m/s^2].
  Eigen::Vector3d centerOfMassJdotQd(const Workspace& ws) const;
  /// 3 x n_q CoM Jacobian (world frame).
  void centerOfMassJacobian(Workspace& ws, Eigen::Ref<Eigen::Matrix3Xd> Jc) const;

  /// Throws ReachError unless q and qd have size n_q and are finite.
  void checkState(const Eigen::Ref<const Eigen::VectorXd>& q,
                  const Eigen::Ref<const Eigen::VectorXd>& qd) const;

  const ModelTree& tree() const { return *tree_; }

 private:
  RobotModel();
  /// The velocity part of update() on buffers whose poses are current.
  void velocityPass(Workspace& ws, const Eigen::Ref<const Eigen::VectorXd>& qd) const;
  /// The RNEA's force and backward passes (inverseDynamics and bias): on entry the buffers'
  /// fn, ff hold each body's angular and linear acceleration from qdd and gravity, body frame
  /// (the velocity products dw, dv of update() are added here); tau (size n_q) receives the
  /// generalized forces. fn, ff are overwritten.
  void rneaForcesAndBackwardPass(Workspace& ws, Eigen::Ref<Eigen::VectorXd> tau) const;
  friend class Workspace;
  friend class ModelBuilder;

  std::string name_;
  std::string source_;
  bool floating_base_ = false;
  double total_mass_ = 0.0;
  Eigen::Vector3d gravity_;
  LockedJoints locked_joints_;
  std::vector<JointInfo> joints_;
  std::vector<std::string> frame_names_;
  std::vector<std::string> link_names_;
  std::vector<std::string> link_parents_;
  std::vector<CollisionShape> collision_shapes_;
  std::unique_ptr<ModelTree> tree_;
};

/// Scratch space for one thread's computations on one RobotModel (poses, velocities,
/// composite inertias...). Sized once at construction; the computations allocate nothing.
class Workspace {
 public:
  explicit Workspace(const RobotModel& model);
  ~Workspace();
  Workspace(Workspace&&) noexcept;
  Workspace& operator=(Workspace&&) noexcept;

  struct Buffers;  // implementation detail
  Buffers& buffers() { return *buffers_; }
  const Buffers& buffers() const { return *buffers_; }

 private:
  std::unique_ptr<Buffers> buffers_;
};

}  // namespace reach_trajopt
