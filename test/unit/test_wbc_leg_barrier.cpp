// The whole-body controller's barrier between the legs (wbc.leg_clearance): standing on the
// left sole, the right sole is commanded through the left one. Bullet's own contact test
// between the legs' URDF shapes (an oracle that is not the controller's capsules) finds no
// contact with the barrier on, and finds one with it off (so the test can fail); with it on,
// the capsules (which contain the shapes) never overlap.

#include <gtest/gtest.h>

#include "reach_trajopt/control/whole_body_controller.h"
#include "reach_trajopt/sim/bullet_world.h"
#include "reach_trajopt/walk/standing_pose.h"

using namespace reach_trajopt;

namespace {

const std::string kUrdf = std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf";

struct SwingRun {
  int leg_contact_ticks = 0;         ///< ticks where Bullet saw the legs touch
  double min_distance_m = HUGE_VAL;  ///< the capsules' distance over the swing
  int failed_ticks = 0;
};

/// 1 s of double support moving the CoM over the left sole, then 0.6 s of single support on it
/// with the right sole's target 2 cm inside the left sole's (across the left leg).
SwingRun swingIntoTheStanceLeg(bool barrier) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  const Eigen::VectorXd q0 = standingConfiguration(*model, 0.6, "l_sole", RobotConfig{});
  const Eigen::VectorXd qd0 = Eigen::VectorXd::Zero(model->nq());
  auto world = BulletWorld::fromUrdfFile(kUrdf, *model, SimConfig{});
  world->reset(q0, qd0);
  WbcConfig config;
  config.leg_clearance = barrier;
  const ContactConfig contact;
  WholeBodyController wbc(model, contact, config, q0);
  const LegClearance legs(*model, contact.left_sole_frame, contact.right_sole_frame);
  Workspace ws(*model);
  model->update(ws, q0, qd0);
  const Eigen::Isometry3d left = model->framePose(ws, model->frameId(contact.left_sole_frame));
  const Eigen::Isometry3d right = model->framePose(ws, model->frameId(contact.right_sole_frame));
  WbcReference ref;
  ref.com_position = model->centerOfMass(ws);
  ref.com_position.head<2>() = left.translation().head<2>();
  ref.w_com_xy = 100.0;
  ref.posture = q0;
  ref.swing_rotation = right.linear();
  ref.swing_position = left.translation() + Eigen::Vector3d(0, -0.02, 0.05);
  SwingRun run;
  const int ticks = static_cast<int>(1.6 / SimConfig{}.time_step);
  for (int k = 0; k < ticks; ++k) {
    const bool single = k * SimConfig{}.time_step >= 1.0;
    const ContactMode mode =
        single ? ContactMode::singleSupport(Side::kLeft) : ContactMode::doubleSupport();
    const WbcOutput& out = wbc.compute(world->q(), world->qd(), mode, ref);
    if (out.status != qp::QpStatus::kOptimal) ++run.failed_ticks;
    world->step(out.u);
    if (!world->legContacts().empty()) ++run.leg_contact_ticks;
    if (single)
      run.min_distance_m = std::min(run.min_distance_m, legs.distanceAt(*model, world->q()));
  }
  return run;
}

}  // namespace

TEST(WholeBodyController, LegBarrierKeepsASwingOutOfTheStanceLeg) {
  const SwingRun with = swingIntoTheStanceLeg(true);
  EXPECT_EQ(with.leg_contact_ticks, 0);
  EXPECT_GE(with.min_distance_m, 0.0);  // the capsules contain the shapes
  // Stopping the swing at once can saturate the torques (the tick then drops their limits).
  EXPECT_LE(with.failed_ticks, 5);
  const SwingRun without = swingIntoTheStanceLeg(false);
  EXPECT_GT(without.leg_contact_ticks, 0) << "the swing did not reach the stance leg: no test";
  EXPECT_LT(without.min_distance_m, 0.0);
}
