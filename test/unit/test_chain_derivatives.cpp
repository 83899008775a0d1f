// The analytic kinematic chain of the transition OCP against central finite differences:
//  - KinematicDerivatives (model/kinematic_derivatives.h): directional derivatives of a frame's
//    Jacobian, velocity and drift against differences of RobotModel::frameJacobian,
//    frameVelocity and frameJdotQd along random directions at random states, and the same as
//    matrices (d(J x)/dq, d(J^T lambda)/dq included) against differences joint by joint;
//  - inverseLeftJacobianDerivative against differences of ContactConstraint::inverseLeftJacobian
//    on both sides of its series thresholds;
//  - StanceReducedDynamics::evaluate's analytic Jacobian (all columns) against central
//    differences of the signals-only evaluate() at random states,
// on the shipped biped and on TALOS (talos_reduced.urdf of example-robot-data, nothing locked:
// 32 joints, arms and torso branching off the legs' path).
//
// Tolerance: central differences with step h have truncation error O(h^2 |f'''|) and roundoff
// O(eps |f| / h); with h = 1e-5 (1e-6 for the frame terms) both stay below ~1e-8 relative to
// max(1, |row|), so the analytic values must agree to 1e-6.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <string>

#include "reach_trajopt/contact/contact_constraint.h"
#include "reach_trajopt/model/kinematic_derivatives.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/ocp/stance_reduced_dynamics.h"
#include "reach_trajopt/testing/matrix_error.h"

using namespace reach_trajopt;

namespace {

struct Robot {
  std::string name, urdf, stance, swing;
};

std::vector<Robot> robots() {
  const std::string src = REACH_TRAJOPT_SOURCE_DIR;
  const char* erd = std::getenv("EXAMPLE_ROBOT_DATA");
  const std::string robots_dir =
      erd ? std::string(erd)
          : src +
                "/.venv/lib/python3.11/site-packages/cmeel.prefix/share/example-robot-data/robots";
  return {{"biped", src + "/urdf/biped.urdf", "l_sole", "r_sole"},
          {"talos", robots_dir + "/talos_data/robots/talos_reduced.urdf", "right_sole_link",
           "left_sole_link"}};
}

class ChainDerivatives : public ::testing::TestWithParam<Robot> {
 protected:
  void SetUp() override { model_ = RobotModel::fromUrdfFile(GetParam().urdf); }
  std::shared_ptr<const RobotModel> model_;
};

Eigen::VectorXd randomVector(int n, std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i) x[i] = u(rng);
  return x;
}

/// A configuration: the middle of the limits plus up to +-0.3 rad, the base anywhere near the
/// origin with a moderate tilt.
Eigen::VectorXd randomConfiguration(const RobotModel& m, std::mt19937& rng) {
  Eigen::VectorXd q = m.neutralConfiguration() + randomVector(m.nq(), rng, 0.3);
  q[3] *= 5.0;  // any yaw
  return q;
}

using reach_trajopt::testing::rowRelativeError;

}  // namespace

TEST_P(ChainDerivatives, FrameTermsMatchCentralDifferences) {
  const RobotModel& m = *model_;
  const int nq = m.nq();
  KinematicDerivatives kin(model_);
  KinematicDerivatives::Data kd(m);
  Workspace ws(m);
  std::mt19937 rng(7);
  const double h = 1e-6;
  for (const std::string& frame_name : {GetParam().stance, GetParam().swing}) {
    const FrameId frame = m.frameId(frame_name);
    for (int trial = 0; trial < 4; ++trial) {
      const Eigen::VectorXd q = randomConfiguration(m, rng);
      const Eigen::VectorXd qd = randomVector(nq, rng, 1.5);
      const Eigen::VectorXd dq = randomVector(nq, rng, 1.0);
      const Eigen::VectorXd dqd = randomVector(nq, rng, 1.0);
      // The frame's J, velocity and drift stacked into one 6 x (n_q + 2) matrix.
      auto terms = [&](const Eigen::VectorXd& x, const Eigen::VectorXd& xd) {
        m.update(ws, x, xd);
        Eigen::MatrixXd out(6, nq + 2);
        Matrix6Xd J(6, nq);
        m.frameJacobian(ws, frame, J);
        out.leftCols(nq) = J;
        out.col(nq) = m.frameVelocity(ws, frame);
        out.col(nq + 1) = m.frameJdotQd(ws, frame);
        return out;
      };
      const Eigen::MatrixXd fd =
          (terms(q + h * dq, qd + h * dqd) - terms(q - h * dq, qd - h * dqd)) / (2.0 * h);
      kin.compute(kd, q, qd);
      Matrix6Xd dJ(6, nq);
      Vector6d dvel, ddrift;
      kin.frameDerivatives(kd, frame, dq, dqd, &dJ, &dvel, &ddrift);
      Eigen::MatrixXd an(6, nq + 2);
      an << dJ, dvel, ddrift;
      EXPECT_LT(rowRelativeError(an, fd), 1e-6) << frame_name << " trial " << trial;
      // The requested outputs alone give the same numbers.
      Vector6d ddrift_only;
      kin.frameDerivatives(kd, frame, dq, dqd, nullptr, nullptr, &ddrift_only);
      EXPECT_LT((ddrift_only - ddrift).cwiseAbs().maxCoeff(), 1e-12);
    }
  }
}

