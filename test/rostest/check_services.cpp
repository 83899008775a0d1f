// rostest checker of services.test (a gtest executable run by rostest): malformed requests to
// check_reachability and plan_transition get success = false with the reason, the nodes keep
// serving, and a round trip of each service on our robot returns a well-formed answer.

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "reach_trajopt/CheckReachability.h"
#include "reach_trajopt/PlanTransition.h"
#include "reference_step.h"

namespace {

using reach_trajopt::test::fillReferenceStep;

int g_nq = 0, g_nu = 0;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A malformed variant of a request and a piece of the reason it must get.
template <typename Req>
std::vector<std::pair<std::string, Req>> malformed() {
  std::vector<std::pair<std::string, Req>> cases;
  Req base;
  fillReferenceStep(base);
  auto add = [&](const std::string& reason, auto edit) {
    Req r = base;
    edit(r);
    cases.emplace_back(reason, r);
  };
  add("non-finite", [](Req& r) {
    r.q.assign(g_nq, kNaN);
    r.qd.assign(g_nq, 0.0);
  });
  add("expected size", [](Req& r) {
    r.q.assign(3, 0.0);
    r.qd.assign(3, 0.0);
  });
  add("non-finite", [](Req& r) { r.foothold.x = kNaN; });
  add("unknown frame 'map'", [](Req& r) { r.header.frame_id = "map"; });
  add("empty contact set", [](Req& r) { r.contact_mode = ""; });
  add("empty contact set", [](Req& r) { r.contact_mode = "flight"; });
  add("no swing sole", [](Req& r) { r.contact_mode = "DS"; });
  add("SS-X", [](Req& r) { r.contact_mode = "SS-X"; });
  add("must lie on the ground", [](Req& r) { r.foothold.z = 0.3; });
  add("must be positive", [](Req& r) { r.swing_duration = -1.0; });
  return cases;
}

}  // namespace

// Each malformed() variant of Srv's request: `service` answers success = false with the reason
// and an "error" status (`statusOf(response)`), and keeps serving.
template <typename Srv, typename StatusOf>
void expectMalformedRejected(const char* service, StatusOf statusOf) {
  for (auto& [reason, req] : malformed<typename Srv::Request>()) {
    Srv srv;
    srv.request = req;
    ASSERT_TRUE(ros::service::call(service, srv)) << "the node stopped serving";
    EXPECT_FALSE(srv.response.success) << reason;
    EXPECT_NE(srv.response.message.find(reason), std::string::npos)
        << "expected '" << reason << "' in: " << srv.response.message;
    EXPECT_EQ(statusOf(srv.response), "error");
  }
}

TEST(Services, CheckReachabilityRejectsMalformedRequests) {
  expectMalformedRejected<reach_trajopt::CheckReachability>(
      "check_reachability", [](const auto& res) { return res.result.verdict; });
}

TEST(Services, PlanTransitionRejectsMalformedRequests) {
  expectMalformedRejected<reach_trajopt::PlanTransition>(
      "plan_transition", [](const auto& res) { return res.trajectory.status; });
}

TEST(Services, CheckReachabilityRoundTrip) {
  reach_trajopt::CheckReachability srv;
  fillReferenceStep(srv.request);     // empty q: the node's standing pose, left sole the stance
  srv.request.forward_samples = 300;  // a small check: this tests the plumbing
  srv.request.return_samples = true;
  ASSERT_TRUE(ros::service::call("check_reachability", srv));
  const auto& r = srv.response.result;
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  EXPECT_TRUE(r.verdict == "reachable" || r.verdict == "unreachable") << r.verdict;
  EXPECT_EQ(r.header.frame_id, "world");
  EXPECT_EQ(r.swing_frame, "r_sole");
  EXPECT_DOUBLE_EQ(r.foothold.x, 0.05);
  if (r.message.rfind("kinematically infeasible", 0) != 0) {
    EXPECT_GT(r.slices.size(), 0u);
    EXPECT_GT(r.forward_samples, 0u);
    EXPECT_GT(r.total_time, 0.0);
    EXPECT_GT(r.qps, 0u);
    // The adaptive budget: one budget or two; a check that gave up drew one and is unreachable.
    EXPECT_TRUE(r.budgets == 1u || r.budgets == 2u) << r.budgets;
    if (r.gave_up) {
      EXPECT_EQ(r.budgets, 1u);
      EXPECT_EQ(r.verdict, "unreachable");
    }
    EXPECT_LE(r.overlap_start, r.overlap_end);
    for (const auto& s : r.slices) {
      EXPECT_EQ(s.header.frame_id, "world");
      EXPECT_TRUE(s.hausdorff_distance >= 0.0 || s.hausdorff_distance == -1.0);
      for (const auto& p : s.forward_outputs) EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y));
    }
  }
  std::printf("check_reachability: %s\n", srv.response.message.c_str());
  reach_trajopt::CheckReachability again;
  fillReferenceStep(again.request);
  again.request.contact_mode = "DS";
  ASSERT_TRUE(ros::service::call("check_reachability", again));
  EXPECT_FALSE(again.response.success);
}

TEST(Services, PlanTransitionRoundTrip) {
  reach_trajopt::PlanTransition srv;
  fillReferenceStep(srv.request);
  srv.request.allow_relaxation = true;
  ASSERT_TRUE(ros::service::call("plan_transition", srv));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  const auto& t = srv.response.trajectory;
  std::printf("plan_transition: %s\n", srv.response.message.c_str());
  EXPECT_TRUE(t.status == "converged" || t.status == "relaxed" || t.status == "failed");
  const size_t n = t.time.size();
  ASSERT_GT(n, 1u);
  EXPECT_EQ(t.joint_names.size(), static_cast<size_t>(g_nq));
  EXPECT_EQ(t.actuated_joint_names.size(), static_cast<size_t>(g_nu));
  EXPECT_EQ(t.q.size(), n * g_nq);
  EXPECT_EQ(t.qd.size(), n * g_nq);
  EXPECT_EQ(t.u.size(), n * g_nu);
  EXPECT_EQ(t.lambda.size(), n * 6 * t.contact_frames.size());
  for (size_t k = 1; k < n; ++k) EXPECT_GT(t.time[k], t.time[k - 1]);
  for (double v : t.q) ASSERT_TRUE(std::isfinite(v));
  EXPECT_EQ(srv.response.reachability.verdict, "not_checked");
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "check_services");
  ros::NodeHandle nh;
  std::string urdf;
  if (!nh.getParam("robot_description", urdf)) {
    std::fprintf(stderr, "robot_description not set\n");
    return 1;
  }
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(urdf);
  for (const auto& [name, joint] : model->joints_)
    if (joint->type != urdf::Joint::FIXED) ++g_nu;
  g_nq = 6 + g_nu;
  if (!ros::service::waitForService("check_reachability", ros::Duration(120)) ||
      !ros::service::waitForService("plan_transition", ros::Duration(120))) {
    std::fprintf(stderr, "the services did not come up\n");
    return 1;
  }
  return RUN_ALL_TESTS();
}
