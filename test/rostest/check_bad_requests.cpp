// rostest checker of bad_requests.test (a gtest executable run by rostest): both service nodes
// get a few thousand malformed or over-limit requests, each must be rejected (success = false,
// a reason) without the node growing (resident memory read from /proc/<pid>/status) or
// stopping, and then a valid request must still be answered. Prints the BENCH line. The
// walking loop's plan_footstep gets malformed requests too, each rejected naming its field,
// then a valid one; so does a reachability worker's check_footholds (the request id echoed),
// reachability_node's check_footstep and tvr_planner_node's propose_footstep.

#include <gtest/gtest.h>
#include <ros/master.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <xmlrpcpp/XmlRpcClient.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "reach_trajopt/CheckFootholds.h"
#include "reach_trajopt/CheckFootstep.h"
#include "reach_trajopt/CheckReachability.h"
#include "reach_trajopt/PlanFootstep.h"
#include "reach_trajopt/PlanTransition.h"
#include "reach_trajopt/ProposeFootstep.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/ros/foothold_candidate_msgs.h"
#include "reach_trajopt/ros/footstep_check_msgs.h"
#include "reach_trajopt/ros/footstep_plan_msgs.h"
#include "reach_trajopt/ros/tvr_proposal_msgs.h"
#include "reach_trajopt/walk/standing_pose.h"
#include "reference_step.h"

namespace {

using reach_trajopt::test::fillReferenceStep;

constexpr int kNq = 18;      // urdf/biped.urdf: 6 virtual + 12 leg joints
constexpr int kRounds = 12;  // rounds over all malformed kinds, per service and pass
/// The bound on the resident memory's growth per pass after the warm-up (the smaller of the
/// median increment and the floor's rise, see below) [KiB per pass of 432 requests]: a leak of
/// 0.5 KiB per request fails it. Measured on the 2-core test machine, bad_requests.test run
/// alone 10 times in a row (both nodes' VmRSS summed, 10 passes after the warm-up), with the
/// launch file's fixed mmap threshold: 0.0 KiB per pass in 9 runs, 1.6 in one, 0.01-0.03 MiB
/// end to end. Without it glibc's heap stepped by 3-5 MiB up and back between passes (2 of 20
/// runs failed the bound).
constexpr double kMaxSlopeKiB = 200.0;
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

/// PID of the node `node` of this test's own ROS graph, -1 if none: its URI from the master
/// (lookupNode), then its pid from the node itself (getPid), as `rosnode info` does. Another
/// graph's node of the same name (a rostest run beside this one) is not this one.
int pidOf(const std::string& node) {
  XmlRpc::XmlRpcValue args, response, uri;
  args[0] = ros::this_node::getName();
  args[1] = "/" + node;
  if (!ros::master::execute("lookupNode", args, response, uri, false) ||
      uri.getType() != XmlRpc::XmlRpcValue::TypeString)
    return -1;
  std::string host;
  uint32_t port = 0;
  if (!ros::network::splitURI(static_cast<std::string>(uri), host, port)) return -1;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue caller, answer;
  caller[0] = ros::this_node::getName();
  if (!client.execute("getPid", caller, answer) ||
      answer.getType() != XmlRpc::XmlRpcValue::TypeArray || answer.size() != 3 ||
      answer[0].getType() != XmlRpc::XmlRpcValue::TypeInt || static_cast<int>(answer[0]) != 1 ||
      answer[2].getType() != XmlRpc::XmlRpcValue::TypeInt)
    return -1;
  return static_cast<int>(answer[2]);
}

/// Resident memory of `pid` [MiB] (VmRSS), -1 when the process is gone.
double rssMiB(int pid) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return -1.0;
}

