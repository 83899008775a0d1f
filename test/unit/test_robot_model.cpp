// Robot model: URDF sanity (inertias, sole frames), clear errors, and the analytic quantities
// against independent computations (finite differences of kinematics, inverse dynamics columns,
// a one-joint pendulum in closed form). The Pinocchio comparison is test/oracle/.

#include <gtest/gtest.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>

#include "reach_trajopt/model/robot_model.h"

using namespace reach_trajopt;

namespace {

const std::string kUrdf = std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf";

Eigen::VectorXd randomState(const RobotModel& model, std::mt19937& rng, bool velocity) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::VectorXd x(model.nq());
  for (int i = 0; i < model.nq(); ++i) {
    const auto& j = model.joints()[i];
    if (velocity) {
      x[i] = (2 * u(rng) - 1) * 2.0;
    } else if (j.is_virtual) {
      x[i] = (2 * u(rng) - 1) * (j.is_prismatic ? 1.0 : 1.2);
    } else {
      x[i] = j.q_min + u(rng) * (j.q_max - j.q_min);
    }
  }
  return x;
}

/// Runs `check(q, qd)` for `trials` random states (q then qd drawn by randomState from a
/// generator seeded `seed`), each after model.update(ws, q, qd).
template <typename Check>
void forRandomStates(const RobotModel& model, Workspace& ws, unsigned seed, int trials,
                     Check&& check) {
  std::mt19937 rng(seed);
  for (int trial = 0; trial < trials; ++trial) {
    const Eigen::VectorXd q = randomState(model, rng, false);
    const Eigen::VectorXd qd = randomState(model, rng, true);
    model.update(ws, q, qd);
    check(q, qd);
  }
}

/// Log map of a rotation as a 3-vector (small angles), for finite differences of orientation.
Eigen::Vector3d rotationDelta(const Eigen::Matrix3d& R1, const Eigen::Matrix3d& R0) {
  const Eigen::AngleAxisd aa(R1 * R0.transpose());
  return aa.angle() * aa.axis();
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST(BipedUrdf, InertiasArePhysicallyValidAndSolesExist) {
  const auto urdf = urdf::parseURDFFile(kUrdf);
  ASSERT_TRUE(urdf);
  double mass = 0.0;
  for (const auto& kv : urdf->links_) {
    const auto& in = kv.second->inertial;
    if (!in) continue;
    mass += in->mass;
    Eigen::Matrix3d I;
    I << in->ixx, in->ixy, in->ixz, in->ixy, in->iyy, in->iyz, in->ixz, in->iyz, in->izz;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(I);
    const Eigen::Vector3d ev = es.eigenvalues();
    EXPECT_GT(in->mass, 0.0) << kv.first;
    EXPECT_GT(ev.minCoeff(), 0.0) << kv.first << ": inertia not positive definite";
    // Triangle inequality on the principal moments.
    EXPECT_GE(ev[0] + ev[1], ev[2] - 1e-12) << kv.first;
    EXPECT_GE(ev[0] + ev[2], ev[1] - 1e-12) << kv.first;
    EXPECT_GE(ev[1] + ev[2], ev[0] - 1e-12) << kv.first;
  }
  EXPECT_GE(mass, 60.0);
  EXPECT_LE(mass, 130.0);
  EXPECT_TRUE(urdf->getLink("l_sole"));
  EXPECT_TRUE(urdf->getLink("r_sole"));
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  EXPECT_EQ(model->nu(), 12);
  EXPECT_EQ(model->nq(), 18);
  EXPECT_NEAR(model->totalMass(), mass, 1e-9);
  for (const auto& j : model->joints()) {
    if (j.is_virtual) continue;
    EXPECT_LT(j.q_min, j.q_max) << j.name;
    EXPECT_GT(j.qd_max, 0.0) << j.name;
    EXPECT_GT(j.effort_max, 0.0) << j.name;
  }
}

TEST(RobotModel, StandingCoMIsNearOneMetre) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  Workspace ws(*model);
  Eigen::VectorXd q = model->neutralConfiguration();
  model->update(ws, q, Eigen::VectorXd::Zero(model->nq()));
  const double sole_z = model->framePose(ws, model->frameId("l_sole")).translation().z();
  const double com_height = model->centerOfMass(ws).z() - sole_z;
  EXPECT_GT(com_height, 0.9);
  EXPECT_LT(com_height, 1.2);
}

