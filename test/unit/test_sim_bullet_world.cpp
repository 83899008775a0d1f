// The Bullet world (bullet_world.h) against our RobotModel as the independent oracle:
//  - kinematics: every frame's pose in Bullet equals the model's at random configurations;
//  - dynamics: with the ground removed and gravity on, the velocity change of one 1 ms step
//    from 50 random states with random torques equals dt M^-1 (S^T u - b) to 1e-6 (relative);
//  - determinism: two runs of 1000 steps are bit-identical (two worlds, and reset());
//  - contact: a robot standing under a joint PD stays up and its sole wrenches carry its
//    weight (and, with gravity tilted, the friction forces and the moments balance it);
//  - fall detection: a limp robot ends with its pelvis or torso on the ground;
//  - leg self-collision: crossed shanks touch (distance of their axes as the oracle), apart
//    they do not, and nothing without SimConfig::leg_self_collision.
// It also prints the real-time factor of 10 s of standing (no timing assertion).
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>
#include <cstring>
#include <random>

#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/sim/bullet_world.h"

using namespace reach_trajopt;

namespace {

const std::string kUrdf = std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf";

std::shared_ptr<const RobotModel> loadModel(const Eigen::Vector3d& gravity) {
  ModelOptions options;
  options.gravity = gravity;
  return RobotModel::fromUrdfFile(kUrdf, options);
}

Eigen::VectorXd actuated(const RobotModel& model, const Eigen::VectorXd& x) {
  return x.tail(model.nu());
}

// A crouched standing posture with both soles flat on z = 0 (base height from the model).
Eigen::VectorXd standingPosture(const RobotModel& model) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.nq());
  for (const char* side : {"l_", "r_"}) {
    q[model.jointIndex(std::string(side) + "hip_pitch")] = -0.3;
    q[model.jointIndex(std::string(side) + "knee")] = 0.6;
    q[model.jointIndex(std::string(side) + "ankle_pitch")] = -0.3;
  }
  Workspace ws(model);
  model.update(ws, q, Eigen::VectorXd::Zero(model.nq()));
  q[2] = -model.framePose(ws, model.frameId("l_sole")).translation().z();
  return q;
}

// Joint PD toward q_ref (the test's stand-in for a controller).
struct JointPd {
  double kp = 2000.0;  // [Nm/rad]
  double kd = 80.0;    // [Nm s/rad]
  Eigen::VectorXd torque(const RobotModel& model, const Eigen::VectorXd& q_ref,
                         const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const {
    return kp * (actuated(model, q_ref) - actuated(model, q)) - kd * actuated(model, qd);
  }
};

SimConfig defaultConfig(const Eigen::Vector3d& gravity = Eigen::Vector3d(0, 0, -9.81)) {
  SimConfig c;
  c.gravity = gravity;
  return c;
}

/// The biped at rest at standingPosture() (q0) in a world with gravity `g` [m/s^2], the model
/// with the same gravity.
struct StandingRobot {
  std::shared_ptr<const RobotModel> model;
  std::unique_ptr<BulletWorld> world;
  Eigen::VectorXd q0;
};

StandingRobot standingRobot(const Eigen::Vector3d& g = Eigen::Vector3d(0, 0, -9.81)) {
  StandingRobot r;
  r.model = loadModel(g);
  r.world = BulletWorld::fromUrdfFile(kUrdf, *r.model, defaultConfig(g));
  r.q0 = standingPosture(*r.model);
  r.world->reset(r.q0, Eigen::VectorXd::Zero(r.model->nq()));
  return r;
}

}  // namespace

