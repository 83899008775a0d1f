// The nearest kinematically feasible foothold (planner/nearest_feasible_foothold.h) on the
// shipped biped: a target inside the stance sole is replaced by the first feasible ring point,
// which the kinematic check itself accepts (an independent re-check), no closer ring holds a
// feasible point, and a search too small to leave the infeasible region finds nothing. A ring
// checked in chunks elsewhere (as worker nodes do) finds the same foothold and posture, bit for
// bit, as the search in process; a check that answers too few candidates is an error.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

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

TEST(NearestFeasibleFoothold, RingsCheckedInChunksGiveTheInProcessAnswer) {
  const auto kf = kinematics();
  const NearestFeasibleFoothold search(kf, NearestFootholdConfig{});
  const FlatContact stance = at(0.0, 0.1), target = at(0.02, 0.05);
  int batches = 0;
  // Three chunks per ring, the last one first, each checked in full (what a worker answers).
  const CandidateCheck chunked = [&](const FootholdCandidates& batch) {
    ++batches;
    const size_t n = batch.candidates.size();
    std::vector<std::vector<CandidateOutcome>> parts(3);
    for (int c = 2; c >= 0; --c) {
      FootholdCandidates part = batch;
      part.candidates.assign(batch.candidates.begin() + n * c / 3,
                             batch.candidates.begin() + n * (c + 1) / 3);
      parts[c] = checkFootholdCandidates(*kf, part, false);
    }
    std::vector<CandidateOutcome> all;
    for (auto& p : parts) all.insert(all.end(), p.begin(), p.end());
    return all;
  };
  const auto local = search.find(Side::kLeft, stance, target, {}, std::nullopt);
  const auto remote = search.find(Side::kLeft, stance, target, {}, std::nullopt, chunked);
  ASSERT_TRUE(local && remote);
  EXPECT_GT(batches, 1);  // the target's ring 1 is infeasible: more than one ring was checked
  EXPECT_EQ(remote->foothold.position, local->foothold.position);
  EXPECT_EQ(remote->kinematics.q_f, local->kinematics.q_f);
  EXPECT_EQ(remote->kinematics.iterations, local->kinematics.iterations);
  EXPECT_EQ(remote->kinematics.position_residual, local->kinematics.position_residual);

  const CandidateCheck short_answer = [&](const FootholdCandidates& batch) {
    FootholdCandidates first = batch;
    first.candidates.resize(1);
    return checkFootholdCandidates(*kf, first, false);
  };
  EXPECT_THROW(search.find(Side::kLeft, stance, target, {}, std::nullopt, short_answer),
               ReachError);
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
