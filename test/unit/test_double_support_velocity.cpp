// The terminal velocity qd_f from the LIPM touchdown CoM velocity (planner/
// double_support_velocity.h) on the shipped biped, checked with the model's Jacobians: both
// soles still, base not rotating, CoM at the requested velocity; bad input throws.
#include <gtest/gtest.h>

#include <limits>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/planner/double_support_velocity.h"
#include "reach_trajopt/planner/kinematic_feasibility.h"

using namespace reach_trajopt;

TEST(DoubleSupportVelocity, SolesStillBaseNotRotatingCoMAtTheRequestedVelocity) {
  const auto m =
      RobotModel::fromUrdfFile(std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf");
  const KinematicFeasibility kf(m);
  FlatContact left, right;
  left.position << 0.0, 0.1, 0.0;
  right.position << 0.15, -0.12, 0.0;
  // Pelvis low enough for bent knees (a straight knee is singular: tested below).
  const auto ik =
      kf.check(Side::kLeft, left, right, Eigen::VectorXd(), Eigen::Vector3d(0.07, 0.0, 0.98));
  ASSERT_TRUE(ik.feasible) << ik.reason;
  const FrameId l = m->frameId("l_sole"), r = m->frameId("r_sole");
  for (const Eigen::Vector3d v : {Eigen::Vector3d(0.3, -0.2, 0.0), Eigen::Vector3d(0, 0, 0),
                                  Eigen::Vector3d(-0.1, 0.4, 0.05)}) {
    const Eigen::VectorXd qd = doubleSupportVelocity(*m, ik.q_f, l, r, v);
    Workspace ws(*m);
    m->update(ws, ik.q_f, qd);
    Matrix6Xd J(6, m->nq());
    m->frameJacobian(ws, l, J);
    EXPECT_LT((J * qd).norm(), 1e-10);
    m->frameJacobian(ws, r, J);
    EXPECT_LT((J * qd).norm(), 1e-10);
    EXPECT_LT(qd.segment<3>(3).norm(), 1e-12);  // base yaw, pitch, roll rates
    Eigen::Matrix3Xd Jc(3, m->nq());
    m->centerOfMassJacobian(ws, Jc);
    EXPECT_LT((Jc * qd - v).norm(), 1e-10);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(doubleSupportVelocity(*m, ik.q_f, l, r, Eigen::Vector3d(nan, 0, 0)), ReachError);
  EXPECT_THROW(doubleSupportVelocity(*m, ik.q_f.head(5), l, r, Eigen::Vector3d::Zero()),
               ReachError);
  Eigen::VectorXd straight = ik.q_f;
  straight[m->jointIndex("l_knee")] = 0.0;
  straight[m->jointIndex("l_hip_pitch")] = straight[m->jointIndex("l_ankle_pitch")] = 0.0;
  EXPECT_THROW(doubleSupportVelocity(*m, straight, l, r, Eigen::Vector3d::Zero()), ReachError);
}
