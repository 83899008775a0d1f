#include "reach_trajopt/sim/bullet_world.h"

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "reach_trajopt/model/robot_model.h"

#ifndef BT_USE_DOUBLE_PRECISION
#error "reach_trajopt's simulator needs Bullet in double precision (pkg-config bullet-float64)"
#endif

namespace reach_trajopt {

namespace {

// Robot links collide with the ground; with leg self-collision, each leg's links also with the
// other leg's (never with their own leg or the rest of the robot); the ground with the robot.
constexpr int kRobotGroup = btBroadphaseProxy::DefaultFilter;
constexpr int kGroundGroup = btBroadphaseProxy::StaticFilter;
constexpr int kLegGroup[2] = {1 << 6, 1 << 7};  // left, right (Bullet's user filter bits)

btVector3 toBt(const Eigen::Vector3d& v) { return btVector3(v.x(), v.y(), v.z()); }
Eigen::Vector3d toEigen(const btVector3& v) { return Eigen::Vector3d(v.x(), v.y(), v.z()); }
btQuaternion toBt(const Eigen::Quaterniond& q) { return btQuaternion(q.x(), q.y(), q.z(), q.w()); }
Eigen::Quaterniond toEigen(const btQuaternion& q) {
  return Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z());
}
btTransform toBt(const Eigen::Isometry3d& T) {
  return btTransform(toBt(Eigen::Quaterniond(T.linear()).normalized()), toBt(T.translation()));
}

}  // namespace

/// Every Bullet object of one world. Declaration order matters: the world is declared last so
/// it is destroyed first, while the objects it refers to still exist.
struct BulletWorld::Bullet {
  std::unique_ptr<btDefaultCollisionConfiguration> collision_config;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  std::unique_ptr<btBroadphaseInterface> broadphase;
  std::unique_ptr<btMultiBodyConstraintSolver> solver;
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::unique_ptr<btMultiBody> multibody;
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders;
  std::vector<std::unique_ptr<btMultiBodyJointLimitConstraint>> limits;
  std::unique_ptr<btStaticPlaneShape> ground_shape;
  std::unique_ptr<btCollisionObject> ground;
  std::unique_ptr<btMultiBodyDynamicsWorld> world;
  bool ground_in_world = false;
  // Scratch for forward kinematics (kept to avoid allocations per step).
  btAlignedObjectArray<btQuaternion> world_to_local;
  btAlignedObjectArray<btVector3> local_origin;

  /// The robot as one btMultiBody: a link per body of the tree, in Bullet's principal frames.
  void addMultiBody(const SimBodyTree& tree, const SimConfig& config, bool floating,
                    bool self_collision);
  /// One compound collider per body with shapes (boxes, spheres, cylinders of the URDF);
  /// `leg` per body: 0 left leg, 1 right leg, -1 neither (collides with the ground only).
  void addColliders(const SimBodyTree& tree, const SimConfig& config, const std::vector<int>& leg);
  /// Bullet's joint limit constraints for the joints with finite limits.
  void addJointLimits(const SimBodyTree& tree);

  ~Bullet() {
    if (world) {
      for (auto& c : limits) world->removeMultiBodyConstraint(c.get());
      if (multibody) world->removeMultiBody(multibody.get());
      for (auto& c : colliders)
        if (c) world->removeCollisionObject(c.get());
      if (ground_in_world) world->removeCollisionObject(ground.get());
    }
    world.reset();
  }

  // Pose of body k's principal frame in the world (k = 0: the base).
  btTransform bodyPose(int k) const {
    const btMultiBody& mb = *multibody;
    if (k == 0) return mb.getBaseWorldTransform();
    btTransform T;
    T.setOrigin(mb.localPosToWorld(k - 1, btVector3(0, 0, 0)));
    T.setBasis(mb.localFrameToWorld(k - 1, btMatrix3x3::getIdentity()));
    return T;
  }
};