TEST_P(ChainDerivatives, FrameMatricesMatchCentralDifferences) {
  const RobotModel& m = *model_;
  const int nq = m.nq();
  KinematicDerivatives kin(model_);
  KinematicDerivatives::Data kd(m);
  KinematicDerivatives::FrameMatrices fm(nq);
  Workspace ws(m);
  std::mt19937 rng(5);
  const double h = 1e-6;
  for (const std::string& frame_name : {GetParam().stance, GetParam().swing}) {
    const FrameId frame = m.frameId(frame_name);
    for (int trial = 0; trial < 3; ++trial) {
      const Eigen::VectorXd q = randomConfiguration(m, rng);
      const Eigen::VectorXd qd = randomVector(nq, rng, 1.5);
      const Eigen::VectorXd x = randomVector(nq, rng, 3.0);
      const Vector6d lambda = randomVector(6, rng, 100.0);
      // J x, J qd, Jdot qd and J^T lambda stacked into one vector.
      auto terms = [&](const Eigen::VectorXd& y, const Eigen::VectorXd& yd) {
        m.update(ws, y, yd);
        Matrix6Xd J(6, nq);
        m.frameJacobian(ws, frame, J);
        Eigen::VectorXd out(18 + nq);
        out << J * x, m.frameVelocity(ws, frame), m.frameJdotQd(ws, frame), J.transpose() * lambda;
        return out;
      };
      Eigen::MatrixXd fd_q(18 + nq, nq), fd_qd(18 + nq, nq);
      for (int k = 0; k < nq; ++k) {
        const Eigen::VectorXd e = Eigen::VectorXd::Unit(nq, k);
        fd_q.col(k) = (terms(q + h * e, qd) - terms(q - h * e, qd)) / (2.0 * h);
        fd_qd.col(k) = (terms(q, qd + h * e) - terms(q, qd - h * e)) / (2.0 * h);
      }
      kin.compute(kd, q, qd);
      kin.frameMatrices(kd, frame, x, &lambda, fm);
      EXPECT_LT(rowRelativeError(fm.dJx_dq, fd_q.topRows(6)), 1e-6) << frame_name;
      EXPECT_LT(rowRelativeError(fm.dvelocity_dq, fd_q.middleRows(6, 6)), 1e-6) << frame_name;
      EXPECT_LT(rowRelativeError(fm.ddrift_dq, fd_q.middleRows(12, 6)), 1e-6) << frame_name;
      EXPECT_LT(rowRelativeError(fm.ddrift_dqd, fd_qd.middleRows(12, 6)), 1e-6) << frame_name;
      EXPECT_LT(rowRelativeError(fm.dJTlambda_dq, fd_q.bottomRows(nq)), 1e-6) << frame_name;
    }
  }
}