TEST(SimBodyTree, MergesFixedLinksAndKeepsTheMass) {
  const SimBodyTree tree = SimBodyTree::fromUrdfFile(kUrdf);
  const auto model = loadModel(Eigen::Vector3d(0, 0, -9.81));
  EXPECT_TRUE(tree.floating_base);
  EXPECT_EQ(static_cast<int>(tree.bodies.size()), 1 + model->nu());
  EXPECT_NEAR(tree.totalMass(), model->totalMass(), 1e-12);
  // pelvis + torso are one body; the sole frames live on the feet.
  EXPECT_EQ(tree.frame("torso").first, 0);
  EXPECT_EQ(tree.bodies[tree.frame("l_sole").first].name, "l_foot");
  EXPECT_EQ(tree.bodies[tree.frame("r_sole").first].name, "r_foot");
  for (const SimBody& b : tree.bodies) {
    // The principal frame diagonalizes the merged inertia.
    const Eigen::Matrix3d R = b.principal.linear();
    const Eigen::Matrix3d D = R.transpose() * b.inertia * R;
    EXPECT_LT((D - Eigen::Matrix3d(b.principal_inertia.asDiagonal())).norm(), 1e-12) << b.name;
  }
  EXPECT_THROW(SimBodyTree::fromUrdfFile("/nonexistent.urdf"), ReachError);
  EXPECT_THROW(SimBodyTree::fromUrdfString("<robot name='x'><link", "<bad>"), ReachError);
  EXPECT_THROW(tree.frame("no_such_link"), ReachError);
}

TEST(SimBulletWorld, FramePosesMatchTheModel) {
  const auto model = loadModel(Eigen::Vector3d(0, 0, -9.81));
  auto world = BulletWorld::fromUrdfFile(kUrdf, *model, defaultConfig());
  Workspace ws(*model);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd q(model->nq());
    for (int i = 0; i < model->nq(); ++i) {
      const JointInfo& j = model->joints()[i];
      q[i] = j.is_virtual ? (2 * U(rng) - 1) * (i == 4 ? 1.2 : 3.0)
                          : j.q_min + U(rng) * (j.q_max - j.q_min);
    }
    const Eigen::VectorXd qd = Eigen::VectorXd::Zero(model->nq());
    world->reset(q, qd);
    EXPECT_LT((world->q() - q).cwiseAbs().maxCoeff(), 1e-12);
    model->update(ws, q, qd);
    int compared = 0;
    for (const auto& kv : world->bodyTree().frames) {
      if (!model->hasFrame(kv.first)) continue;
      const Eigen::Isometry3d Tm = model->framePose(ws, model->frameId(kv.first));
      const Eigen::Isometry3d Ts = world->framePose(kv.first);
      EXPECT_LT((Tm.matrix() - Ts.matrix()).cwiseAbs().maxCoeff(), 1e-12) << kv.first;
      ++compared;
    }
    EXPECT_GE(compared, 1 + model->nu() + 2);  // every body and the two soles
  }
}