TEST(RobotModel, ClearErrors) {
  try {
    RobotModel::fromUrdfFile("/nonexistent/robot.urdf");
    FAIL() << "no throw";
  } catch (const ReachError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/robot.urdf"), std::string::npos);
  }
  EXPECT_THROW(RobotModel::fromUrdfString("<robot name='x'><link name='a'>", {}, "broken.urdf"),
               ReachError);
  EXPECT_THROW(RobotModel::fromUrdfString("not xml at all", {}, "junk"), ReachError);
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  try {
    model->frameId("l_sol");
    FAIL() << "no throw";
  } catch (const ReachError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown frame 'l_sol'"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("biped.urdf"), std::string::npos);
  }
  Workspace ws(*model);
  Eigen::VectorXd q = model->neutralConfiguration(), qd = Eigen::VectorXd::Zero(model->nq());
  EXPECT_THROW(model->update(ws, q.head(5), qd), ReachError);
  EXPECT_THROW(model->update(ws, q, qd.head(17)), ReachError);
  q[7] = std::nan("");
  try {
    model->update(ws, q, qd);
    FAIL() << "no throw";
  } catch (const ReachError& e) {
    EXPECT_NE(std::string(e.what()).find("non-finite"), std::string::npos);
  }
  // Queries before update() are an error, not garbage.
  Workspace fresh(*model);
  Eigen::MatrixXd M(model->nq(), model->nq());
  EXPECT_THROW(model->massMatrix(fresh, M), ReachError);
  // A joint with a NaN limit or an inverted range is reported.
  std::string xml = readFile(kUrdf);
  const std::string bad =
      std::regex_replace(xml, std::regex("lower=\"0\" upper=\"2.4\""), "lower=\"2.4\" upper=\"0\"");
  EXPECT_THROW(RobotModel::fromUrdfString(bad, {}, "inverted.urdf"), ReachError);
}

TEST(RobotModel, MassMatrixAndBiasMatchInverseDynamics) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  Workspace ws(*model);
  const int n = model->nq();
  forRandomStates(*model, ws, 7, 20, [&](const Eigen::VectorXd&, const Eigen::VectorXd&) {
    Eigen::MatrixXd M(n, n);
    Eigen::VectorXd b(n), tau(n), tau0(n);
    model->massMatrix(ws, M);
    model->bias(ws, b);
    model->inverseDynamics(ws, Eigen::VectorXd::Zero(n), tau0);
    EXPECT_LT((tau0 - b).norm(), 1e-9 * (1 + b.norm()));
    for (int k = 0; k < n; ++k) {
      model->inverseDynamics(ws, Eigen::VectorXd::Unit(n, k), tau);
      EXPECT_LT((tau - b - M.col(k)).norm(), 1e-9 * (1 + M.norm())) << "column " << k;
    }
    EXPECT_LT((M - M.transpose()).norm(), 1e-12 * M.norm());
    Eigen::LLT<Eigen::MatrixXd> llt(M);
    EXPECT_EQ(llt.info(), Eigen::Success) << "M not positive definite";
  });
}

TEST(RobotModel, VelocityOnlyUpdateGivesTheBitsOfAFullUpdate) {
  // updateVelocity (the backward step's children share their parent's q) against update at
  // the same (q, qd): the bias, a sole's velocity and Jdot qd must be identical, not close.
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  Workspace full(*model), fast(*model);
  std::mt19937 rng(11);
  const int n = model->nq();
  const FrameId sole = model->frameId("l_sole");
  EXPECT_THROW(model->updateVelocity(fast, Eigen::VectorXd::Zero(n)), ReachError);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = randomState(*model, rng, false);
    model->update(fast, q, randomState(*model, rng, true));
    for (int child = 0; child < 3; ++child) {
      const Eigen::VectorXd qd = randomState(*model, rng, true);
      model->update(full, q, qd);
      model->updateVelocity(fast, qd);
      Eigen::VectorXd b_full(n), b_fast(n);
      model->bias(full, b_full);
      model->bias(fast, b_fast);
      EXPECT_TRUE(b_full == b_fast) << "trial " << trial;
      EXPECT_TRUE(model->frameVelocity(full, sole) == model->frameVelocity(fast, sole));
      EXPECT_TRUE(model->frameJdotQd(full, sole) == model->frameJdotQd(fast, sole));
    }
  }
  Eigen::VectorXd bad = Eigen::VectorXd::Zero(n);
  bad[0] = std::nan("");
  EXPECT_THROW(model->updateVelocity(fast, bad), ReachError);
  EXPECT_THROW(model->updateVelocity(fast, Eigen::VectorXd::Zero(n + 1)), ReachError);
}

