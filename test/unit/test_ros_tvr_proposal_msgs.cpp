// ROS layer, the propose_footstep service's conversions (no master): the walking loop's TVR
// proposal sent through the request and answered through the response is, bit for bit, what
// its own planner proposes in process (eq. 11, planner/tvr_proposal.h), for either swing side
// and with or without the heuristic bounds; malformed requests are rejected naming the field,
// malformed answers too.

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <random>
#include <string>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/ros/tvr_proposal_msgs.h"
#include "ros_message_checks.h"

using namespace reach_trajopt;
namespace rb = reach_trajopt::ros_bridge;
using reach_trajopt::test::expectRejected;
using reach_trajopt::test::sameBits;

namespace {

const std::string kRepo = REACH_TRAJOPT_SOURCE_DIR;

TvrConfig shippedPlanner() {
  return TvrConfig::fromYaml(
      YamlSection::loadFile(kRepo + "/config/biped.yaml").section("planner"));
}

// A walking-loop request with every bit of the mantissas in use.
TvrProposalRequest randomRequest(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  TvrProposalRequest r;
  r.measured.p = Eigen::Vector2d(0.3 * u(rng), 0.05 * u(rng));
  r.measured.pd = Eigen::Vector2d(0.4 * u(rng), 0.5 * u(rng));
  r.stance = r.measured.p + Eigen::Vector2d(0.05 * u(rng), 0.1 * u(rng));
  r.swing = seed % 2 == 0 ? Side::kLeft : Side::kRight;
  r.time = 2.0 + u(rng);
  r.remaining = 0.1 + 0.05 * u(rng);
  r.x_start = 0.01 * u(rng);
  r.forward_speed = 0.2 * u(rng);
  r.y_mid = 0.01 * u(rng);
  r.com_height = 0.8 + 0.1 * u(rng);
  r.heuristic_bounds = seed % 3 == 0;
  return r;
}

}  // namespace

TEST(RosTvrProposalMsgs, ProposalThroughTheMessagesIsTheInProcessProposal) {
  const TvrConfig config = shippedPlanner();
  int clipped = 0;
  for (unsigned seed = 0; seed < 24; ++seed) {
    const TvrProposalRequest request = randomRequest(seed);
    const TvrProposal here = proposeFootstep(config, request);
    // The node's side: the request as it arrives, planned, answered.
    const auto request_msg = rb::toProposeFootstepRequestMsg(request, ros::Time(3.0));
    EXPECT_EQ(request_msg.header.frame_id, "world");
    const TvrProposalRequest arrived = rb::fromProposeFootstepRequestMsg(request_msg);
    const auto response = rb::toProposeFootstepResponseMsg(proposeFootstep(config, arrived));
    ASSERT_TRUE(response.success);
    // The loop's side.
    const TvrProposal there = rb::fromProposeFootstepResponseMsg(response, request);
    SCOPED_TRACE("seed " + std::to_string(seed));
    EXPECT_TRUE(sameBits(there.step.alpha_tvr, here.step.alpha_tvr));
    EXPECT_TRUE(sameBits(there.step.alpha, here.step.alpha));
    EXPECT_TRUE(sameBits(there.step.offset, here.step.offset));
    EXPECT_TRUE(sameBits(there.step.com_velocity_used, here.step.com_velocity_used));
    EXPECT_EQ(there.step.speed_clipped, here.step.speed_clipped);
    EXPECT_EQ(there.step.offset_clipped, here.step.offset_clipped);
    EXPECT_TRUE(sameBits(there.input.com.p, here.input.com.p));
    EXPECT_TRUE(sameBits(there.input.com.pd, here.input.com.pd));
    EXPECT_TRUE(sameBits(there.input.p_des, here.input.p_des));
    EXPECT_TRUE(sameBits(there.input.stance, here.input.stance));
    EXPECT_EQ(there.input.swing, here.input.swing);
    clipped += here.step.speed_clipped || here.step.offset_clipped;
  }
  // The bounds were exercised (the fields are not all false by default).
  EXPECT_GT(clipped, 0);
}

TEST(RosTvrProposalMsgs, MalformedRequestsAreRejectedNamingTheField) {
  const auto good = rb::toProposeFootstepRequestMsg(randomRequest(1), ros::Time(1.0));
  EXPECT_NO_THROW(rb::fromProposeFootstepRequestMsg(good));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto reject = [&](const std::function<void(reach_trajopt::ProposeFootstep::Request&)>& edit,
                    const std::string& field) {
    auto m = good;
    edit(m);
    expectRejected([&] { rb::fromProposeFootstepRequestMsg(m); }, field);
  };
  reject([](auto& m) { m.com.pop_back(); }, "com");
  reject([&](auto& m) { m.com[2] = nan; }, "com");
  reject([](auto& m) { m.stance.clear(); }, "stance");
  reject([&](auto& m) { m.stance[1] = std::numeric_limits<double>::infinity(); }, "stance");
  reject([](auto& m) { m.swing = "up"; }, "swing");
  reject([](auto& m) { m.swing = ""; }, "swing");
  reject([&](auto& m) { m.time = nan; }, "time");
  reject([](auto& m) { m.remaining = -1e-3; }, "remaining");
  reject([&](auto& m) { m.x_start = nan; }, "x_start");
  reject([&](auto& m) { m.forward_speed = nan; }, "forward_speed");
  reject([&](auto& m) { m.y_mid = nan; }, "y_mid");
  reject([](auto& m) { m.com_height = 0.0; }, "com_height");
  reject([](auto& m) { m.com_height = -0.9; }, "com_height");
  reject([&](auto& m) { m.com_height = nan; }, "com_height");
}

TEST(RosTvrProposalMsgs, MalformedAnswersAreErrorsNamingTheField) {
  const TvrProposalRequest request = randomRequest(2);
  const auto good = rb::toProposeFootstepResponseMsg(proposeFootstep(shippedPlanner(), request));
  EXPECT_NO_THROW(rb::fromProposeFootstepResponseMsg(good, request));
  for (const std::string field :
       {"alpha_tvr", "alpha", "offset", "com_velocity_used", "predicted_com", "p_des"}) {
    auto m = good;
    if (field == "alpha_tvr") m.alpha_tvr.pop_back();
    if (field == "alpha") m.alpha.push_back(0.0);
    if (field == "offset") m.offset.clear();
    if (field == "com_velocity_used") m.com_velocity_used.pop_back();
    if (field == "predicted_com") m.predicted_com.resize(2);
    if (field == "p_des") m.p_des.clear();
    try {
      rb::fromProposeFootstepResponseMsg(m, request);
      ADD_FAILURE() << field << ": accepted";
    } catch (const ReachError& e) {
      EXPECT_NE(std::string(e.what()).find(field + ":"), std::string::npos) << e.what();
    }
  }
}