TEST(InverseLeftJacobianDerivative, MatchesCentralDifferences) {
  std::mt19937 rng(3);
  for (double theta : {1e-6, 5e-5, 2e-3, 0.05, 0.099, 0.101, 0.7, 2.5}) {
    for (int trial = 0; trial < 3; ++trial) {
      const Eigen::Vector3d e = theta * randomVector(3, rng, 1.0).normalized();
      const Eigen::Vector3d de = randomVector(3, rng, 1.0);
      // Step small against theta so the differences stay on one side of the series thresholds.
      const double h = std::min(1e-6, 1e-2 * theta);
      const Eigen::Matrix3d fd = (ContactConstraint::inverseLeftJacobian(e + h * de) -
                                  ContactConstraint::inverseLeftJacobian(e - h * de)) /
                                 (2.0 * h);
      const Eigen::Matrix3d an = inverseLeftJacobianDerivative(e, de);
      EXPECT_LT((an - fd).cwiseAbs().maxCoeff(), 1e-7) << "theta " << theta;
    }
  }
}

TEST_P(ChainDerivatives, StanceReducedJacobianMatchesCentralDifferences) {
  const RobotModel& m = *model_;
  const int nq = m.nq(), nu = m.nu();
  std::mt19937 rng(11);
  Workspace ws(m);
  for (int trial = 0; trial < 3; ++trial) {
    // The stance sole's pose at a random configuration; the swing target somewhere else, turned,
    // so phi_2's rotation error is not small.
    const Eigen::VectorXd q = randomConfiguration(m, rng);
    m.update(ws, q, Eigen::VectorXd::Zero(nq));
    const FrameId stance = m.frameId(GetParam().stance), swing = m.frameId(GetParam().swing);
    const Eigen::Isometry3d stance_pose = m.framePose(ws, stance);
    Eigen::Isometry3d target = m.framePose(ws, swing);
    target.translation() += Eigen::Vector3d(0.2, -0.05, 0.03);
    target.linear() =
        Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.3, 0.2, 1.0).normalized()) * target.linear();
    StanceReducedDynamics d(model_, stance, stance_pose, swing, target, q[3]);
    StanceReducedDynamics::Scratch s(d);
    Eigen::VectorXd input(d.inputCount());
    input << q.tail(nu) + randomVector(nu, rng, 0.1), randomVector(nu, rng, 1.0),
        randomVector(nu, rng, 4.0), randomVector(6, rng, 100.0);
    auto f = [&](const Eigen::VectorXd& x) {
      Eigen::VectorXd sig(d.signalCount());
      d.evaluate(s, x, sig);
      return sig;
    };
    const double h = 1e-5;
    Eigen::MatrixXd fd(d.signalCount(), d.inputCount());
    for (int i = 0; i < d.inputCount(); ++i) {
      const double hi = h * std::max(1.0, std::abs(input[i]));
      Eigen::VectorXd a = input, b = input;
      a[i] += hi;
      b[i] -= hi;
      fd.col(i) = (f(a) - f(b)) / (2.0 * hi);
    }
    const Eigen::VectorXd sig0 = f(input);
    Eigen::VectorXd sig(d.signalCount());
    Eigen::MatrixXd J(d.signalCount(), d.inputCount());
    d.evaluate(s, input, sig, J);
    EXPECT_EQ((sig - sig0).cwiseAbs().maxCoeff(), 0.0) << "the same signals";
    EXPECT_LT(rowRelativeError(J.leftCols(nu), fd.leftCols(nu)), 1e-6) << "q_a, trial " << trial;
    EXPECT_LT(rowRelativeError(J.middleCols(nu, nu), fd.middleCols(nu, nu)), 1e-6)
        << "qd_a, trial " << trial;
    EXPECT_LT(rowRelativeError(J.rightCols(nu + 6), fd.rightCols(nu + 6)), 1e-6)
        << "qdd_a, lambda_2, trial " << trial;
    // The finite-difference scheme (central, step 1e-5) agrees with the analytic one.
    Eigen::MatrixXd Jfd(d.signalCount(), d.inputCount());
    d.evaluate(s, input, sig, Jfd, 1e-5, true);
    EXPECT_LT(rowRelativeError(Jfd, J), 1e-6) << "trial " << trial;
  }
}

INSTANTIATE_TEST_SUITE_P(Robots, ChainDerivatives, ::testing::ValuesIn(robots()),
                         [](const ::testing::TestParamInfo<Robot>& info) {
                           return info.param.name;
                         });