TEST(SimBulletWorld, FreeFallStepMatchesModelDynamics) {
  const Eigen::Vector3d g(0, 0, -9.81);
  const auto model = loadModel(g);
  SimConfig config = defaultConfig(g);
  config.contacts = false;            // no ground
  config.joint_limits = false;        // only eq. (1), no limit impulses
  config.leg_self_collision = false;  // random postures cross the legs
  auto world = BulletWorld::fromUrdfFile(kUrdf, *model, config);
  const double dt = world->timeStep();
  const BaseCoordinates& coords = world->baseCoordinates();
  Workspace ws(*model);
  Eigen::MatrixXd M(model->nq(), model->nq());
  Eigen::VectorXd b(model->nq());
  const Eigen::MatrixXd S = model->selectionMatrix();
  const Eigen::VectorXd u_max = model->effortLimits();

  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  double worst = 0.0;
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::VectorXd q(model->nq()), qd(model->nq()), u(model->nu());
    for (int i = 0; i < model->nq(); ++i) {
      const JointInfo& j = model->joints()[i];
      if (j.is_virtual) {
        q[i] = i < 3 ? U(rng) : (i == 4 ? 1.2 : 3.0) * U(rng);
        qd[i] = 1.5 * U(rng);
      } else {
        q[i] = 0.5 * (j.q_min + j.q_max) + 0.5 * (j.q_max - j.q_min) * U(rng);
        qd[i] = 3.0 * U(rng);
      }
    }
    for (int i = 0; i < model->nu(); ++i) u[i] = u_max[i] * U(rng);

    world->reset(q, qd);
    const BaseBodyState body0 = world->baseBodyState();
    const Eigen::VectorXd qd0 = world->qd();
    const Eigen::VectorXd q0 = world->q();
    world->step(u);
    const BaseBodyState body1 = world->baseBodyState();

    // Bullet: qd+ = qd + dt qdd(q, qd, u) with the base velocities in world coordinates (the
    // base body's centre of mass and angular velocity). Its qdd, mapped to our coordinates at
    // the initial state exactly (no O(dt) error from the Euler-angle chart):
    BaseBodyAcceleration acc;
    acc.linear = (body1.linear_velocity - body0.linear_velocity) / dt;
    acc.angular = (body1.angular_velocity - body0.angular_velocity) / dt;
    Eigen::VectorXd qdd_sim(model->nq());
    qdd_sim.head<6>() = coords.accelerationToVirtual(q0.head<6>(), qd0.head<6>(), acc);
    qdd_sim.tail(model->nu()) = (world->qd() - qd0).tail(model->nu()) / dt;

    model->update(ws, q, qd);
    model->massMatrix(ws, M);
    model->bias(ws, b);
    const Eigen::VectorXd qdd_model = M.ldlt().solve(S.transpose() * u - b);
    const double err = (qdd_sim - qdd_model).norm() / std::max(1.0, qdd_model.norm());
    worst = std::max(worst, err);
    EXPECT_LT(err, 1e-6) << "trial " << trial << "\n sim   " << qdd_sim.transpose() << "\n model "
                         << qdd_model.transpose();

    // Semi-implicit Euler: the joint positions move with the NEW velocities.
    const Eigen::VectorXd dq = (world->q() - q0).tail(model->nu());
    EXPECT_LT((dq - dt * world->qd().tail(model->nu())).cwiseAbs().maxCoeff(), 1e-13);
    // No ground, no contacts.
    EXPECT_FALSE(world->soleContacts()[0].in_contact);
    EXPECT_TRUE(world->nonFootContacts().empty());
  }
  std::printf("[sim] free-fall step vs M^-1 (S^T u - b): worst relative error %.3g\n", worst);
}

TEST(SimBulletWorld, TorquesLastOneStep) {
  // A torque applied in one step must not leak into the next (Bullet clears its forces).
  const auto model = loadModel(Eigen::Vector3d::Zero());
  SimConfig config = defaultConfig(Eigen::Vector3d::Zero());
  config.contacts = false;
  auto world = BulletWorld::fromUrdfFile(kUrdf, *model, config);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model->nq());
  q[model->jointIndex("l_knee")] = 0.5;
  world->reset(q, Eigen::VectorXd::Zero(model->nq()));
  Eigen::VectorXd u = Eigen::VectorXd::Zero(model->nu());
  u[model->jointIndex("l_knee") - 6] = 10.0;
  world->step(u);
  const Eigen::VectorXd qd1 = world->qd();
  EXPECT_GT(std::abs(qd1[model->jointIndex("l_knee")]), 0.0);
  // Zero gravity, zero torque: momentum is conserved, so the free system keeps drifting;
  // compare the second step with a fresh world started from the state after the first.
  world->step(Eigen::VectorXd::Zero(model->nu()));
  auto fresh = BulletWorld::fromUrdfFile(kUrdf, *model, config);
  fresh->reset(q, Eigen::VectorXd::Zero(model->nq()));
  fresh->step(u);
  fresh->step(Eigen::VectorXd::Zero(model->nu()));
  EXPECT_EQ(fresh->qd(), world->qd());
  auto pushed_twice = BulletWorld::fromUrdfFile(kUrdf, *model, config);
  pushed_twice->reset(q, Eigen::VectorXd::Zero(model->nq()));
  pushed_twice->step(u);
  pushed_twice->step(u);
  EXPECT_GT((pushed_twice->qd() - world->qd()).norm(), 1e-3);
}

