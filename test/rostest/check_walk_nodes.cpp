// rostest checker of walk_nodes.test and killed_node_walk.test (a gtest executable run by
// rostest): the walk of walk.launch with ~in_process false (every contact proposed by
// tvr_planner_node's propose_footstep, every checked footstep planned by transition_ocp_node's
// plan_footstep, which checks it on reachability_node's check_footstep) gives the same WALK line
// and the same step records, byte for byte, as the same scenario run in process here, and every
// checked step's messages (reachability_result, transition_trajectory) arrive. The two differ
// only in wall times (wall_s of the WALK line, check_time and ocp_time).
// Without ~kill_after_steps every check's messages come from transition_ocp_node, every check
// was answered by /reachability_node (its latched footsteps_checked counts one per checked step)
// and every proposal by /tvr_planner_node (its footsteps_proposed: one per step at least, exactly
// one without replanning during the swing); with it, the
// checker kills transition_ocp_node (rosnode kill) when that many step reports have arrived:
// the walk must still equal the in-process one (sim_node plans the rest itself), the steps
// before come from transition_ocp_node, the last from sim_node, no step without its messages.
// With ~workers N (workers_walk.test) transition_ocp_node checks the candidates of its
// nearest-feasible-foothold search on N reachability workers: the walk must equal the
// in-process one and every worker must have checked candidates (its footholds_checked). With
// ~hang_worker_after_steps K as well, the checker hangs worker 0 (SIGSTOP, by the pid the node
// reports) once K step reports have arrived: its calls time out, its candidates go to the other
// worker, and the walk must still equal the in-process one with every step's messages from
// transition_ocp_node, and worker 1 must have checked whole rings since; worker 0 is continued
// (SIGCONT) at the end so the launch can stop it. With ~hang_planner true (hung_node_walk.test)
// the checker stops transition_ocp_node (SIGSTOP) instead of killing it: sim_node's call
// times out (~plan_timeout) and the rest is as when it was killed.

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <signal.h>
#include <std_msgs/String.h>
#include <std_msgs/UInt64.h>
#include <sys/types.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "message_bytes.h"
#include "reach_trajopt/CenterOfMassState.h"
#include "reach_trajopt/ReachabilityResult.h"
#include "reach_trajopt/StepReport.h"
#include "reach_trajopt/TransitionTrajectory.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/ros/conversions.h"
#include "reach_trajopt/ros/node_setup.h"
#include "reach_trajopt/walk/walk_setup.h"

using namespace reach_trajopt;
namespace rb = reach_trajopt::ros_bridge;

