// RneaDerivatives (model/rnea_derivatives.h) against central finite differences of
// RobotModel::inverseDynamics, on the shipped biped (floating base) and on a small branched tree
// with a prismatic joint (fixed base). The Pinocchio comparison is
// test/oracle/test_rnea_derivatives.py.
//
// Tolerance: central differences with step h have truncation error O(h^2 |d3 tau|) and roundoff
// O(eps |tau| / h); with h = 1e-5 and |tau| up to ~1e3 N m both are below ~1e-6, so the entries
// must agree to 1e-5 relative to max(1, |column|).

#include <gtest/gtest.h>

#include <random>

#include "reach_trajopt/model/rnea_derivatives.h"
#include "reach_trajopt/model/robot_model.h"

using namespace reach_trajopt;

namespace {

const std::string kUrdf = std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf";

// A fixed-base tree: a prismatic slider carrying two revolute branches, offset inertias.
const char* kTree = R"(<robot name="tree">
  <link name="world"/>
  <link name="slider"><inertial><origin xyz="0.1 0 0.05" rpy="0.1 0.2 0.3"/><mass value="2"/>
    <inertia ixx="0.1" ixy="0.01" ixz="0" iyy="0.2" iyz="0.02" izz="0.15"/></inertial></link>
  <link name="a"><inertial><origin xyz="0 0.2 0" rpy="0 0 0"/><mass value="1.5"/>
    <inertia ixx="0.05" ixy="0" ixz="0.01" iyy="0.04" iyz="0" izz="0.03"/></inertial></link>
  <link name="b"><inertial><origin xyz="0.3 0 -0.1" rpy="0.5 0 0"/><mass value="1"/>
    <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.04"/></inertial></link>
  <link name="c"><inertial><origin xyz="0 0 0.2" rpy="0 0 0"/><mass value="0.7"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.02"/></inertial></link>
  <joint name="j0" type="prismatic"><parent link="world"/><child link="slider"/>
    <origin xyz="0 0 1" rpy="0 0.3 0"/><axis xyz="1 0.2 0"/>
    <limit lower="-1" upper="1" effort="100" velocity="1"/></joint>
  <joint name="j1" type="revolute"><parent link="slider"/><child link="a"/>
    <origin xyz="0.1 0 0.2" rpy="0.2 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="100" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="a"/><child link="b"/>
    <origin xyz="0 0.4 0" rpy="0 0 0.4"/><axis xyz="1 0 1"/>
    <limit lower="-2" upper="2" effort="100" velocity="1"/></joint>
  <joint name="j3" type="revolute"><parent link="slider"/><child link="c"/>
    <origin xyz="-0.1 0 0.1" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="100" velocity="1"/></joint>
</robot>)";

Eigen::VectorXd randomVector(int n, std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i) x[i] = u(rng);
  return x;
}

Eigen::VectorXd inverseDynamics(const RobotModel& m, Workspace& ws, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd) {
  Eigen::VectorXd tau(m.nq());
  m.update(ws, q, qd);
  m.inverseDynamics(ws, qdd, tau);
  return tau;
}

void checkAgainstFiniteDifferences(const std::shared_ptr<const RobotModel>& model, int states) {
  const RobotModel& m = *model;
  const int n = m.nq();
  const RneaDerivatives rd(model);
  RneaDerivatives::Data data(m);
  Workspace ws(m);
  std::mt19937 rng(7);
  constexpr double h = 1e-5;
  for (int s = 0; s < states; ++s) {
    const Eigen::VectorXd q = randomVector(n, rng, 1.0);
    const Eigen::VectorXd qd = randomVector(n, rng, 2.0);
    const Eigen::VectorXd qdd = randomVector(n, rng, 5.0);
    Eigen::VectorXd tau(n);
    Eigen::MatrixXd dq(n, n), dqd(n, n);
    rd.compute(data, q, qd, qdd, tau, dq, dqd);
    const Eigen::VectorXd tau_ref = inverseDynamics(m, ws, q, qd, qdd);
    EXPECT_LE((tau - tau_ref).norm(), 1e-9 * std::max(1.0, tau_ref.norm())) << "state " << s;
    for (int k = 0; k < n; ++k) {
      Eigen::VectorXd qp = q, qm = q, vp = qd, vm = qd;
      qp[k] += h;
      qm[k] -= h;
      vp[k] += h;
      vm[k] -= h;
      const Eigen::VectorXd fd_q =
          (inverseDynamics(m, ws, qp, qd, qdd) - inverseDynamics(m, ws, qm, qd, qdd)) / (2 * h);
      const Eigen::VectorXd fd_v =
          (inverseDynamics(m, ws, q, vp, qdd) - inverseDynamics(m, ws, q, vm, qdd)) / (2 * h);
      EXPECT_LE((dq.col(k) - fd_q).norm(), 1e-5 * std::max(1.0, fd_q.norm()))
          << m.name() << " state " << s << " d tau / d q_" << k << "\nours "
          << dq.col(k).transpose() << "\nfd   " << fd_q.transpose();
      EXPECT_LE((dqd.col(k) - fd_v).norm(), 1e-5 * std::max(1.0, fd_v.norm()))
          << m.name() << " state " << s << " d tau / d qd_" << k << "\nours "
          << dqd.col(k).transpose() << "\nfd   " << fd_v.transpose();
    }
  }
}

TEST(RneaDerivatives, BipedMatchesFiniteDifferences) {
  checkAgainstFiniteDifferences(RobotModel::fromUrdfFile(kUrdf), 5);
}

TEST(RneaDerivatives, BranchedTreeWithPrismaticJointMatchesFiniteDifferences) {
  checkAgainstFiniteDifferences(RobotModel::fromUrdfString(kTree, {}, "tree"), 10);
}

TEST(RneaDerivatives, RejectsWrongSizes) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  const RneaDerivatives rd(model);
  RneaDerivatives::Data data(*model);
  const int n = model->nq();
  Eigen::VectorXd tau(n);
  Eigen::MatrixXd dq(n, n), dqd(n, n);
  const Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
  EXPECT_THROW(rd.compute(data, z, z, Eigen::VectorXd::Zero(n - 1), tau, dq, dqd), ReachError);
  Eigen::MatrixXd small(n, n - 1);
  EXPECT_THROW(rd.compute(data, z, z, z, tau, small, dqd), ReachError);
}

}  // namespace