TEST(SimBulletWorld, DeterministicBitForBit) {
  const auto model = loadModel(Eigen::Vector3d(0, 0, -9.81));
  const JointPd pd;
  Eigen::VectorXd q0 = standingPosture(*model);
  q0[2] += 0.02;  // dropped from 2 cm: contacts appear and change during the run
  q0[5] = 0.05;   // rolled: lands on one foot first
  const Eigen::VectorXd qd0 = Eigen::VectorXd::Zero(model->nq());
  int contact_steps = 0;  // steps with a sole on the ground, over every run
  auto run = [&](BulletWorld& world) {
    world.reset(q0, qd0);
    Eigen::MatrixXd trace(2 * model->nq(), 1000);
    for (int k = 0; k < 1000; ++k) {
      world.step(pd.torque(*model, q0, world.q(), world.qd()));
      trace.col(k) << world.q(), world.qd();
      contact_steps += world.soleContacts()[0].in_contact || world.soleContacts()[1].in_contact;
    }
    return trace;
  };
  auto a = BulletWorld::fromUrdfFile(kUrdf, *model, defaultConfig());
  auto b = BulletWorld::fromUrdfFile(kUrdf, *model, defaultConfig());
  const Eigen::MatrixXd ta = run(*a);
  const Eigen::MatrixXd tb = run(*b);
  const Eigen::MatrixXd ta2 = run(*a);  // the same world again, after reset()
  ASSERT_EQ(ta.size(), tb.size());
  EXPECT_EQ(0, std::memcmp(ta.data(), tb.data(), sizeof(double) * ta.size()));
  EXPECT_EQ(0, std::memcmp(ta.data(), ta2.data(), sizeof(double) * ta.size()));
  EXPECT_GT(contact_steps, 1000) << "the runs must land on the ground";
}

TEST(SimBulletWorld, StandingUnderPdCarriesTheWeight) {
  auto [model, world, q0] = standingRobot();
  const JointPd pd;
  const double weight = model->totalMass() * 9.81;
  Vector6d mean = Vector6d::Zero();
  const int n_steps = 3000, n_avg = 200;
  for (int k = 0; k < n_steps; ++k) {
    world->step(pd.torque(*model, q0, world->q(), world->qd()));
    ASSERT_TRUE(world->nonFootContacts().empty()) << "fell at step " << k;
    if (k >= n_steps - n_avg) {
      for (const SoleContact& s : world->soleContacts()) mean.head<3>() += s.wrench.head<3>();
    }
  }
  mean /= n_avg;
  const SoleContact& left = world->soleContacts()[0];
  const SoleContact& right = world->soleContacts()[1];
  EXPECT_TRUE(left.in_contact);
  EXPECT_TRUE(right.in_contact);
  // Stays up: pelvis within 3 cm of its start, soles on the ground.
  EXPECT_LT((world->q().head<3>() - q0.head<3>()).norm(), 0.03);
  EXPECT_NEAR(left.sole_pose.translation().z(), 0.0, 5e-3);
  // The ground carries the weight once settled.
  EXPECT_NEAR(mean[2], weight, 0.03 * weight);
  EXPECT_LT(mean.head<2>().norm(), 0.01 * weight);
  // Last step alone, too.
  const double fz = left.wrench[2] + right.wrench[2];
  EXPECT_NEAR(fz, weight, 0.03 * weight);
  // Each sole's centre of pressure lies under the sole (half sizes 0.135 x 0.08 m).
  for (const SoleContact& s : world->soleContacts()) {
    const Eigen::Matrix3d R = s.sole_pose.linear();
    const Eigen::Vector3d f = R.transpose() * s.wrench.head<3>();
    const Eigen::Vector3d tau = R.transpose() * s.wrench.tail<3>();
    ASSERT_GT(f.z(), 0.0) << s.frame;
    EXPECT_LE(std::abs(-tau.y() / f.z()), 0.135 + 1e-6) << s.frame;
    EXPECT_LE(std::abs(tau.x() / f.z()), 0.08 + 1e-6) << s.frame;
    EXPECT_GT(s.num_points, 0);
  }
  std::printf("[sim] standing: sum fz %.2f N, weight %.2f N (%.3f%%), pelvis drift %.4f m\n", fz,
              weight, 100.0 * (fz - weight) / weight, (world->q().head<3>() - q0.head<3>()).norm());
}

