// ROS layer, the check_footholds service's conversions (no master): a ring of candidate
// footholds and the workers' outcomes go through the messages and come back bit for bit (what
// a search through workers needs to equal the in-process one), a malformed request is rejected
// naming its field, a malformed response is an error naming its field.

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <string>
#include <vector>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/ros/foothold_candidate_msgs.h"
#include "ros_message_checks.h"

using namespace reach_trajopt;
namespace rb = reach_trajopt::ros_bridge;
using reach_trajopt::test::awkward;

namespace {

constexpr int kNq = 18;

FootholdCandidates makeBatch() {
  FootholdCandidates b;
  b.stance = Side::kRight;
  b.stance_contact.position = awkward(3, 1);
  b.stance_contact.yaw = 1.0 / 7.0;
  for (unsigned i = 0; i < 5; ++i) {
    FlatContact c;
    c.position = awkward(3, 10 + i);
    c.yaw = awkward(1, 20 + i)[0];
    b.candidates.push_back(c);
  }
  b.q_init = awkward(kNq, 2);
  b.pelvis_position = Eigen::Vector3d(awkward(3, 3));
  return b;
}

TEST(RosFootholdCandidateMsgs, RequestRoundTripIsBitExact) {
  const FootholdCandidates b = makeBatch();
  const reach_trajopt::CheckFootholds::Request m = rb::toCheckFootholdsRequestMsg(b, 42);
  EXPECT_EQ(m.request_id, 42u);
  const FootholdCandidates back = rb::fromCheckFootholdsRequestMsg(m, kNq);
  EXPECT_EQ(back.stance, b.stance);
  EXPECT_EQ(back.stance_contact.position, b.stance_contact.position);
  EXPECT_EQ(back.stance_contact.yaw, b.stance_contact.yaw);
  ASSERT_EQ(back.candidates.size(), b.candidates.size());
  for (size_t i = 0; i < b.candidates.size(); ++i) {
    EXPECT_EQ(back.candidates[i].position, b.candidates[i].position);
    EXPECT_EQ(back.candidates[i].yaw, b.candidates[i].yaw);
  }
  EXPECT_EQ(back.q_init, b.q_init);
  ASSERT_TRUE(back.pelvis_position.has_value());
  EXPECT_EQ(*back.pelvis_position, *b.pelvis_position);

  FootholdCandidates no_pelvis = b;
  no_pelvis.pelvis_position.reset();
  EXPECT_FALSE(rb::fromCheckFootholdsRequestMsg(rb::toCheckFootholdsRequestMsg(no_pelvis, 1), kNq)
                   .pelvis_position.has_value());
}

void expectRejected(const reach_trajopt::CheckFootholds::Request& m, const std::string& field) {
  try {
    rb::fromCheckFootholdsRequestMsg(m, kNq);
    ADD_FAILURE() << "accepted a bad " << field;
  } catch (const ReachError& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

TEST(RosFootholdCandidateMsgs, BadRequestsNameTheirField) {
  const reach_trajopt::CheckFootholds::Request good =
      rb::toCheckFootholdsRequestMsg(makeBatch(), 7);
  auto m = good;
  m.stance = "middle";
  expectRejected(m, "stance");
  m = good;
  m.candidate_yaw.pop_back();
  expectRejected(m, "candidate_yaw");
  m = good;
  m.candidates[2].y = std::numeric_limits<double>::quiet_NaN();
  expectRejected(m, "candidates[2]");
  m = good;
  m.q_init.pop_back();
  expectRejected(m, "q_init");
  m = good;
  m.pelvis_position.push_back(0.0);
  expectRejected(m, "pelvis_position");
  m = good;
  m.stance_yaw = std::numeric_limits<double>::infinity();
  expectRejected(m, "stance_yaw");
}

std::vector<CandidateOutcome> makeOutcomes() {
  std::vector<CandidateOutcome> out(3);
  out[0].kinematics.feasible = false;
  out[0].kinematics.reason = "knee limit";
  out[0].kinematics.position_residual = 1.0 / 3.0;
  out[0].kinematics.orientation_residual = 2.0 / 3.0;
  out[0].kinematics.iterations = 17;
  out[0].kinematics.q_f = awkward(kNq, 5);
  out[0].kinematics.qd_f = Eigen::VectorXd::Zero(kNq);
  out[1].error = "step outside the workspace";
  out[2].kinematics.feasible = true;
  out[2].kinematics.position_residual = 1e-13 / 3.0;
  out[2].kinematics.iterations = 4;
  out[2].kinematics.q_f = awkward(kNq, 6);
  out[2].kinematics.qd_f = awkward(kNq, 7);
  return out;
}

TEST(RosFootholdCandidateMsgs, ResponseRoundTripIsBitExact) {
  const std::vector<CandidateOutcome> out = makeOutcomes();
  const reach_trajopt::CheckFootholds::Response m = rb::toCheckFootholdsResponseMsg(out, 9);
  EXPECT_TRUE(m.success);
  EXPECT_EQ(m.request_id, 9u);
  const std::vector<CandidateOutcome> back = rb::fromCheckFootholdsResponseMsg(m, 3, kNq);
  ASSERT_EQ(back.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(back[i].error, out[i].error);
    const KinematicFeasibilityResult &a = back[i].kinematics, &b = out[i].kinematics;
    EXPECT_EQ(a.feasible, b.feasible);
    EXPECT_EQ(a.reason, b.reason);
    EXPECT_EQ(a.position_residual, b.position_residual);
    EXPECT_EQ(a.orientation_residual, b.orientation_residual);
    EXPECT_EQ(a.iterations, b.iterations);
    EXPECT_EQ(a.q_f, b.q_f);
    EXPECT_EQ(a.qd_f, b.qd_f);
  }
}

TEST(RosFootholdCandidateMsgs, MalformedResponsesNameTheirField) {
  const reach_trajopt::CheckFootholds::Response good =
      rb::toCheckFootholdsResponseMsg(makeOutcomes(), 9);
  auto expectError = [](const reach_trajopt::CheckFootholds::Response& m, size_t n,
                        const std::string& field) {
    try {
      rb::fromCheckFootholdsResponseMsg(m, n, kNq);
      ADD_FAILURE() << "accepted a bad " << field;
    } catch (const ReachError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  expectError(good, 4, "feasible");  // an answer for fewer candidates than asked
  auto m = good;
  m.q_f.pop_back();
  expectError(m, 3, "q_f");
  m = good;
  m.iterations.push_back(1);
  expectError(m, 3, "iterations");
}

}  // namespace
