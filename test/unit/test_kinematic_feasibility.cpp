// Kinematic feasibility of Sec. III-B on the shipped biped: a normal step is feasible with both
// soles on target (checked by forward kinematics at q_f) and joints within limits; a too long
// step and a foot through the other foot are infeasible with a reason; bad input throws.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/planner/kinematic_feasibility.h"
#include "reach_trajopt/testing/reference_cases.h"

using namespace reach_trajopt;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

std::shared_ptr<const RobotModel> biped() { return shippedBipedModel(REACH_TRAJOPT_SOURCE_DIR); }

FlatContact contact(double x, double y, double z = 0.0, double yaw = 0.0) {
  FlatContact c;
  c.position << x, y, z;
  c.yaw = yaw;
  return c;
}

/// Rotation angle between two rotations [rad].
double angleBetween(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  return Eigen::AngleAxisd(Eigen::Matrix3d(A * B.transpose())).angle();
}

/// Checks q_f by forward kinematics: soles on target, pelvis upright at the nominal height,
/// joints inside their limits.
void expectStandingAt(const KinematicFeasibility& kf, const KinematicFeasibilityResult& r,
                      const FlatContact& left, const FlatContact& right) {
  const RobotModel& m = kf.model();
  ASSERT_EQ(r.q_f.size(), m.nq());
  ASSERT_EQ(r.qd_f.size(), m.nq());
  EXPECT_EQ(r.qd_f.norm(), 0.0);
  Workspace ws(m);
  m.update(ws, r.q_f, r.qd_f);
  const Eigen::Isometry3d L = m.framePose(ws, m.frameId("l_sole"));
  const Eigen::Isometry3d R = m.framePose(ws, m.frameId("r_sole"));
  EXPECT_LT((L.translation() - left.position).norm(), 1e-6);
  EXPECT_LT((R.translation() - right.position).norm(), 1e-6);
  EXPECT_LT(angleBetween(L.linear(), left.pose().linear()), 1e-6);
  EXPECT_LT(angleBetween(R.linear(), right.pose().linear()), 1e-6);
  const Eigen::Isometry3d P = m.framePose(ws, m.frameId("pelvis"));
  EXPECT_NEAR(P.translation().z(),
              0.5 * (left.position.z() + right.position.z()) + kf.config().pelvis_height, 1e-6);
  EXPECT_LT(std::abs(P.linear()(2, 2) - 1.0), 1e-12);  // upright: pelvis z axis vertical
  const Eigen::VectorXd lo = m.positionLowerLimits(), hi = m.positionUpperLimits();
  for (int i = 0; i < m.nq(); ++i) {
    EXPECT_GE(r.q_f[i], lo[i]) << m.joints()[i].name;
    EXPECT_LE(r.q_f[i], hi[i]) << m.joints()[i].name;
  }
}

}  // namespace

TEST(KinematicFeasibility, NormalStepIsFeasible) {
  const KinematicFeasibility kf(biped());
  // Stance right sole at y = -0.1; the left sole steps 0.3 m forward and 0.2 m to the left.
  const FlatContact right = contact(0.0, -0.1), left = contact(0.3, 0.1);
  const auto r = kf.check(Side::kRight, right, left);
  ASSERT_TRUE(r.feasible) << r.reason;
  EXPECT_TRUE(r.reason.empty());
  EXPECT_LE(r.position_residual, 1e-6);
  EXPECT_LE(r.orientation_residual, 1e-6);
  expectStandingAt(kf, r, left, right);
}

TEST(KinematicFeasibility, MirroredAndTurnedStepsAreFeasible) {
  const KinematicFeasibility kf(biped());
  {
    const FlatContact left = contact(0.0, 0.1), right = contact(0.3, -0.1);
    const auto r = kf.check(Side::kLeft, left, right);
    ASSERT_TRUE(r.feasible) << r.reason;
    expectStandingAt(kf, r, left, right);
  }
  {
    // A turning step on a slightly raised stance: the left sole turned by 0.2 rad.
    const FlatContact right = contact(0.1, -0.1, 0.02, 0.0), left = contact(0.3, 0.12, 0.0, 0.2);
    const auto r = kf.check(Side::kRight, right, left);
    ASSERT_TRUE(r.feasible) << r.reason;
    expectStandingAt(kf, r, left, right);
  }
}

TEST(KinematicFeasibility, TooLongStepIsInfeasible) {
  const KinematicFeasibility kf(biped());
  const auto r = kf.check(Side::kRight, contact(0.0, -0.1), contact(1.5, 0.1));
  EXPECT_FALSE(r.feasible);
  EXPECT_NE(r.reason.find("kinematically infeasible"), std::string::npos) << r.reason;
  EXPECT_GT(r.position_residual, 1e-3) << r.reason;
  std::cout << "1.5 m step: " << r.reason << "\n";
  // Even the failed iterate respects the joint limits.
  const RobotModel& m = kf.model();
  EXPECT_TRUE((r.q_f.array() >= m.positionLowerLimits().array()).all());
  EXPECT_TRUE((r.q_f.array() <= m.positionUpperLimits().array()).all());
}

TEST(KinematicFeasibility, FootThroughTheOtherFootIsInfeasible) {
  const KinematicFeasibility kf(biped());
  // Overlapping soles.
  const auto overlap = kf.check(Side::kRight, contact(0.0, -0.1), contact(0.1, -0.05));
  EXPECT_FALSE(overlap.feasible);
  EXPECT_NE(overlap.reason.find("overlaps the stance sole r_sole"), std::string::npos)
      << overlap.reason;
  // The left sole placed beyond the right one: the left leg would cross through the right.
  const auto cross = kf.check(Side::kRight, contact(0.0, -0.1), contact(0.0, -0.4));
  EXPECT_FALSE(cross.feasible);
  EXPECT_NE(cross.reason.find("pass through the stance leg"), std::string::npos) << cross.reason;
  std::cout << "overlap: " << overlap.reason << "\ncross: " << cross.reason << "\n";
}