TEST(SimBulletWorld, TiltedGravityFrictionAndMomentsBalance) {
  // Gravity with a horizontal part (a 3 degree slope; the crouched posture has its CoM a few
  // cm behind the sole centres, so a larger backward tilt tips it over): static friction must
  // hold the robot, so the sole forces equal -m g and their moments about the CoM cancel.
  const Eigen::Vector3d g(0.4, 0.3, -9.80);
  auto [model, world, q0] = standingRobot(g);
  const JointPd pd;
  const int n_steps = 3000, n_avg = 200;
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
  Workspace ws(*model);
  for (int k = 0; k < n_steps; ++k) {
    world->step(pd.torque(*model, q0, world->q(), world->qd()));
    ASSERT_TRUE(world->nonFootContacts().empty());
    if (k >= n_steps - n_avg) {
      model->update(ws, world->q(), world->qd());
      const Eigen::Vector3d com = model->centerOfMass(ws);
      for (const SoleContact& s : world->soleContacts()) {
        force += s.wrench.head<3>();
        moment += s.wrench.tail<3>() + (s.sole_pose.translation() - com).cross(s.wrench.head<3>());
      }
    }
  }
  force /= n_avg;
  moment /= n_avg;
  const Eigen::Vector3d mg = model->totalMass() * g;
  EXPECT_LT((force + mg).norm(), 0.03 * mg.norm()) << force.transpose();
  EXPECT_LT((force.head<2>() + mg.head<2>()).norm(), 0.05 * mg.head<2>().norm());
  // Moments about the CoM: compare with the weight times 1 cm.
  EXPECT_LT(moment.norm(), 0.01 * mg.norm()) << moment.transpose();
  EXPECT_LT(world->qd().head<3>().norm(), 0.01);  // not sliding
  std::printf(
      "[sim] tilted gravity: |f + m g| = %.3f N of |m g| = %.1f N, |moment about CoM| = "
      "%.3f Nm\n",
      (force + mg).norm(), mg.norm(), moment.norm());
}

TEST(SimBulletWorld, LimpRobotFallsOntoPelvisOrTorso) {
  const auto model = loadModel(Eigen::Vector3d(0, 0, -9.81));
  auto world = BulletWorld::fromUrdfFile(kUrdf, *model, defaultConfig());
  world->reset(standingPosture(*model), Eigen::VectorXd::Zero(model->nq()));
  bool fell = false;
  for (int k = 0; k < 4000 && !fell; ++k) {
    world->step(Eigen::VectorXd::Zero(model->nu()));
    for (const std::string& link : world->nonFootContacts())
      fell = fell || link == "pelvis" || link == "torso";
  }
  EXPECT_TRUE(fell);
}

