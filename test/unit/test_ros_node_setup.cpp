// ROS layer, node helpers (no master): the temporary URDF file and the request handler that
// answers a bad request with its reason.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/ros/node_setup.h"

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