TEST(RobotModel, JacobianAndJdotQdMatchFiniteDifferences) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  Workspace ws(*model);
  std::mt19937 rng(11);
  const int n = model->nq();
  const double h = 1e-6;
  for (const char* name : {"l_sole", "r_sole", "torso", "pelvis"}) {
    const FrameId id = model->frameId(name);
    for (int trial = 0; trial < 10; ++trial) {
      const Eigen::VectorXd q = randomState(*model, rng, false);
      const Eigen::VectorXd qd = randomState(*model, rng, true);
      model->update(ws, q, qd);
      Matrix6Xd J(6, n);
      model->frameJacobian(ws, id, J);
      const Vector6d jdqd = model->frameJdotQd(ws, id);
      // d/dt pose along q + t qd equals J qd (linear velocity, angular velocity in the world).
      model->update(ws, q + h * qd, qd);
      const Eigen::Isometry3d Tp = model->framePose(ws, id);
      Matrix6Xd Jp(6, n);
      model->frameJacobian(ws, id, Jp);
      model->update(ws, q - h * qd, qd);
      const Eigen::Isometry3d Tm = model->framePose(ws, id);
      Matrix6Xd Jm(6, n);
      model->frameJacobian(ws, id, Jm);
      Vector6d vel_fd;
      vel_fd.head<3>() = (Tp.translation() - Tm.translation()) / (2 * h);
      vel_fd.tail<3>() = rotationDelta(Tp.linear(), Tm.linear()) / (2 * h);
      EXPECT_LT((J * qd - vel_fd).norm(), 1e-6 * (1 + vel_fd.norm())) << name;
      // Jdot qd = d/dt (J(q(t))) qd with qdd = 0.
      const Vector6d jdqd_fd = (Jp - Jm) * qd / (2 * h);
      EXPECT_LT((jdqd - jdqd_fd).norm(), 1e-5 * (1 + jdqd_fd.norm())) << name;
    }
  }
}

TEST(RobotModel, CoMJacobianMatchesFiniteDifferences) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  Workspace ws(*model);
  std::mt19937 rng(3);
  const int n = model->nq();
  const Eigen::VectorXd q = randomState(*model, rng, false);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  model->update(ws, q, zero);
  Eigen::Matrix3Xd Jc(3, n);
  model->centerOfMassJacobian(ws, Jc);
  for (int k = 0; k < n; ++k) {
    model->update(ws, q + 1e-6 * Eigen::VectorXd::Unit(n, k), zero);
    const Eigen::Vector3d cp = model->centerOfMass(ws);
    model->update(ws, q - 1e-6 * Eigen::VectorXd::Unit(n, k), zero);
    const Eigen::Vector3d cm = model->centerOfMass(ws);
    EXPECT_LT((Jc.col(k) - (cp - cm) / 2e-6).norm(), 1e-7) << "column " << k;
  }
}

TEST(RobotModel, SimplePendulumIsExact) {
  // A point-like mass m on a massless rod of length l about y, fixed base:
  // M = m l^2 + I_yy, b = m g l sin(theta) (theta = 0 hanging down).
  const std::string xml = R"(<robot name="pendulum">
    <link name="world"/>
    <link name="bob"><inertial><origin xyz="0 0 -0.7"/><mass value="2.0"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.01"/></inertial></link>
    <joint name="hinge" type="continuous"><parent link="world"/><child link="bob"/>
      <origin xyz="0 0 1"/><axis xyz="0 1 0"/></joint></robot>)";
  const auto model = RobotModel::fromUrdfString(xml, {}, "pendulum");
  ASSERT_FALSE(model->floatingBase());
  ASSERT_EQ(model->nq(), 1);
  Workspace ws(*model);
  Eigen::VectorXd q(1), qd(1), b(1);
  Eigen::MatrixXd M(1, 1);
  q << 0.4;
  qd << 1.5;
  model->update(ws, q, qd);
  model->massMatrix(ws, M);
  model->bias(ws, b);
  EXPECT_NEAR(M(0, 0), 2.0 * 0.49 + 0.02, 1e-12);
  EXPECT_NEAR(b[0], 2.0 * 9.81 * 0.7 * std::sin(0.4), 1e-12);
}

TEST(RobotModel, CoMJdotQdMatchesFiniteDifferences) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  Workspace ws(*model);
  const int n = model->nq();
  forRandomStates(*model, ws, 5, 10, [&](const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
    const Eigen::Vector3d drift = model->centerOfMassJdotQd(ws);
    Eigen::Matrix3Xd Jp(3, n), Jm(3, n);
    const double h = 1e-6;
    model->update(ws, q + h * qd, qd);
    model->centerOfMassJacobian(ws, Jp);
    model->update(ws, q - h * qd, qd);
    model->centerOfMassJacobian(ws, Jm);
    const Eigen::Vector3d fd = (Jp - Jm) * qd / (2 * h);
    EXPECT_LT((drift - fd).norm(), 1e-5 * (1 + fd.norm()));
  });
}