/// The malformed kinds: each edits a default request (left stance, foothold on the ground).
template <typename Req>
std::vector<std::function<void(Req&)>> kinds(std::mt19937& rng) {
  std::vector<std::function<void(Req&)>> k;
  k.push_back([](Req& r) {
    r.q.assign(kNq, kNaN);
    r.qd.assign(kNq, 0.0);
  });
  k.push_back([](Req& r) {
    r.q.assign(kNq, 0.0);
    r.qd.assign(kNq, kInf);
  });
  k.push_back([](Req& r) {
    r.q.assign(kNq - 1, 0.0);
    r.qd.assign(kNq - 1, 0.0);
  });
  k.push_back([](Req& r) {
    r.q.assign(200000, 0.0);
    r.qd.assign(200000, 0.0);
  });                                                 // 3 MB
  k.push_back([](Req& r) { r.q.assign(kNq, 0.0); });  // qd missing
  k.push_back([](Req& r) { r.foothold.x = kNaN; });
  k.push_back([](Req& r) { r.foothold.y = -kInf; });
  k.push_back([](Req& r) { r.foothold.z = 1e300; });
  k.push_back([](Req& r) { r.header.frame_id = "map"; });
  k.push_back([&](Req& r) { r.header.frame_id = std::string(1 + rng() % 64, 'a' + rng() % 26); });
  k.push_back([](Req& r) { r.contact_mode = ""; });
  k.push_back([](Req& r) { r.contact_mode = "DS"; });
  k.push_back([](Req& r) { r.contact_mode = std::string("SS-\0L", 5); });
  k.push_back([](Req& r) { r.swing_duration = -1.0; });
  k.push_back([](Req& r) { r.swing_duration = kNaN; });
  k.push_back([](Req& r) { r.swing_duration = 1000.0; });  // over the duration limit
  k.push_back([](Req& r) { r.swing_duration = 1e-300; });
  return k;
}

struct Tally {
  int calls = 0, answered = 0;
};

/// ros::service::call, tried once more when it fails. A failed call is a transport failure
/// (the nodes answer every request, valid or not, with true): seen once in a CI run while
/// the node had logged its answer. The retry waits for the service first, so a node that
/// stopped serving still fails the test; the first failure is printed, not hidden.
template <typename Srv>
bool callService(const std::string& service, Srv& srv) {
  if (ros::service::call(service, srv)) return true;
  std::fprintf(stderr, "%s: call failed in transport, retrying once\n", service.c_str());
  return ros::service::waitForService(service, ros::Duration(10)) &&
         ros::service::call(service, srv);
}

/// The malformed requests of one service: each an edit of a valid request and the field its
/// rejection must name.
template <typename Srv>
using FieldEdits = std::vector<std::pair<std::string, std::function<void(typename Srv::Request&)>>>;

/// Each edit of `valid` is rejected by `service` with a message that starts "<field>:"
/// (`check` may look at more of each rejection), and the node keeps serving: the answer to
/// `valid` itself is returned.
template <typename Srv>
typename Srv::Response expectEachRejected(
    const std::string& service, const typename Srv::Request& valid, const FieldEdits<Srv>& kinds,
    const std::function<void(const typename Srv::Response&, const std::string&)>& check = {}) {
  for (const auto& [field, edit] : kinds) {
    Srv srv;
    srv.request = valid;
    edit(srv.request);
    EXPECT_TRUE(callService(service, srv)) << "stopped serving at " << field;
    EXPECT_FALSE(srv.response.success) << field;
    EXPECT_EQ(srv.response.message.rfind(field + ":", 0), 0u)
        << field << ": " << srv.response.message;
    if (check) check(srv.response, field);
  }
  Srv srv;
  srv.request = valid;
  EXPECT_TRUE(callService(service, srv));
  return srv.response;
}

/// The robot of the test's robot_description parameter.
std::shared_ptr<const reach_trajopt::RobotModel> robotDescriptionModel() {
  std::string urdf;
  if (!ros::NodeHandle().getParam("robot_description", urdf))
    throw std::runtime_error("no robot_description parameter");
  return reach_trajopt::RobotModel::fromUrdfString(urdf, {}, "robot_description");
}

/// Standing on the left sole, the right one to land where it stands.
reach_trajopt::ContactTransition standingStep(const reach_trajopt::RobotModel& model) {
  using namespace reach_trajopt;
  ContactTransition t;
  t.stance = Side::kLeft;
  t.q0 = standingConfiguration(model, 0.6, "l_sole", RobotConfig{});
  t.qd0 = Eigen::VectorXd::Zero(model.nq());
  Workspace ws(model);
  model.update(ws, t.q0, t.qd0);
  t.stance_contact = FlatContact::fromPose(model.framePose(ws, model.frameId("l_sole")));
  t.target = {model.framePose(ws, model.frameId("r_sole")).translation(), t.stance_contact.yaw};
  return t;
}