namespace {

struct Received {
  std::vector<reach_trajopt::StepReport> reports;
  std::vector<std::string> check_publishers;  ///< publisher of each reachability_result
  std::vector<double> check_stamps;           ///< its stamp (the sim time of the check) [s]
  std::vector<std::string> trajectory_publishers;
  std::string walk_line;
};
Received g_received;
std::mutex g_mutex;
int g_kill_after_steps = 0;         ///< 0: kill nothing
bool g_killed = false;              ///< killed, or hung with ~hang_planner
bool g_hang_planner = false;        ///< stop transition_ocp_node instead of killing it
pid_t g_planner_pid = 0;            ///< read before the walk starts
int g_hang_worker_after_steps = 0;  ///< 0: hang no worker
pid_t g_worker0_pid = 0;            ///< read before the walk starts
bool g_hung = false;
/// Candidates checked by each worker (its latched footholds_checked), and by worker 1 once
/// worker 0 was hung.
std::vector<uint64_t> g_worker_checked;
uint64_t g_worker1_checked_at_hang = 0;
/// The latest latched count of a node's answers.
struct Count {
  uint64_t value = 0;
};

// The publishers of `topic` as the master lists them (getSystemState).
std::vector<std::string> publishersOf(const std::string& topic) {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  std::vector<std::string> out;
  if (!ros::master::execute("getSystemState", args, result, payload, true)) return out;
  XmlRpc::XmlRpcValue& publishers = payload[0];
  for (int i = 0; i < publishers.size(); ++i) {
    if (static_cast<std::string>(publishers[i][0]) != topic) continue;
    for (int j = 0; j < publishers[i][1].size(); ++j)
      out.push_back(static_cast<std::string>(publishers[i][1][j]));
  }
  return out;
}
Count g_footsteps_checked;   ///< reachability_node's check_footstep answers
Count g_footsteps_proposed;  ///< tvr_planner_node's propose_footstep answers

const char* kHungWorker = "/reachability_worker_0/reachability_node";

// The pid of a running node, from its XML-RPC getPid (through rosnode info); 0: unknown.
pid_t nodePid(const std::string& node) {
  const std::string command = "rosnode info " + node + " 2>/dev/null | sed -n 's/^Pid: //p'";
  FILE* f = popen(command.c_str(), "r");
  if (!f) return 0;
  char buffer[64] = {0};
  const bool read = fgets(buffer, sizeof(buffer), f) != nullptr;
  pclose(f);
  return read ? static_cast<pid_t>(std::atol(buffer)) : 0;
}

using reach_trajopt::test::bytes;

// The record without what depends on the machine (wall times) or the transport (seq).
reach_trajopt::StepReport comparable(reach_trajopt::StepReport m) {
  m.header.seq = 0;
  m.check_time = 0.0;
  m.ocp_time = 0.0;
  return m;
}

std::string withoutWallTime(const std::string& line) {
  return std::regex_replace(line, std::regex(" wall_s=[^ ]*"), "");
}

template <typename T>
T param(const ros::NodeHandle& nh, const std::string& name, const T& fallback) {
  T value;
  return nh.getParam(name, value) ? value : fallback;
}

TEST(WalkNodes, NodeWiredWalkEqualsInProcessWalk) {
  ros::NodeHandle nh, pnh("~");
  const double timeout = param(pnh, "timeout", 300.0);
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
  auto received = [] {
    std::lock_guard<std::mutex> lock(g_mutex);
    return g_received;
  };
  while (ros::ok() && received().walk_line.empty() && ros::WallTime::now() < deadline)
    ros::WallDuration(0.05).sleep();
  ros::WallDuration(1.0).sleep();  // the last step report and check messages
  const Received got = received();
  const bool got_killed = [] {
    std::lock_guard<std::mutex> lock(g_mutex);
    return g_killed;
  }();
  ASSERT_FALSE(got.walk_line.empty()) << "no walk_result within ~timeout";

  // The same scenario in process, from the same parameters.
  WalkSetup setup = WalkSetup::fromYamlFile(param<std::string>(pnh, "config", ""));
  const std::string sim_config = param<std::string>(pnh, "sim_config", "");
  if (!sim_config.empty())
    setup.sim = SimConfig::fromYaml(YamlSection::loadFile(sim_config).section("sim"));
  setup.walk.policy = WalkingPolicy::parse(param<std::string>(pnh, "policy", "proposed"));
  setup.walk.steps = param(pnh, "steps", 3);
  setup.walk.seed = static_cast<unsigned>(param(pnh, "seed", 1));
  setup.walk.initial_com_velocity.x() = param(pnh, "push_vx", 0.0);
  setup.walk.initial_com_velocity.y() = param(pnh, "push_vy", 0.0);
  const rb::TempUrdf urdf(rb::robotDescription(nh));
  const std::unique_ptr<WalkingExperiment> experiment = setup.experiment(urdf.path());
  const WalkResult in_process = experiment->run();

  EXPECT_EQ(withoutWallTime(got.walk_line), withoutWallTime(in_process.summaryLine()));
  ASSERT_EQ(got.reports.size(), in_process.records.size());
  ASSERT_GT(in_process.records.size(), 0u);
  for (size_t i = 0; i < in_process.records.size(); ++i) {
    const StepRecord& r = in_process.records[i];
    const reach_trajopt::StepReport expected =
        comparable(rb::toStepReportMsg(r, setup.walk.policy, false, r.executed.z()));
    const reach_trajopt::StepReport report = comparable(got.reports[i]);
    EXPECT_EQ(bytes(report), bytes(expected)) << "step " << r.index << "\nnodes:\n"
                                              << report << "\nin process:\n"
                                              << expected;
  }
  size_t checked = 0;
  for (const StepRecord& r : in_process.records) checked += r.verdict != StepVerdict::kNotChecked;
  EXPECT_EQ(checked, in_process.records.size());
  const int workers = param(pnh, "workers", 0);
  if (workers > 0) {
    std::lock_guard<std::mutex> lock(g_mutex);
    for (int i = 0; i < workers; ++i)
      EXPECT_GT(g_worker_checked[i], 0u) << "worker " << i << " checked no candidate";
    if (g_hang_worker_after_steps > 0) {
      EXPECT_TRUE(g_hung) << "worker 0 was not hung";
      // Candidates went to worker 1 after worker 0 hung. That none was lost or made up is the
      // walk's byte equality above: a count of whole rings after the hang cannot tell, because
      // the SIGSTOP races with the ring in flight (worker 0 may have answered part of it) and
      // with worker 1's count messages (seen in CI: 174 after the hang, 14.5 rings of 12).
      const uint64_t after_hang = g_worker_checked[1] - g_worker1_checked_at_hang;
      EXPECT_GT(after_hang, 0u) << "no candidate went to worker 1 after worker 0 hung";
    }
  }
  if (g_kill_after_steps == 0) {
    // Every check went through transition_ocp_node (none fell back to sim_node's planner).
    ASSERT_EQ(got.check_publishers.size(), checked);
    ASSERT_EQ(got.trajectory_publishers.size(), checked);
    for (size_t i = 0; i < checked; ++i) {
      EXPECT_EQ(got.check_publishers[i], "/transition_ocp_node");
      EXPECT_EQ(got.trajectory_publishers[i], "/transition_ocp_node");
    }
    // The checks were answered by reachability_node, the proposals by tvr_planner_node.
    std::lock_guard<std::mutex> lock(g_mutex);
    // At least one per checked step; more where a ring point stood in for the target
    // (on_fail=nearest_reachable checks candidates).
    EXPECT_GE(g_footsteps_checked.value, checked) << "checks answered by reachability_node";
    EXPECT_EQ(publishersOf("/footsteps_checked"), std::vector<std::string>{"/reachability_node"});
    EXPECT_GE(g_footsteps_proposed.value, in_process.records.size())
        << "proposals answered by tvr_planner_node";
    if (setup.walk.replan_fraction == 0.0)
      EXPECT_EQ(g_footsteps_proposed.value, in_process.records.size());
    EXPECT_EQ(publishersOf("/footsteps_proposed"), std::vector<std::string>{"/tvr_planner_node"});
    return;
  }
  // Killed after kill_after_steps reports: those steps from the node, the last from sim_node,
  // every step's check published (at most one twice: the one in flight when the node died),
  // but for at most one: a plan the node answered as it was being killed, whose
  // reachability_result left with the dying node (ROS does not deliver a dead publisher's
  // queue; seen in CI). That the walk went on with that answer is the byte equality above.
  ASSERT_TRUE(got_killed);
  const std::set<double> stamps(got.check_stamps.begin(), got.check_stamps.end());
  EXPECT_GE(stamps.size() + 1, checked) << "checked steps without their reachability_result";
  ASSERT_GE(got.check_publishers.size() + 1, checked);
  EXPECT_LE(got.check_publishers.size(), checked + 1);
  for (int i = 0; i < g_kill_after_steps; ++i)
    EXPECT_EQ(got.check_publishers[i], "/transition_ocp_node") << "step " << i + 1;
  EXPECT_EQ(got.check_publishers.back(), "/sim_node");
  EXPECT_EQ(got.trajectory_publishers.back(), "/sim_node");
}

void onReport(const reach_trajopt::StepReport::ConstPtr& m) {
  std::lock_guard<std::mutex> lock(g_mutex);
  g_received.reports.push_back(*m);
  if (g_hang_worker_after_steps > 0 && !g_hung &&
      static_cast<int>(g_received.reports.size()) == g_hang_worker_after_steps) {
    // At once (mid-walk: the next step's search is on its way): a hung node, not a dead one.
    g_hung = g_worker0_pid > 0 && ::kill(g_worker0_pid, SIGSTOP) == 0;
    if (!g_hung) ADD_FAILURE() << "could not hang " << kHungWorker;
    if (g_worker_checked.size() > 1) g_worker1_checked_at_hang = g_worker_checked[1];
  }
  if (g_kill_after_steps > 0 && !g_killed &&
      static_cast<int>(g_received.reports.size()) == g_kill_after_steps) {
    g_killed = true;  // mid-walk: the next step's check is already on its way
    if (g_hang_planner) {
      if (g_planner_pid <= 0 || ::kill(g_planner_pid, SIGSTOP) != 0)
        ADD_FAILURE() << "could not stop /transition_ocp_node";
      return;
    }
    std::thread([] {
      if (std::system("rosnode kill /transition_ocp_node > /dev/null 2>&1") != 0)
        ADD_FAILURE() << "rosnode kill /transition_ocp_node failed";
    }).detach();
  }
}
void onCheck(const ros::MessageEvent<const reach_trajopt::ReachabilityResult>& e) {
  std::lock_guard<std::mutex> lock(g_mutex);
  g_received.check_publishers.push_back(e.getPublisherName());
  g_received.check_stamps.push_back(e.getMessage()->header.stamp.toSec());
}
void onTrajectory(const ros::MessageEvent<const reach_trajopt::TransitionTrajectory>& e) {
  std::lock_guard<std::mutex> lock(g_mutex);
  g_received.trajectory_publishers.push_back(e.getPublisherName());
}
void onResult(const std_msgs::String::ConstPtr& m) {
  std::lock_guard<std::mutex> lock(g_mutex);
  g_received.walk_line = m->data;
}
void onCount(Count& count, const ros::MessageEvent<const std_msgs::UInt64>& e) {
  std::lock_guard<std::mutex> lock(g_mutex);
  count.value = e.getMessage()->data;
}
void onCom(const reach_trajopt::CenterOfMassState::ConstPtr&) {}
void onWorkerChecked(size_t worker, const std_msgs::UInt64::ConstPtr& m) {
  std::lock_guard<std::mutex> lock(g_mutex);
  g_worker_checked[worker] = m->data;
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "check_walk_nodes");
  ros::NodeHandle nh;
  ros::NodeHandle("~").getParam("kill_after_steps", g_kill_after_steps);
  ros::NodeHandle("~").getParam("hang_worker_after_steps", g_hang_worker_after_steps);
  ros::NodeHandle("~").getParam("hang_planner", g_hang_planner);
  int workers = 0;
  ros::NodeHandle("~").getParam("workers", workers);
  g_worker_checked.assign(std::max(workers, 0), 0);
  std::vector<ros::Subscriber> worker_subs;
  for (int i = 0; i < workers; ++i)
    worker_subs.push_back(nh.subscribe<std_msgs::UInt64>(
        "reachability_worker_" + std::to_string(i) + "/footholds_checked", 10,
        [i](const std_msgs::UInt64::ConstPtr& m) { onWorkerChecked(i, m); }));
  const ros::Subscriber reports = nh.subscribe("step_report", 100, onReport);
  const ros::Subscriber checks = nh.subscribe("reachability_result", 100, onCheck);
  const ros::Subscriber trajectories = nh.subscribe("transition_trajectory", 100, onTrajectory);
  const ros::Subscriber result = nh.subscribe("walk_result", 1, onResult);
  const ros::Subscriber footsteps_checked = nh.subscribe<std_msgs::UInt64>(
      "footsteps_checked", 10,
      [](const ros::MessageEvent<const std_msgs::UInt64>& e) { onCount(g_footsteps_checked, e); });
  const ros::Subscriber footsteps_proposed = nh.subscribe<std_msgs::UInt64>(
      "footsteps_proposed", 10,
      [](const ros::MessageEvent<const std_msgs::UInt64>& e) { onCount(g_footsteps_proposed, e); });
  if (g_hang_worker_after_steps > 0) {  // before the walk starts: rosnode info takes a while
    ros::service::waitForService("/reachability_worker_0/check_footholds", ros::Duration(60.0));
    g_worker0_pid = nodePid(kHungWorker);
  }
  if (g_hang_planner) {
    ros::service::waitForService("/plan_footstep", ros::Duration(60.0));
    g_planner_pid = nodePid("/transition_ocp_node");
  }
  // Last: sim_node starts once com_state has this subscriber too (extra_com_subscribers).
  const ros::Subscriber com = nh.subscribe("com_state", 10, onCom);
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const int rc = RUN_ALL_TESTS();
  if (g_hung) ::kill(g_worker0_pid, SIGCONT);  // so that the launch can stop it
  if (g_hang_planner && g_killed) ::kill(g_planner_pid, SIGCONT);
  spinner.stop();
  return rc;
}