TEST(SimBulletWorld, ContactsAndGravitySwitches) {
  auto [model, world, q0] = standingRobot();
  world->setContactsEnabled(false);
  for (int k = 0; k < 100; ++k) world->step(Eigen::VectorXd::Zero(model->nu()));
  // 0.1 s of free fall through the missing ground: z drops by g t^2 / 2 (no contact at all).
  EXPECT_NEAR(world->q()[2] - q0[2], -0.5 * 9.81 * 0.1 * 0.1, 2e-3);
  EXPECT_FALSE(world->soleContacts()[0].in_contact);
  // Zero gravity, zero velocity, zero torque: nothing moves.
  world->setGravity(Eigen::Vector3d::Zero());
  world->reset(q0, Eigen::VectorXd::Zero(model->nq()));
  for (int k = 0; k < 10; ++k) world->step(Eigen::VectorXd::Zero(model->nu()));
  EXPECT_LT((world->q() - q0).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_EQ(world->time(), 10 * world->timeStep());
}

TEST(SimBulletWorld, RejectsBadInput) {
  const auto model = loadModel(Eigen::Vector3d(0, 0, -9.81));
  auto world = BulletWorld::fromUrdfFile(kUrdf, *model, defaultConfig());
  EXPECT_THROW(world->step(Eigen::VectorXd::Zero(3)), ReachError);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(model->nu());
  u[2] = std::nan("");
  EXPECT_THROW(world->step(u), ReachError);
  EXPECT_THROW(world->reset(Eigen::VectorXd::Zero(4), Eigen::VectorXd::Zero(4)), ReachError);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model->nq());
  q[4] = M_PI / 2;  // gimbal lock
  EXPECT_THROW(world->reset(q, Eigen::VectorXd::Ones(model->nq())), ReachError);
  SimConfig bad = defaultConfig();
  bad.left_sole_frame = "no_such_frame";
  EXPECT_THROW(BulletWorld::fromUrdfFile(kUrdf, *model, bad), ReachError);
  bad = defaultConfig();
  bad.time_step = 0.0;
  EXPECT_THROW(BulletWorld::fromUrdfFile(kUrdf, *model, bad), ReachError);
  const SimBodyTree tree = SimBodyTree::fromUrdfFile(kUrdf);
  EXPECT_THROW(BulletWorld(tree, {"l_knee"}, defaultConfig()), ReachError);
}

TEST(SimBulletWorld, RealTimeFactorOfStandingTenSeconds) {
  // Reported, not asserted (speed belongs in benchmarks).
  auto [model, world, q0] = standingRobot();
  const JointPd pd;
  const int n_steps = static_cast<int>(std::lround(10.0 / world->timeStep()));
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < n_steps; ++k) world->step(pd.torque(*model, q0, world->q(), world->qd()));
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_TRUE(world->nonFootContacts().empty());
  std::printf(
      "[sim] 10 s standing under joint PD: wall %.3f s, real-time factor %.1fx "
      "(%.1f us/step)\n",
      wall, 10.0 / wall, 1e6 * wall / n_steps);
}

namespace {

// Shortest distance between the segments [a0, a1] and [b0, b1] (sampled finely: a test oracle
// independent of Bullet's collision code) [m].
double segmentDistance(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                       const Eigen::Vector3d& b0, const Eigen::Vector3d& b1) {
  double best = 1e9;
  for (int i = 0; i <= 200; ++i)
    for (int j = 0; j <= 200; ++j)
      best =
          std::min(best, ((a0 + (a1 - a0) * (i / 200.0)) - (b0 + (b1 - b0) * (j / 200.0))).norm());
  return best;
}

// The axis of a shank's collision cylinder (urdf/biped.urdf: centre 0.23 m below the knee,
// length 0.34 m, along the shank's z) in the world.
void shankAxis(const RobotModel& model, Workspace& ws, const char* side, Eigen::Vector3d& top,
               Eigen::Vector3d& bottom) {
  const Eigen::Isometry3d T = model.framePose(ws, model.frameId(std::string(side) + "shank"));
  top = T * Eigen::Vector3d(0, 0, -0.23 + 0.17);
  bottom = T * Eigen::Vector3d(0, 0, -0.23 - 0.17);
}

}  // namespace