TEST(KinematicFeasibility, BadInput) {
  const KinematicFeasibility kf(biped());
  const FlatContact ok = contact(0.0, -0.1);
  EXPECT_THROW(kf.check(Side::kRight, ok, contact(kNaN, 0.1)), ReachError);
  FlatContact bad_yaw = contact(0.3, 0.1);
  bad_yaw.yaw = kNaN;
  EXPECT_THROW(kf.check(Side::kRight, ok, bad_yaw), ReachError);
  // Outside the workspace: an error, not a step.
  try {
    kf.check(Side::kRight, ok, contact(5.0, 0.1));
    ADD_FAILURE() << "no error for a 5 m step";
  } catch (const ReachError& e) {
    EXPECT_NE(std::string(e.what()).find("outside the workspace"), std::string::npos);
  }
  EXPECT_THROW(kf.check(Side::kRight, ok, contact(0.3, 0.1, 1.0)), ReachError);
  // q_init of the wrong size or with a NaN.
  EXPECT_THROW(kf.check(Side::kRight, ok, contact(0.3, 0.1), Eigen::VectorXd::Zero(3)), ReachError);
  Eigen::VectorXd q = biped()->neutralConfiguration();
  q[7] = kNaN;
  EXPECT_THROW(kf.check(Side::kRight, ok, contact(0.3, 0.1), q), ReachError);
  // Unknown frames and bad configs.
  ContactConfig cc;
  cc.left_sole_frame = "no_such_sole";
  EXPECT_THROW(KinematicFeasibility(biped(), {}, cc), ReachError);
  KinematicFeasibilityConfig kc;
  kc.pelvis_frame = "nope";
  EXPECT_THROW(KinematicFeasibility(biped(), kc), ReachError);
  kc = {};
  kc.position_tolerance = 0.0;
  EXPECT_THROW(KinematicFeasibility(biped(), kc), ReachError);
  kc = {};
  kc.pelvis_height = kNaN;
  EXPECT_THROW(kc.validate(), ReachError);
  cc = {};
  cc.half_width = 0.0;  // zero-size sole
  EXPECT_THROW(KinematicFeasibility(biped(), {}, cc), ReachError);
  EXPECT_THROW(KinematicFeasibility(nullptr), ReachError);
}

TEST(KinematicFeasibility, WarmStartFromTheCurrentConfiguration) {
  // Starting from a solved standing pose, a second check converges in a few iterations.
  const KinematicFeasibility kf(biped());
  const FlatContact right = contact(0.0, -0.1);
  const auto first = kf.check(Side::kRight, right, contact(0.0, 0.1));
  ASSERT_TRUE(first.feasible) << first.reason;
  const auto second = kf.check(Side::kRight, right, contact(0.25, 0.15), first.q_f);
  ASSERT_TRUE(second.feasible) << second.reason;
  expectStandingAt(kf, second, contact(0.25, 0.15), right);
}

TEST(KinematicFeasibility, ShippedYaml) {
  const auto file =
      YamlSection::loadFile(std::string(REACH_TRAJOPT_SOURCE_DIR) + "/config/biped.yaml");
  const auto c = KinematicFeasibilityConfig::fromYaml(file.section("kinematic_feasibility"));
  EXPECT_EQ(c.pelvis_frame, "pelvis");
  EXPECT_NO_THROW(KinematicFeasibility(biped(), c));
}

TEST(KinematicFeasibility, HeldPelvisPositionIsReachedWithSolesOnTarget) {
  // The walking check's variant: the pelvis origin held where the CoM will carry it (here 3 cm
  // ahead of and 2 cm toward the stance sole from the midpoint, 5 cm above the nominal
  // height). Checked by forward kinematics at q_f.
  const auto m = biped();
  const KinematicFeasibility kf(m);
  const Eigen::Vector3d pelvis(0.08, 0.03, kf.config().pelvis_height + 0.05);
  const auto r =
      kf.check(Side::kLeft, contact(0.0, 0.1), contact(0.1, -0.1), Eigen::VectorXd(), pelvis);
  ASSERT_TRUE(r.feasible) << r.reason;
  Workspace ws(*m);
  m->update(ws, r.q_f, Eigen::VectorXd::Zero(m->nq()));
  EXPECT_LT((m->framePose(ws, m->frameId("pelvis")).translation() - pelvis).norm(), 1e-5);
  EXPECT_LT(
      (m->framePose(ws, m->frameId("l_sole")).translation() - Eigen::Vector3d(0, 0.1, 0)).norm(),
      1e-5);
  EXPECT_LT(
      (m->framePose(ws, m->frameId("r_sole")).translation() - Eigen::Vector3d(0.1, -0.1, 0)).norm(),
      1e-5);
  // A pelvis held far from the soles cannot be reached: infeasible with a reason.
  const auto far = kf.check(Side::kLeft, contact(0.0, 0.1), contact(0.1, -0.1), Eigen::VectorXd(),
                            Eigen::Vector3d(0.6, 0.0, 1.0));
  EXPECT_FALSE(far.feasible);
  EXPECT_NE(far.reason.find("pelvis"), std::string::npos) << far.reason;
  EXPECT_THROW(kf.check(Side::kLeft, contact(0.0, 0.1), contact(0.1, -0.1), Eigen::VectorXd(),
                        Eigen::Vector3d(kNaN, 0.0, 1.0)),
               ReachError);
}