BulletWorld::BulletWorld(const SimBodyTree& tree, const std::vector<std::string>& joint_order,
                         const SimConfig& config)
    : tree_(tree), config_(config), floating_(tree.floating_base) {
  config_.validate();
  if (tree_.bodies.empty()) throw ModelError(tree_.source + ": no bodies");
  nu_ = static_cast<int>(joint_order.size());
  const int offset = floating_ ? 6 : 0;
  nq_ = nu_ + offset;
  if (static_cast<int>(tree_.bodies.size()) - 1 != nu_) {
    std::ostringstream os;
    os << tree_.source << ": the URDF has " << tree_.bodies.size() - 1
       << " revolute/prismatic joints but the joint order names " << nu_;
    throw ModelError(os.str());
  }
  body_to_q_.assign(tree_.bodies.size(), -1);
  effort_max_.resize(nu_);
  std::vector<bool> used(nu_, false);
  for (size_t k = 1; k < tree_.bodies.size(); ++k) {
    const SimBody& b = tree_.bodies[k];
    auto it = std::find(joint_order.begin(), joint_order.end(), b.joint);
    if (it == joint_order.end()) {
      throw ModelError("joint '" + b.joint + "' of " + tree_.source +
                       " is not in the simulator's joint order");
    }
    const int j = static_cast<int>(it - joint_order.begin());
    if (used[j]) throw ModelError("joint '" + b.joint + "' appears twice in the joint order");
    used[j] = true;
    body_to_q_[k] = offset + j;
    effort_max_[j] = b.effort_max;
  }
  base_coords_ = BaseCoordinates(tree_.bodies[0].principal);
  const std::string sole_names[2] = {config_.left_sole_frame, config_.right_sole_frame};
  soles_.resize(2);
  for (int s = 0; s < 2; ++s) {
    const auto& f = tree_.frame(sole_names[s]);
    sole_body_[s] = f.first;
    sole_in_principal_[s] = tree_.bodies[f.first].principal.inverse() * f.second;
    soles_[s].frame = sole_names[s];
    if (config_.sole_box_size.minCoeff() > 0.0) {
      SimShape box;
      box.type = SimShape::Type::kBox;
      box.link = sole_names[s];
      box.size = config_.sole_box_size;
      box.pose = f.second * Eigen::Translation3d(0.0, 0.0, 0.5 * box.size.z());
      tree_.bodies[f.first].shapes.push_back(box);
    }
  }
  if (sole_body_[0] == sole_body_[1]) {
    throw ModelError(tree_.source + ": both sole frames are on body '" +
                     tree_.bodies[sole_body_[0]].name + "'");
  }
  findLegs();
  reset(Eigen::VectorXd::Zero(nq_), Eigen::VectorXd::Zero(nq_));
}

void BulletWorld::findLegs() {
  const int n = static_cast<int>(tree_.bodies.size());
  body_leg_.assign(n, -1);
  if (!config_.leg_self_collision) return;
  // A leg: the child of the root on the path to a sole, and every body below it.
  int top[2] = {-1, -1};
  for (int s = 0; s < 2; ++s) {
    for (int k = sole_body_[s]; k > 0; k = tree_.bodies[k].parent)
      if (tree_.bodies[k].parent == 0) top[s] = k;
  }
  if (top[0] < 0 || top[1] < 0 || top[0] == top[1]) return;  // no two separate legs
  for (int k = 1; k < n; ++k) {
    for (int a = k; a > 0; a = tree_.bodies[a].parent) {
      if (a == top[0] || a == top[1]) {
        body_leg_[k] = a == top[0] ? 0 : 1;
        break;
      }
    }
  }
}

std::unique_ptr<BulletWorld> BulletWorld::fromUrdfFile(const std::string& urdf_path,
                                                       const RobotModel& model,
                                                       const SimConfig& config) {
  SimBodyTree tree = SimBodyTree::fromUrdfFile(urdf_path, model.lockedJoints());
  if (tree.floating_base != model.floatingBase()) {
    throw ModelError(urdf_path + ": the robot model and the simulator disagree on the base (" +
                     std::string(model.floatingBase() ? "floating" : "fixed") + " in the model)");
  }
  std::vector<std::string> order;
  for (const JointInfo& j : model.joints())
    if (!j.is_virtual) order.push_back(j.name);
  return std::make_unique<BulletWorld>(tree, order, config);
}

BulletWorld::~BulletWorld() = default;

