// The nearest kinematically feasible foothold (planner/nearest_feasible_foothold.h) on the
// shipped biped: a target inside the stance sole is replaced by the first feasible ring point,
// which the kinematic check itself accepts (an independent re-check), no closer ring holds a
// feasible point, and a search too small to leave the infeasible region finds nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/planner/nearest_feasible_foothold.h"

using namespace reach_trajopt;

namespace {

std::shared_ptr<const KinematicFeasibility> kinematics() {
  static const auto model =
      RobotModel::fromUrdfFile(std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf");
  static const auto kf =
      std::make_shared<KinematicFeasibility>(model, KinematicFeasibilityConfig{}, ContactConfig{});
  return kf;
}

FlatContact at(double x, double y) {
  FlatContact c;
  c.position << x, y, 0.0;
  return c;
}

TEST(NearestFeasibleFoothold, ReplacesAFootThroughTheOtherByTheFirstFeasibleRingPoint) {
  const auto kf = kinematics();
  NearestFootholdConfig config;
  const NearestFeasibleFoothold search(kf, config);
  const FlatContact stance = at(0.0, 0.1);    // left sole held
  const FlatContact target = at(0.02, 0.05);  // right sole inside the left one
  ASSERT_FALSE(kf->check(Side::kLeft, stance, target, {}).feasible);
  const auto found = search.find(Side::kLeft, stance, target, {}, std::nullopt);
  ASSERT_TRUE(found.has_value());
  EXPECT_TRUE(found->kinematics.feasible);
  EXPECT_TRUE(kf->check(Side::kLeft, stance, found->foothold, {}).feasible);
  const double r = (found->foothold.position - target.position).norm();
  EXPECT_LE(r, config.searchRadius() + 1e-12);
  // Its ring is the first with a feasible point: every point of the rings inside is infeasible.
  const int ring = static_cast<int>(std::lround(r / config.ring_step));
  for (int k = 1; k < ring; ++k)
    for (int d = 0; d < config.directions; ++d) {
      const double a = 2.0 * M_PI * d / config.directions;
      FlatContact p = target;
      p.position += k * config.ring_step * Eigen::Vector3d(std::cos(a), std::sin(a), 0.0);
      EXPECT_FALSE(kf->check(Side::kLeft, stance, p, {}).feasible) << "ring " << k << " dir " << d;
    }
}

TEST(NearestFeasibleFoothold, SearchTooSmallFindsNothing) {
  NearestFootholdConfig config;
  config.rings = 1;
  config.ring_step = 0.005;
  const NearestFeasibleFoothold search(kinematics(), config);
  EXPECT_FALSE(search.find(Side::kLeft, at(0.0, 0.1), at(0.0, 0.1), {}, std::nullopt));
}

TEST(NearestFeasibleFoothold, BadConfigNamesTheField) {
  NearestFootholdConfig config;
  config.ring_step = -1.0;
  try {
    NearestFeasibleFoothold search(kinematics(), config);
    FAIL() << "no error";
  } catch (const ReachError& e) {
    EXPECT_NE(std::string(e.what()).find("ring_step"), std::string::npos) << e.what();
  }
}

}  // namespace
