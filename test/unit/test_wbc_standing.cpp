// The whole-body controller holds the robot standing in the Bullet simulation: 10 s of sim
// time, pelvis within 1 cm of where it started, and the QP's contact wrenches carry the weight.

#include <gtest/gtest.h>

#include "reach_trajopt/control/whole_body_controller.h"
#include "reach_trajopt/sim/bullet_world.h"
#include "reach_trajopt/walk/standing_pose.h"

using namespace reach_trajopt;

namespace {
const std::string kUrdf = std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf";
}

TEST(WholeBodyController, HoldsStandingForTenSeconds) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  const Eigen::VectorXd q0 = standingConfiguration(*model, 0.6, "l_sole", RobotConfig{});
  const Eigen::VectorXd qd0 = Eigen::VectorXd::Zero(model->nq());
  SimConfig sim_config;
  auto world = BulletWorld::fromUrdfFile(kUrdf, *model, sim_config);
  world->reset(q0, qd0);
  WholeBodyController wbc(model, ContactConfig{}, WbcConfig{}, q0);
  Workspace ws(*model);
  model->update(ws, q0, qd0);
  WbcReference ref;
  ref.com_position = model->centerOfMass(ws);
  ref.posture = q0;
  double max_pelvis_error = 0.0;
  int failures = 0;
  for (int k = 0; k < 10000; ++k) {
    const WbcOutput& out = wbc.compute(world->q(), world->qd(), ContactMode::doubleSupport(), ref);
    if (out.status != qp::QpStatus::kOptimal) ++failures;
    world->step(out.u);
    max_pelvis_error = std::max(max_pelvis_error, (world->q().head(3) - q0.head(3)).norm());
    if (k == 5000) {
      const double fz = out.lambda_left[2] + out.lambda_right[2];
      EXPECT_NEAR(fz, model->totalMass() * 9.81, 0.02 * model->totalMass() * 9.81);
    }
  }
  EXPECT_EQ(failures, 0);
  EXPECT_LT(max_pelvis_error, 0.01) << "pelvis drifted";
  EXPECT_TRUE(world->nonFootContacts().empty());
}