void BulletWorld::Bullet::addMultiBody(const SimBodyTree& tree, const SimConfig& config,
                                       bool floating, bool self_collision) {
  btMultiBodyDynamicsWorld& dynamics = *world;
  const int n_links = static_cast<int>(tree.bodies.size()) - 1;
  const SimBody& root = tree.bodies[0];
  multibody = std::make_unique<btMultiBody>(n_links, root.mass, toBt(root.principal_inertia),
                                            /*fixedBase=*/!floating, /*canSleep=*/false);
  btMultiBody& mb = *multibody;
  for (int k = 1; k <= n_links; ++k) {
    const SimBody& b = tree.bodies[k];
    const SimBody& p = tree.bodies[b.parent];
    // Bullet's frames are the principal frames; P and K below are the parent's and this one's.
    const Eigen::Isometry3d P_to_K = p.principal.inverse() * b.parent_to_body * b.principal;
    const btQuaternion rot_parent_to_this =
        toBt(Eigen::Quaterniond(P_to_K.linear()).normalized()).inverse();
    const Eigen::Vector3d pivot_in_P = p.principal.inverse() * b.parent_to_body.translation();
    const Eigen::Vector3d pivot_to_com_in_K =
        b.principal.linear().transpose() * b.principal.translation();
    const Eigen::Vector3d axis_in_K = b.principal.linear().transpose() * b.axis;
    if (b.joint_type == SimBody::JointType::kPrismatic) {
      mb.setupPrismatic(k - 1, b.mass, toBt(b.principal_inertia), b.parent - 1, rot_parent_to_this,
                        toBt(axis_in_K), toBt(pivot_in_P), toBt(pivot_to_com_in_K),
                        /*disableParentCollision=*/true);
    } else {
      mb.setupRevolute(k - 1, b.mass, toBt(b.principal_inertia), b.parent - 1, rot_parent_to_this,
                       toBt(axis_in_K), toBt(pivot_in_P), toBt(pivot_to_com_in_K),
                       /*disableParentCollision=*/true);
    }
  }
  mb.finalizeMultiDof();
  mb.setLinearDamping(0.0);
  mb.setAngularDamping(0.0);
  mb.setMaxCoordinateVelocity(config.max_coordinate_velocity);
  mb.setUseGyroTerm(true);
  mb.setHasSelfCollision(self_collision);  // which pairs: the filter groups of addColliders
  dynamics.addMultiBody(&mb);
}

void BulletWorld::Bullet::addColliders(const SimBodyTree& tree, const SimConfig& config,
                                       const std::vector<int>& leg) {
  btMultiBodyDynamicsWorld& dynamics = *world;
  btMultiBody& mb = *multibody;
  colliders.resize(tree.bodies.size());
  for (size_t k = 0; k < tree.bodies.size(); ++k) {
    const SimBody& b = tree.bodies[k];
    if (b.shapes.empty()) continue;
    auto compound = std::make_unique<btCompoundShape>();
    for (const SimShape& s : b.shapes) {
      std::unique_ptr<btCollisionShape> child;
      switch (s.type) {
        case SimShape::Type::kBox:
          child = std::make_unique<btBoxShape>(toBt(0.5 * s.size));
          child->setMargin(config.collision_margin);  // keeps the outer box size
          break;
        case SimShape::Type::kSphere:
          child = std::make_unique<btSphereShape>(s.size[0]);
          break;
        case SimShape::Type::kCylinder:
          child =
              std::make_unique<btCylinderShapeZ>(btVector3(s.size[0], s.size[0], 0.5 * s.size[1]));
          child->setMargin(config.collision_margin);
          break;
      }
      compound->addChildShape(toBt(b.principal.inverse() * s.pose), child.get());
      shapes.push_back(std::move(child));
    }
    auto collider = std::make_unique<btMultiBodyLinkCollider>(&mb, static_cast<int>(k) - 1);
    collider->setCollisionShape(compound.get());
    collider->setFriction(config.mu);  // combined friction = product; the ground has 1
    collider->setRestitution(0.0);
    collider->setRollingFriction(0.0);
    collider->setSpinningFriction(0.0);
    collider->setActivationState(DISABLE_DEACTIVATION);
    shapes.push_back(std::move(compound));
    if (leg[k] >= 0) {
      dynamics.addCollisionObject(collider.get(), kRobotGroup | kLegGroup[leg[k]],
                                  kGroundGroup | kLegGroup[1 - leg[k]]);
    } else {
      dynamics.addCollisionObject(collider.get(), kRobotGroup, kGroundGroup);
    }
    if (k == 0) {
      mb.setBaseCollider(collider.get());
    } else {
      mb.getLink(static_cast<int>(k) - 1).m_collider = collider.get();
    }
    colliders[k] = std::move(collider);
  }
}

