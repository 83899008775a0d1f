// Step-timing adaptation (planner/step_timing.h) against the LIPM's closed form and eq. (11)
// written out here: the chosen swing duration fits the TVR step into the foot offset bounds
// when some duration of the range can, keeps the nominal duration when it fits there, and no
// duration nearer the nominal one does as well.

#include <gtest/gtest.h>

#include <cmath>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/planner/step_timing.h"
#include "reach_trajopt/planner/tvr_planner.h"

using namespace reach_trajopt;

namespace {

/// Eq. (11) from the state predicted T ahead about `stance` (eq. 9-10), per axis.
Eigen::Vector2d tvrFoothold(const TvrConfig& c, const Eigen::Vector2d& p0,
                            const Eigen::Vector2d& v0, const Eigen::Vector2d& stance, double t,
                            double T, double x_start, double forward_speed, double y_mid) {
  const double w = std::sqrt(c.gravity / c.com_height);
  const Eigen::Vector2d p = stance + (p0 - stance) * std::cosh(w * T) + v0 * std::sinh(w * T) / w;
  const Eigen::Vector2d v = w * (p0 - stance) * std::sinh(w * T) + v0 * std::cosh(w * T);
  const Eigen::Vector2d p_des(x_start + forward_speed * (t + T), y_mid);
  const Eigen::Vector2d kappa(c.kappa_x, c.kappa_y);
  return p + v / (w * std::tanh(w * c.t_s)) + kappa.cwiseProduct(p_des - p);
}

/// Distance of a foothold to the foot offset bounds (heading 0), y signed toward the swing.
double boundViolation(const TvrConfig& c, const Eigen::Vector2d& a, const Eigen::Vector2d& stance,
                      Side swing) {
  const double sign = swing == Side::kLeft ? 1.0 : -1.0;
  const Eigen::Vector2d o = a - stance;
  const double dx = std::max({c.foot_offset_x_min - o.x(), o.x() - c.foot_offset_x_max, 0.0});
  const double dy =
      std::max({c.foot_offset_y_min - sign * o.y(), sign * o.y() - c.foot_offset_y_max, 0.0});
  return std::hypot(dx, dy);
}

struct Case {
  Eigen::Vector2d p, v, stance;
  Side swing;
};

}  // namespace

TEST(StepTiming, ChoosesTheDurationNearestTheNominalThatFitsTheBounds) {
  TvrConfig config;
  const TvrPlanner planner(config);
  StepTimingRange range;
  range.nominal = 0.22;
  range.min = 0.12;
  range.max = 0.4;
  range.resolution = 0.005;
  const Case cases[] = {
      {{0.0, 0.0}, {0.0, 0.05}, {0.0, 0.1}, Side::kRight},    // in place: fits at nominal
      {{0.05, 0.0}, {0.9, 0.0}, {0.0, 0.1}, Side::kRight},    // fast forward: too long a step
      {{-0.03, 0.0}, {-0.8, 0.1}, {0.0, -0.1}, Side::kLeft},  // fast backward
      {{0.0, 0.05}, {0.0, 0.35}, {0.0, 0.1}, Side::kRight},   // lateral toward the stance
      {{0.0, -0.02}, {0.1, -0.6}, {0.0, 0.1}, Side::kRight},  // lateral away from the stance
  };
  int adapted = 0;
  for (const Case& k : cases) {
    const LipmState com{k.p, k.v};
    const StepTiming s =
        adaptStepTiming(planner, com, k.stance, k.swing, 1.0, 0.0, 0.0, 0.0, range);
    const auto violationAt = [&](double T) {
      return boundViolation(config, tvrFoothold(config, k.p, k.v, k.stance, 1.0, T, 0.0, 0.0, 0.0),
                            k.stance, k.swing);
    };
    EXPECT_NEAR(s.bound_violation, violationAt(s.swing_duration), 1e-9);
    EXPECT_NEAR(s.nominal_violation, violationAt(range.nominal), 1e-9);
    EXPECT_GE(s.swing_duration, range.min - 1e-12);
    EXPECT_LE(s.swing_duration, range.max + 1e-12);
    // No duration of the grid fits better, and none nearer the nominal one fits as well.
    for (int i = 0; range.min + i * range.resolution <= range.max + 1e-12; ++i) {
      const double T = range.min + i * range.resolution;
      EXPECT_GE(violationAt(T), s.bound_violation - 1e-9) << "T=" << T;
      if (std::abs(T - range.nominal) < std::abs(s.swing_duration - range.nominal) - 1e-9)
        EXPECT_GT(violationAt(T), s.bound_violation + 1e-12) << "T=" << T;
    }
    if (s.nominal_violation == 0.0) EXPECT_EQ(s.swing_duration, range.nominal);
    adapted += s.swing_duration != range.nominal;
  }
  EXPECT_GE(adapted, 2) << "the cases must exercise the adaptation";
}

TEST(StepTiming, RejectsAnInvalidRange) {
  const TvrPlanner planner{TvrConfig{}};
  StepTimingRange range;
  range.min = 0.3;  // above the nominal 0.22
  range.max = 0.4;
  EXPECT_THROW(adaptStepTiming(planner, LipmState{}, Eigen::Vector2d::Zero(), Side::kLeft, 0.0, 0.0,
                               0.0, 0.0, range),
               ReachError);
  range = StepTimingRange{};
  range.resolution = 0.0;
  EXPECT_THROW(adaptStepTiming(planner, LipmState{}, Eigen::Vector2d::Zero(), Side::kLeft, 0.0, 0.0,
                               0.0, 0.0, range),
               ReachError);
}