template <typename Srv>
void hammer(const char* service, Tally& t, std::function<void(typename Srv::Request&)> extra) {
  // One persistent connection per pass: a malformed request must not break it either.
  ros::NodeHandle nh;
  ros::ServiceClient client = nh.serviceClient<Srv>(service, true);
  // A failed call is retried once on a new connection after waiting for the service (as
  // callService() does): a node that stopped serving still fails the test.
  auto call = [&](Srv& srv) {
    if (!client.isValid()) client = nh.serviceClient<Srv>(service, true);
    if (client.call(srv)) return true;
    std::fprintf(stderr, "%s: persistent call failed in transport, retrying once\n", service);
    if (!ros::service::waitForService(service, ros::Duration(10))) return false;
    client = nh.serviceClient<Srv>(service, true);
    return client.call(srv);
  };
  std::mt19937 rng(1);
  const auto all = kinds<typename Srv::Request>(rng);
  for (int round = 0; round < kRounds; ++round) {
    for (std::size_t i = 0; i < all.size(); ++i) {
      Srv srv;
      fillReferenceStep(srv.request);
      all[i](srv.request);
      ++t.calls;
      if (!call(srv)) {
        ADD_FAILURE() << service << " stopped serving at kind " << i;
        return;
      }
      if (!srv.response.success && !srv.response.message.empty())
        ++t.answered;
      else
        ADD_FAILURE() << service << " kind " << i << " accepted: " << srv.response.message;
    }
    Srv srv;  // a service-specific over-limit request
    fillReferenceStep(srv.request);
    extra(srv.request);
    ++t.calls;
    if (call(srv) && !srv.response.success) ++t.answered;
  }
}

}  // namespace