void BulletWorld::Bullet::addJointLimits(const SimBodyTree& tree) {
  btMultiBodyDynamicsWorld& dynamics = *world;
  btMultiBody& mb = *multibody;
  const int n_links = static_cast<int>(tree.bodies.size()) - 1;
  for (int k = 1; k <= n_links; ++k) {
    const SimBody& b = tree.bodies[k];
    if (!std::isfinite(b.q_min) || !std::isfinite(b.q_max)) continue;
    limits.push_back(
        std::make_unique<btMultiBodyJointLimitConstraint>(&mb, k - 1, b.q_min, b.q_max));
    dynamics.addMultiBodyConstraint(limits.back().get());
  }
}

void BulletWorld::build() {
  bt_.reset();  // destroy the previous world before building the next
  auto bt = std::make_unique<Bullet>();
  bt->collision_config = std::make_unique<btDefaultCollisionConfiguration>();
  // Several contact points per box-plane pair from the first touch (perturbed queries), so a
  // flat sole gets its support polygon at once instead of accumulating it over steps.
  bt->collision_config->setPlaneConvexMultipointIterations();
  bt->dispatcher = std::make_unique<btCollisionDispatcher>(bt->collision_config.get());
  bt->broadphase = std::make_unique<btDbvtBroadphase>();
  bt->solver = std::make_unique<btMultiBodyConstraintSolver>();
  bt->world = std::make_unique<btMultiBodyDynamicsWorld>(
      bt->dispatcher.get(), bt->broadphase.get(), bt->solver.get(), bt->collision_config.get());
  bt->world->setGravity(toBt(config_.gravity));
  bt->world->getSolverInfo().m_numIterations = config_.solver_iterations;
  const bool self_collision = std::find(body_leg_.begin(), body_leg_.end(), 0) != body_leg_.end() &&
                              std::find(body_leg_.begin(), body_leg_.end(), 1) != body_leg_.end();
  bt->addMultiBody(tree_, config_, floating_, self_collision);
  bt->addColliders(tree_, config_, body_leg_);
  if (config_.joint_limits) bt->addJointLimits(tree_);
  bt->ground_shape = std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0.0);
  bt->ground = std::make_unique<btCollisionObject>();
  bt->ground->setCollisionShape(bt->ground_shape.get());
  bt->ground->setFriction(1.0);
  bt->ground->setRestitution(0.0);
  bt_ = std::move(bt);
  setContactsEnabled(config_.contacts);
}

void BulletWorld::setContactsEnabled(bool enabled) {
  config_.contacts = enabled;
  if (!bt_) return;
  if (enabled && !bt_->ground_in_world) {
    bt_->world->addCollisionObject(bt_->ground.get(), kGroundGroup, kRobotGroup);
  } else if (!enabled && bt_->ground_in_world) {
    bt_->world->removeCollisionObject(bt_->ground.get());
  }
  bt_->ground_in_world = enabled;
}

void BulletWorld::setGravity(const Eigen::Vector3d& gravity) {
  requireFinite("BulletWorld::setGravity", gravity);
  config_.gravity = gravity;
  if (bt_) bt_->world->setGravity(toBt(gravity));
}

void BulletWorld::reset(const Eigen::Ref<const Eigen::VectorXd>& q,
                        const Eigen::Ref<const Eigen::VectorXd>& qd) {
  requireSize("BulletWorld::reset q", q.size(), nq_);
  requireSize("BulletWorld::reset qd", qd.size(), nq_);
  requireFinite("BulletWorld::reset q", q);
  requireFinite("BulletWorld::reset qd", qd);
  build();
  applyState(q, qd);
  steps_ = 0;
  time_ = 0.0;
  q_ = q;
  qd_ = qd;
  readState();
  clearContacts();
}