TEST(SimBulletWorld, LegsCollideWithEachOtherOnly) {
  // No ground, no gravity: the only contacts are between the robot's own shapes. The right hip
  // rolled inward to its limit puts the right shank through the left one (distance of the
  // cylinder axes below the sum of the radii, 0.045 + 0.045 m); the standing posture keeps
  // them apart. Bullet must report the first and not the second, and nothing without leg
  // self-collision.
  const auto model = loadModel(Eigen::Vector3d::Zero());
  SimConfig config = defaultConfig(Eigen::Vector3d::Zero());
  config.contacts = false;
  Eigen::VectorXd crossed = standingPosture(*model);
  crossed[model->jointIndex("r_hip_roll")] = 0.35;
  crossed[model->jointIndex("r_hip_yaw")] = 0.0;
  const Eigen::VectorXd standing = standingPosture(*model);
  Workspace ws(*model);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model->nq());
  const auto shankGap = [&](const Eigen::VectorXd& q) {
    model->update(ws, q, zero);
    Eigen::Vector3d l0, l1, r0, r1;
    shankAxis(*model, ws, "l_", l0, l1);
    shankAxis(*model, ws, "r_", r0, r1);
    return segmentDistance(l0, l1, r0, r1) - 2 * 0.045;
  };
  ASSERT_LT(shankGap(crossed), -0.01) << "the test posture must cross the shanks";
  ASSERT_GT(shankGap(standing), 0.05);

  auto world = BulletWorld::fromUrdfFile(kUrdf, *model, config);
  // Leg membership: every l_ body on the left leg, every r_ body on the right, the root on none.
  const SimBodyTree& tree = world->bodyTree();
  for (size_t k = 0; k < tree.bodies.size(); ++k) {
    const std::string& name = tree.bodies[k].name;
    const int expected = name.rfind("l_", 0) == 0 ? 0 : (name.rfind("r_", 0) == 0 ? 1 : -1);
    EXPECT_EQ(world->bodyLegs()[k], expected) << name;
  }
  world->reset(standing, zero);
  world->step(Eigen::VectorXd::Zero(model->nu()));
  EXPECT_TRUE(world->legContacts().empty()) << world->legContacts().front();
  world->reset(crossed, zero);
  world->step(Eigen::VectorXd::Zero(model->nu()));
  ASSERT_FALSE(world->legContacts().empty());
  EXPECT_NE(std::find(world->legContacts().begin(), world->legContacts().end(), "l_shank/r_shank"),
            world->legContacts().end())
      << world->legContacts().front();
  EXPECT_TRUE(world->nonFootContacts().empty());

  config.leg_self_collision = false;
  auto apart = BulletWorld::fromUrdfFile(kUrdf, *model, config);
  apart->reset(crossed, zero);
  apart->step(Eigen::VectorXd::Zero(model->nu()));
  EXPECT_TRUE(apart->legContacts().empty());
  for (int leg : apart->bodyLegs()) EXPECT_EQ(leg, -1);
}

TEST(SimBulletWorld, APushChangesTheComVelocityByItsDelta) {
  // pushBase adds its delta to every link's velocity: our model's CoM velocity J_com qd (an
  // independent computation from the simulator's state) changes by exactly the delta, and
  // the joint velocities do not change.
  const auto model = loadModel(Eigen::Vector3d(0, 0, -9.81));
  auto world = BulletWorld::fromUrdfFile(kUrdf, *model, defaultConfig());
  Workspace ws(*model);
  Eigen::Matrix3Xd Jc(3, model->nq());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const Eigen::VectorXd q = standingPosture(*model);
  Eigen::VectorXd qd(model->nq());
  for (int i = 0; i < model->nq(); ++i) qd[i] = 0.3 * U(rng);
  world->reset(q, qd);
  const auto comVelocity = [&]() {
    model->update(ws, world->q(), world->qd());
    model->centerOfMassJacobian(ws, Jc);
    return Eigen::Vector3d(Jc * world->qd());
  };
  const Eigen::Vector3d before = comVelocity();
  const Eigen::VectorXd joints_before = world->qd().tail(model->nu());
  const Eigen::Vector3d delta(0.4, -0.25, 0.05);
  world->pushBase(delta);
  EXPECT_LT((comVelocity() - before - delta).norm(), 1e-9);
  EXPECT_LT((world->qd().tail(model->nu()) - joints_before).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_THROW(world->pushBase(Eigen::Vector3d(NAN, 0, 0)), ReachError);
}
