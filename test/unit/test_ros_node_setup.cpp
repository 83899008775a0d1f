// ROS layer, node helpers (no master): the temporary URDF file and the request handler that
// answers a bad request with its reason.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/ocp/transition_request.h"
#include "reach_trajopt/ros/node_setup.h"
#include "reach_trajopt/ros/sim_node.h"
#include "reach_trajopt/ros/transition_ocp_node_params.h"

namespace rb = reach_trajopt::ros_bridge;

TEST(RosNodeSetup, TempUrdfHoldsTheTextAndIsRemoved) {
  std::string path;
  {
    const rb::TempUrdf urdf("<robot name=\"r\"/>");
    path = urdf.path();
    std::ifstream in(path);
    ASSERT_TRUE(in.good()) << path;
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), "<robot name=\"r\"/>");
  }
  EXPECT_FALSE(std::ifstream(path).good()) << path << " was not removed";
}

TEST(RosNodeSetup, AnswerOrRejectFillsTheResponseWithTheReason) {
  std::string rejected;
  bool ran = false;
  EXPECT_TRUE(rb::answerOrReject(
      "svc", [&] { ran = true; }, [&](const std::string& r) { rejected = r; }));
  EXPECT_TRUE(ran);
  EXPECT_TRUE(rejected.empty());
  EXPECT_TRUE(rb::answerOrReject(
      "svc", [] { throw reach_trajopt::ReachError("unknown frame 'map'"); },
      [&](const std::string& r) { rejected = r; }));
  EXPECT_EQ(rejected, "unknown frame 'map'");
  EXPECT_TRUE(rb::answerOrReject(
      "svc", [] { throw std::runtime_error("other"); },
      [&](const std::string& r) { rejected = r; }));
  EXPECT_EQ(rejected, "other");
}

// `base` with `set` applied is refused by its validate(), the error naming `key`.
template <class Params, class Set>
void expectRefusedNaming(const Params& base, const std::string& key, Set set) {
  Params p = base;
  set(p);
  try {
    p.validate();
    ADD_FAILURE() << key << " accepted";
  } catch (const reach_trajopt::ReachError& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

TEST(RosNodeSetup, SimNodeParamsRefuseDurationsRosCannotHold) {
  EXPECT_NO_THROW(rb::SimNodeParams{}.validate());
  // ros::WallDuration holds 32-bit seconds: a 1e12 s ~linger ended the node after its walk.
  const auto refused = [](const std::string& key, auto set) {
    expectRefusedNaming(rb::SimNodeParams{}, key, set);
  };
  refused("~linger", [](rb::SimNodeParams& p) { p.linger = 1e12; });
  refused("~linger", [](rb::SimNodeParams& p) { p.linger = -1.0; });
  refused("~wait_timeout", [](rb::SimNodeParams& p) { p.wait_timeout = 1e12; });
  refused("~clock_period", [](rb::SimNodeParams& p) { p.clock_period = 1e12; });
  refused("~real_time_factor", [](rb::SimNodeParams& p) { p.real_time_factor = std::nan(""); });
}

TEST(RosNodeSetup, TransitionOcpNodeParamsRefuseWaitsAndCountsOutOfRange) {
  rb::TransitionOcpNodeParams fine;
  fine.default_horizon = 0.2;
  EXPECT_NO_THROW(fine.validate());
  // Checked before the node waits for its services: a negative ros::Duration waits for ever,
  // one past 32-bit seconds throws, and each absent worker costs ~worker_timeout at start.
  const auto refused = [&fine](const std::string& key, auto set) {
    expectRefusedNaming(fine, key, set);
  };
  using P = rb::TransitionOcpNodeParams;
  refused("~default_horizon", [](P& p) { p.default_horizon = 0.0; });
  refused("~default_horizon", [](P& p) { p.default_horizon = 100.0; });
  refused("~default_horizon", [](P& p) { p.default_horizon = std::nan(""); });
  refused("~check_timeout", [](P& p) { p.check_timeout = -1.0; });
  refused("~check_timeout", [](P& p) { p.check_timeout = 1e12; });
  refused("~workers", [](P& p) { p.workers = -1; });
  refused("~workers", [](P& p) { p.workers = 100000; });
  refused("~worker_timeout", [](P& p) { p.worker_timeout = 0.0; });
  refused("~worker_timeout", [](P& p) { p.worker_timeout = std::nan(""); });
  refused("~worker_retry_period", [](P& p) { p.worker_retry_period = -1.0; });
  refused("~worker_retry_period", [](P& p) { p.worker_retry_period = 1e12; });
  // The bounds themselves are accepted.
  P edge = fine;
  edge.default_horizon = reach_trajopt::kMaxTransitionHorizon;
  edge.workers = P::kMaxWorkers;
  edge.worker_timeout = edge.worker_retry_period = edge.check_timeout = P::kMaxWait;
  EXPECT_NO_THROW(edge.validate());
}