void BulletWorld::applyState(const Eigen::Ref<const Eigen::VectorXd>& q,
                             const Eigen::Ref<const Eigen::VectorXd>& qd) {
  btMultiBody& mb = *bt_->multibody;
  if (floating_) {
    const BaseBodyState body = base_coords_.fromVirtual(q.head<6>(), qd.head<6>());
    mb.setBasePos(toBt(body.position));
    mb.setWorldToBaseRot(toBt(body.orientation).inverse());
    mb.setBaseVel(toBt(body.linear_velocity));
    mb.setBaseOmega(toBt(body.angular_velocity));
  } else {
    mb.setBaseWorldTransform(toBt(tree_.bodies[0].principal));
    mb.setBaseVel(btVector3(0, 0, 0));
    mb.setBaseOmega(btVector3(0, 0, 0));
  }
  for (size_t k = 1; k < tree_.bodies.size(); ++k) {
    mb.setJointPos(static_cast<int>(k) - 1, q[body_to_q_[k]]);
    mb.setJointVel(static_cast<int>(k) - 1, qd[body_to_q_[k]]);
  }
  mb.forwardKinematics(bt_->world_to_local, bt_->local_origin);
  mb.updateCollisionObjectWorldTransforms(bt_->world_to_local, bt_->local_origin);
}

void BulletWorld::readState() {
  const btMultiBody& mb = *bt_->multibody;
  if (floating_) {
    const Eigen::Vector3d reference_ypr = q_.segment<3>(3);
    base_coords_.toVirtual(baseBodyState(), reference_ypr, q_.head<6>(), qd_.head<6>());
  }
  for (size_t k = 1; k < tree_.bodies.size(); ++k) {
    q_[body_to_q_[k]] = mb.getJointPos(static_cast<int>(k) - 1);
    qd_[body_to_q_[k]] = mb.getJointVel(static_cast<int>(k) - 1);
  }
}

BaseBodyState BulletWorld::baseBodyState() const {
  const btMultiBody& mb = *bt_->multibody;
  BaseBodyState body;
  body.position = toEigen(mb.getBasePos());
  body.orientation = toEigen(mb.getWorldToBaseRot().inverse());
  body.linear_velocity = toEigen(mb.getBaseVel());
  body.angular_velocity = toEigen(mb.getBaseOmega());
  return body;
}

Eigen::Isometry3d BulletWorld::framePose(const std::string& link) const {
  const auto& f = tree_.frame(link);
  const btTransform T = bt_->bodyPose(f.first);
  Eigen::Isometry3d world_to_principal = Eigen::Isometry3d::Identity();
  world_to_principal.linear() = toEigen(T.getRotation()).normalized().toRotationMatrix();
  world_to_principal.translation() = toEigen(T.getOrigin());
  return world_to_principal * tree_.bodies[f.first].principal.inverse() * f.second;
}

void BulletWorld::pushBase(const Eigen::Vector3d& delta) {
  requireFinite("BulletWorld::pushBase delta", delta);
  if (!floating_) throw ReachError("BulletWorld::pushBase: the robot has a fixed base");
  btMultiBody& mb = *bt_->multibody;
  mb.setBaseVel(mb.getBaseVel() + toBt(delta));
  readState();
}

void BulletWorld::step(const Eigen::Ref<const Eigen::VectorXd>& u) {
  requireSize("BulletWorld::step u", u.size(), nu_);
  requireFinite("BulletWorld::step u", u);
  btMultiBody& mb = *bt_->multibody;
  const int offset = floating_ ? 6 : 0;
  for (size_t k = 1; k < tree_.bodies.size(); ++k) {
    const int j = body_to_q_[k] - offset;
    double tau = u[j];
    if (config_.clamp_torques) tau = std::clamp(tau, -effort_max_[j], effort_max_[j]);
    mb.addJointTorque(static_cast<int>(k) - 1, tau);
  }
  // maxSubSteps = 0: exactly one step of config_.time_step (no interpolation, no accumulator).
  bt_->world->stepSimulation(config_.time_step, 0, config_.time_step);
  ++steps_;
  time_ = static_cast<double>(steps_) * config_.time_step;
  readState();
  if (!q_.allFinite() || !qd_.allFinite()) {
    std::ostringstream os;
    os << "BulletWorld: the simulation diverged at t = " << time_ << " s (non-finite state)";
    throw ReachError(os.str());
  }
  measureContacts();
}

void BulletWorld::clearContacts() {
  for (SoleContact& s : soles_) {
    s.in_contact = false;
    s.num_points = 0;
    s.wrench.setZero();
  }
  non_foot_contacts_.clear();
  leg_contacts_.clear();
  for (int s = 0; s < 2; ++s) soles_[s].sole_pose = framePose(soles_[s].frame);
}

