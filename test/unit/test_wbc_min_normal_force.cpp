// The whole-body controller's minimum normal force in double support (WbcConfig::
// min_normal_force): each sole's wrench is f_min along the sole's normal at its centre plus a
// wrench of its contact cone, C (lambda - lambda_min) >= 0. Standing, with a horizontal CoM
// acceleration that asks for the centre of pressure under the right sole (the left one
// unloaded), the controller without it unloads the left sole below f_min; with it both soles
// carry at least f_min, and lambda - lambda_min lies in the cone as ContactWrenchCone checks it
// in the sole frame (eq. 7), which is not the controller's own row construction.

#include <gtest/gtest.h>

#include "reach_trajopt/control/whole_body_controller.h"
#include "reach_trajopt/walk/standing_pose.h"

using namespace reach_trajopt;

namespace {

const std::string kUrdf = std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf";
constexpr double kMinNormalForce = 40.0;  // [N], about 5 % of the biped's weight

struct Solved {
  WbcOutput out;
  Eigen::Matrix3d left_rotation, right_rotation;  ///< soles in the world
};

/// One tick standing at rest, the CoM asked to accelerate 1.5 m/s^2 toward +y (left), which the
/// pendulum gets from a centre of pressure to the right of the CoM: at the right sole.
Solved standingTick(double min_normal_force) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  const Eigen::VectorXd q0 = standingConfiguration(*model, 0.6, "l_sole", RobotConfig{});
  const Eigen::VectorXd qd0 = Eigen::VectorXd::Zero(model->nq());
  WbcConfig config;
  config.min_normal_force = min_normal_force;
  WholeBodyController wbc(model, ContactConfig{}, config, q0);
  Workspace ws(*model);
  model->update(ws, q0, qd0);
  WbcReference ref;
  ref.com_position = model->centerOfMass(ws);
  ref.com_acceleration = Eigen::Vector3d(0.0, 1.5, 0.0);
  ref.w_com_xy = 1000.0;
  ref.posture = q0;
  Solved s;
  s.out = wbc.compute(q0, qd0, ContactMode::doubleSupport(), ref);
  s.left_rotation = model->framePose(ws, model->frameId("l_sole")).linear();
  s.right_rotation = model->framePose(ws, model->frameId("r_sole")).linear();
  return s;
}

/// The sole-frame wrench of a world wrench [f; tau] at the sole centre.
ContactWrenchCone::Wrench inSoleFrame(const Vector6d& world, const Eigen::Matrix3d& R) {
  ContactWrenchCone::Wrench w;
  w << R.transpose() * world.head<3>(), R.transpose() * world.tail<3>();
  return w;
}

}  // namespace

TEST(WbcMinNormalForce, WithoutItTheAskedMotionUnloadsTheLeftSole) {
  const Solved s = standingTick(0.0);
  ASSERT_EQ(s.out.status, qp::QpStatus::kOptimal) << s.out.message;
  const double fz_left = inSoleFrame(s.out.lambda_left, s.left_rotation)[2];
  EXPECT_LT(fz_left, kMinNormalForce) << "the case does not ask for an unloaded sole";
}

TEST(WbcMinNormalForce, BothSolesKeepItAndTheRestIsInTheCone) {
  const Solved s = standingTick(kMinNormalForce);
  ASSERT_EQ(s.out.status, qp::QpStatus::kOptimal) << s.out.message;
  const ContactWrenchCone cone(ContactConfig{});
  ContactWrenchCone::Wrench lambda_min = ContactWrenchCone::Wrench::Zero();
  lambda_min[2] = kMinNormalForce;
  for (const auto& [lambda, R] : {std::pair{s.out.lambda_left, s.left_rotation},
                                  std::pair{s.out.lambda_right, s.right_rotation}}) {
    const ContactWrenchCone::Wrench w = inSoleFrame(lambda, R);
    EXPECT_GE(w[2], kMinNormalForce - 1e-6) << w.transpose();
    EXPECT_TRUE(cone.contains(w - lambda_min, 1e-6)) << "margin " << cone.margin(w - lambda_min);
  }
  // The soles still carry the weight and the asked acceleration between them.
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  const double weight = model->totalMass() * 9.81;
  EXPECT_NEAR(s.out.lambda_left[2] + s.out.lambda_right[2], weight, 0.05 * weight);
}