TEST(BadRequests, NodesRejectEverythingAndStayFlat) {
  const int pid_reach = pidOf("reachability_node"), pid_ocp = pidOf("transition_ocp_node");
  ASSERT_GT(pid_reach, 0);
  ASSERT_GT(pid_ocp, 0);
  Tally t;
  auto pass = [&t]() {
    hammer<reach_trajopt::CheckReachability>("check_reachability", t, [](auto& r) {
      r.forward_samples = 10000000u;  // 1e7 samples (the 1.6 GB request)
    });
    hammer<reach_trajopt::PlanTransition>("plan_transition", t, [](auto& r) {
      r.swing_duration = 1000.0;  // the 1000 s horizon
    });
  };
  // Warm up: the nodes' first calls allocate lazily (connections, buffers, malloc arenas) and
  // that is not growth. Then the growth per pass over kPasses passes (the resident memory
  // after each), so neither the warm-up nor a one-time step of the allocator counts as a leak
  // the way an end-to-end difference did (issue 43: 8.9 MiB of warm-up against a fixed 8 MiB).
  hammer<reach_trajopt::CheckReachability>("check_reachability", t, [](auto& r) {
    r.forward_samples = 1000000000u;  // 1e9 samples: rejected before any sample is drawn
  });
  hammer<reach_trajopt::PlanTransition>("plan_transition", t,
                                        [](auto& r) { r.swing_duration = 1e9; });
  pass();
  constexpr int kPasses = 10;
  std::vector<double> rss{rssMiB(pid_reach) + rssMiB(pid_ocp)};
  t = Tally();
  const auto t0 = std::chrono::steady_clock::now();
  for (int rep = 0; rep < kPasses; ++rep) {
    pass();
    rss.push_back(rssMiB(pid_reach) + rssMiB(pid_ocp));
    std::printf("rss after %d passes: %.2f MiB\n", rep + 1, rss.back());
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // The growth per pass, two ways that a leak (growth every pass) both show: the median of the
  // passes' increments, which ignores the allocator's one-time step (3 MiB once, in 2 of 10
  // runs measured); and the rise of the floor (the smallest value) of the second half of the
  // passes over the first half's, per pass, which ignores its steps back and forth pass to pass
  // (+-3 MiB alternating, in 1 of 10 runs: the median of those increments is half a step).
  // The smaller of the two is the growth.
  std::vector<double> increments;
  for (std::size_t i = 1; i < rss.size(); ++i) increments.push_back(rss[i] - rss[i - 1]);
  std::sort(increments.begin(), increments.end());
  const double median_increment =
      0.5 * (increments[(increments.size() - 1) / 2] + increments[increments.size() / 2]);
  const std::size_t half = rss.size() / 2;
  const double floor_rise =
      (*std::min_element(rss.begin() + static_cast<std::ptrdiff_t>(half), rss.end()) -
       *std::min_element(rss.begin(), rss.begin() + static_cast<std::ptrdiff_t>(half))) /
      static_cast<double>(half);
  const double slope = std::min(median_increment, floor_rise);
  const int calls_per_pass = t.calls / kPasses;
  // Still serving: a valid, small check.
  reach_trajopt::CheckReachability ok;
  fillReferenceStep(ok.request);
  ok.request.forward_samples = 200;
  const bool alive = callService("check_reachability", ok) && ok.response.success &&
                     rssMiB(pid_reach) > 0 && rssMiB(pid_ocp) > 0;
  std::printf(
      "BENCH ros.bad_requests calls=%d answered=%d node_alive=%d passes=%d "
      "rss_median_kib_per_pass=%.1f rss_growth_mib=%.2f seconds=%.1f\n",
      t.calls, t.answered, alive ? 1 : 0, kPasses, 1024.0 * slope, rss.back() - rss.front(),
      seconds);
  std::fflush(stdout);
  EXPECT_EQ(t.answered, t.calls);
  EXPECT_TRUE(alive) << ok.response.message;
  // Flat: a leak of 1 KiB per request is calls_per_pass KiB per pass (432).
  EXPECT_LT(1024.0 * slope, kMaxSlopeKiB) << "resident memory grows by " << 1024.0 * slope
                                          << " KiB per pass of " << calls_per_pass << " requests";
}

// The longest swing a request may ask (5 s, docs/limits.md) must still end within the OCP's
// time limit (ocp.time_limit = 10 s in config/biped.yaml) plus the sampling of the answer.
TEST(BadRequests, LongestAllowedSwingKeepsTheTimeLimit) {
  reach_trajopt::PlanTransition srv;
  fillReferenceStep(srv.request);
  srv.request.swing_duration = 5.0;
  srv.request.allow_relaxation = true;
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_TRUE(callService("plan_transition", srv));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // The 2 % target is the BENCH line's (a benchmark figure); the test's bound is generous.
  constexpr double kLimit = 10.0;
  std::printf(
      "BENCH ros.longest_swing seconds=%.2f limit_s=%.1f ratio=%.3f within_2pct=%s status=%s\n",
      seconds, kLimit, seconds / kLimit, seconds <= 1.02 * kLimit ? "yes" : "no",
      srv.response.trajectory.status.c_str());
  EXPECT_LT(seconds, kLimit + 5.0) << srv.response.message;
}

// `service` answers the reference step with `duration` [s] with success = false and a message
// containing `words`.
template <typename Srv>
void expectSwingDurationRejected(const char* service, double duration, const std::string& words) {
  Srv srv;
  fillReferenceStep(srv.request);
  srv.request.swing_duration = duration;
  ASSERT_TRUE(callService(service, srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find(words), std::string::npos) << srv.response.message;
}

// A swing_duration of inf or 1e-9 s is answered about swing_duration (issue 43: "must be
// positive" and a message about window_start multiples of dt), by both services.
TEST(BadRequests, SwingDurationMessagesNameTheProblem) {
  const std::pair<double, std::string> cases[] = {
      {kInf, "swing_duration must be finite"},
      {1e-9, "swing_duration 1e-09 s is shorter than one time step of the check"}};
  for (const auto& [duration, words] : cases) {
    expectSwingDurationRejected<reach_trajopt::CheckReachability>("check_reachability", duration,
                                                                  words);
    expectSwingDurationRejected<reach_trajopt::PlanTransition>("plan_transition", duration, words);
  }
}

// plan_footstep (the walking loop's per-step service of transition_ocp_node): each malformed
// request is rejected naming its field; the node then answers a valid one.
TEST(BadRequests, PlanFootstepRejectsNamingTheFieldAndServesOn) {
  using namespace reach_trajopt;
  const auto model = robotDescriptionModel();
  FootstepPlanRequest request(standingStep(*model));  // kinematic check only: fast
  request.check_reachability = false;
  request.solve_ocp = false;
  const reach_trajopt::PlanFootstep::Request valid =
      ros_bridge::toPlanFootstepRequestMsg(request, ReachConfig(), ros::Time(0));
  const FieldEdits<reach_trajopt::PlanFootstep> kinds = {
      {"header.frame_id", [](auto& r) { r.header.frame_id = "map"; }},
      {"stance", [](auto& r) { r.stance = "SS-L"; }},
      {"stance_pose", [](auto& r) { r.stance_pose.assign(3, 0.0); }},
      {"stance_pose", [](auto& r) { r.stance_pose[4] = 5.0; }},
      {"target", [](auto& r) { r.target.x = kNaN; }},
      {"target_yaw", [](auto& r) { r.target_yaw = {kInf}; }},
      {"q", [](auto& r) { r.q.assign(200000, 0.0); }},
      {"qd", [](auto& r) { r.qd[0] = kNaN; }},
      {"touchdown_com", [](auto& r) { r.touchdown_com = {1.0}; }},
      {"horizon", [](auto& r) { r.horizon = 1e9; }},
      {"reach_horizon", [](auto& r) { r.reach_horizon = kNaN; }},
      {"seed", [](auto& r) { r.seed = -5; }},
      {"ocp_policy", [](auto& r) { r.ocp_policy = "sometimes"; }},
      {"on_infeasible", [](auto& r) { r.on_infeasible = "panic"; }},
  };
  const auto answer = expectEachRejected<reach_trajopt::PlanFootstep>(
      "plan_footstep", valid, kinds, [](const auto& response, const std::string& field) {
        EXPECT_EQ(response.trajectory.status, "error") << field;
      });
  EXPECT_TRUE(answer.success) << answer.message;
  EXPECT_EQ(answer.verdict,
            answer.kinematically_feasible ? "kinematically_feasible" : "kinematically_infeasible");
}

TEST(BadRequests, CheckFootholdsRejectsNamingTheFieldAndServesOn) {
  using namespace reach_trajopt;
  const auto model = robotDescriptionModel();
  // Standing on the left sole; three candidates for the right one around where it stands.
  FootholdCandidates batch;
  batch.stance = Side::kLeft;
  batch.q_init = standingConfiguration(*model, 0.6, "l_sole", RobotConfig{});
  Workspace ws(*model);
  model->update(ws, batch.q_init, Eigen::VectorXd::Zero(model->nq()));
  batch.stance_contact.position = model->framePose(ws, model->frameId("l_sole")).translation();
  for (double dx : {-0.02, 0.0, 0.02}) {
    FlatContact c;
    c.position = model->framePose(ws, model->frameId("r_sole")).translation();
    c.position.x() += dx;
    batch.candidates.push_back(c);
  }
  const reach_trajopt::CheckFootholds::Request valid =
      ros_bridge::toCheckFootholdsRequestMsg(batch, 77);
  const FieldEdits<reach_trajopt::CheckFootholds> kinds = {
      {"stance", [](auto& r) { r.stance = "SS-L"; }},
      {"stance_position", [](auto& r) { r.stance_position.z = kNaN; }},
      {"stance_yaw", [](auto& r) { r.stance_yaw = kInf; }},
      {"candidate_yaw", [](auto& r) { r.candidate_yaw.pop_back(); }},
      {"candidates[1]", [](auto& r) { r.candidates[1].x = kNaN; }},
      {"q_init", [](auto& r) { r.q_init.assign(200000, 0.0); }},
      {"pelvis_position", [](auto& r) { r.pelvis_position = {1.0}; }},
      // A million candidates (24 s and 1.15 GB before the cap, issue 43).
      {"candidates",
       [](auto& r) {
         r.candidates.resize(1000000);
         r.candidate_yaw.resize(1000000);
       }},
  };
  const auto answer = expectEachRejected<reach_trajopt::CheckFootholds>(
      "check_footholds", valid, kinds, [](const auto& response, const std::string& field) {
        EXPECT_EQ(response.request_id, 77u) << field;
      });
  ASSERT_TRUE(answer.success) << answer.message;
  EXPECT_EQ(answer.request_id, 77u);
  EXPECT_EQ(ros_bridge::fromCheckFootholdsResponseMsg(answer, 3, model->nq()).size(), 3u);
}

// check_footstep (reachability_node's check of one walk footstep): each malformed request is
// rejected naming its field; the node then answers a valid one.
TEST(BadRequests, CheckFootstepRejectsNamingTheFieldAndServesOn) {
  using namespace reach_trajopt;
  const auto model = robotDescriptionModel();
  const ContactTransition request = standingStep(*model);  // kinematic check only
  const reach_trajopt::CheckFootstep::Request valid = ros_bridge::toCheckFootstepRequestMsg(
      request, ReachConfig(), std::nullopt, false, false, ros::Time(0));
  const FieldEdits<reach_trajopt::CheckFootstep> kinds = {
      {"header.frame_id", [](auto& r) { r.header.frame_id = "map"; }},
      {"stance", [](auto& r) { r.stance = "SS-L"; }},
      {"stance_contact", [](auto& r) { r.stance_contact.assign(3, 0.0); }},
      {"target", [](auto& r) { r.target[0] = kNaN; }},
      {"q0", [](auto& r) { r.q0.assign(200000, 0.0); }},
      {"qd0", [](auto& r) { r.qd0[0] = kNaN; }},
      {"qdf", [](auto& r) { r.qdf = {1.0}; }},
      {"touchdown_com_velocity",
       [](auto& r) {
         r.touchdown_com_velocity = {kInf, 0.0};
       }},
      {"touchdown_pelvis_position", [](auto& r) { r.touchdown_pelvis_position = {1.0}; }},
      {"reach_horizon", [](auto& r) { r.reach_horizon = kNaN; }},
      {"seed", [](auto& r) { r.seed = -5; }},
      {"budget", [](auto& r) { r.budget.resize(2); }},
      {"forward_until",
       [](auto& r) {
         r.budget.resize(1);
         r.forward_until = {0.01};  // without forward_set_only
       }},
  };
  const auto answer =
      expectEachRejected<reach_trajopt::CheckFootstep>("check_footstep", valid, kinds);
  ASSERT_TRUE(answer.success) << answer.message;
  EXPECT_EQ(answer.q_f.size(), static_cast<size_t>(model->nq()));
  ros_bridge::fromCheckFootstepResponseMsg(answer, model->nq());  // well formed
}

// propose_footstep (tvr_planner_node's stateless TVR proposal): each malformed request is
// rejected naming its field; the node then answers a valid one.
TEST(BadRequests, ProposeFootstepRejectsNamingTheFieldAndServesOn) {
  using namespace reach_trajopt;
  TvrProposalRequest request;
  request.measured.p = Eigen::Vector2d(0.0, 0.02);
  request.measured.pd = Eigen::Vector2d(0.0, 0.3);
  request.stance = Eigen::Vector2d(0.0, 0.1);
  request.swing = Side::kRight;
  request.time = 0.2;
  request.remaining = 0.22;
  request.com_height = 0.9;
  const reach_trajopt::ProposeFootstep::Request valid =
      ros_bridge::toProposeFootstepRequestMsg(request, ros::Time(0));
  const FieldEdits<reach_trajopt::ProposeFootstep> kinds = {
      {"com", [](auto& r) { r.com = {1.0}; }},
      {"stance", [](auto& r) { r.stance[0] = kNaN; }},
      {"swing", [](auto& r) { r.swing = "up"; }},
      {"time", [](auto& r) { r.time = kInf; }},
      {"remaining", [](auto& r) { r.remaining = -1.0; }},
      {"x_start", [](auto& r) { r.x_start = kNaN; }},
      {"forward_speed", [](auto& r) { r.forward_speed = kNaN; }},
      {"y_mid", [](auto& r) { r.y_mid = kInf; }},
      {"com_height", [](auto& r) { r.com_height = 0.0; }},
  };
  const auto answer =
      expectEachRejected<reach_trajopt::ProposeFootstep>("propose_footstep", valid, kinds);
  ASSERT_TRUE(answer.success) << answer.message;
  const TvrProposal p = ros_bridge::fromProposeFootstepResponseMsg(answer, request);
  EXPECT_TRUE(p.step.alpha.allFinite());
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "check_bad_requests");
  if (!ros::service::waitForService("check_reachability", ros::Duration(120)) ||
      !ros::service::waitForService("plan_transition", ros::Duration(120)) ||
      !ros::service::waitForService("plan_footstep", ros::Duration(120)) ||
      !ros::service::waitForService("check_footholds", ros::Duration(120)) ||
      !ros::service::waitForService("check_footstep", ros::Duration(120)) ||
      !ros::service::waitForService("propose_footstep", ros::Duration(120))) {
    std::fprintf(stderr, "the services did not come up\n");
    return 1;
  }
  return RUN_ALL_TESTS();
}