void BulletWorld::measureContacts() {
  clearContacts();

  const double inv_dt = 1.0 / config_.time_step;
  btDispatcher& dispatcher = *bt_->dispatcher;
  const int n_manifolds = dispatcher.getNumManifolds();
  for (int m = 0; m < n_manifolds; ++m) {
    const btPersistentManifold& manifold = *dispatcher.getManifoldByIndexInternal(m);
    const auto* col0 = btMultiBodyLinkCollider::upcast(manifold.getBody0());
    const auto* col1 = btMultiBodyLinkCollider::upcast(manifold.getBody1());
    const bool robot_is_0 = col0 != nullptr && col0->m_multiBody == bt_->multibody.get();
    const btMultiBodyLinkCollider* robot = robot_is_0 ? col0 : col1;
    if (robot == nullptr || robot->m_multiBody != bt_->multibody.get()) continue;
    if (robot_is_0 && col1 != nullptr && col1->m_multiBody == bt_->multibody.get()) {
      recordLegContact(manifold, col0->m_link + 1, col1->m_link + 1);
      continue;
    }
    const int k = robot->m_link + 1;
    const int sole = k == sole_body_[0] ? 0 : (k == sole_body_[1] ? 1 : -1);
    const btTransform body_pose = bt_->bodyPose(k);
    for (int i = 0; i < manifold.getNumContacts(); ++i) {
      const btManifoldPoint& pt = manifold.getContactPoint(i);
      // Bullet's impulses act on body 0 along the normal on body 1 and the friction
      // directions; body 1 receives the opposite.
      btVector3 impulse = pt.m_normalWorldOnB * pt.m_appliedImpulse +
                          pt.m_lateralFrictionDir1 * pt.m_appliedImpulseLateral1 +
                          pt.m_lateralFrictionDir2 * pt.m_appliedImpulseLateral2;
      if (!robot_is_0) impulse = -impulse;
      const bool pushing = pt.m_appliedImpulse > 0.0;
      if (sole >= 0) {
        if (!pushing) continue;
        // The material point of the robot, at the body's pose after the step, so the moment
        // arm and the sole centre are taken at the same instant.
        const btVector3 p_world = body_pose * (robot_is_0 ? pt.m_localPointA : pt.m_localPointB);
        const Eigen::Vector3d f = toEigen(impulse) * inv_dt;
        const Eigen::Vector3d r = toEigen(p_world) - soles_[sole].sole_pose.translation();
        soles_[sole].wrench.head<3>() += f;
        soles_[sole].wrench.tail<3>() += r.cross(f);
        soles_[sole].num_points += 1;
        soles_[sole].in_contact = true;
      } else if (pushing || pt.getDistance() <= 0.0) {
        const SimBody& body = tree_.bodies[k];
        const int child = robot_is_0 ? pt.m_index0 : pt.m_index1;
        const std::string& link = child >= 0 && child < static_cast<int>(body.shapes.size())
                                      ? body.shapes[child].link
                                      : body.name;
        if (std::find(non_foot_contacts_.begin(), non_foot_contacts_.end(), link) ==
            non_foot_contacts_.end()) {
          non_foot_contacts_.push_back(link);
        }
      }
    }
  }
}

void BulletWorld::recordLegContact(const btPersistentManifold& manifold, int body0, int body1) {
  for (int i = 0; i < manifold.getNumContacts(); ++i) {
    const btManifoldPoint& pt = manifold.getContactPoint(i);
    if (!(pt.m_appliedImpulse > 0.0 || pt.getDistance() <= 0.0)) continue;
    const auto link = [&](int k, int child) -> const std::string& {
      const SimBody& body = tree_.bodies[k];
      return child >= 0 && child < static_cast<int>(body.shapes.size()) ? body.shapes[child].link
                                                                        : body.name;
    };
    const std::string a = link(body0, pt.m_index0), b = link(body1, pt.m_index1);
    const std::string pair = a < b ? a + "/" + b : b + "/" + a;
    if (std::find(leg_contacts_.begin(), leg_contacts_.end(), pair) == leg_contacts_.end())
      leg_contacts_.push_back(pair);
  }
}

}  // namespace reach_trajopt
