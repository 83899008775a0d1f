// The latency-paying walking loop (WalkConfig::plan_latency): a plan takes effect only after
// its latency has passed in sim time, and one that would take effect after the nominal
// touchdown is dropped. Oracles: the walk up to the first check is the same whatever the
// latency (the plan is computed from the same state), a dropped plan leaves the swing on the
// TVR foothold, and pause mode is the reference loop (no latency, nothing late).

#include <gtest/gtest.h>

#include <string>

#include "reach_trajopt/walk/walk_setup.h"

using namespace reach_trajopt;

namespace {

WalkResult walk(WalkConfig::PlanLatency mode, double latency_s, int steps,
                const Eigen::Vector2d& midswing_push = Eigen::Vector2d::Zero()) {
  WalkSetup setup =
      WalkSetup::fromYamlFile(std::string(REACH_TRAJOPT_SOURCE_DIR) + "/config/biped.yaml");
  setup.walk.policy = WalkingPolicy::parse("kinematic");
  setup.walk.steps = steps;
  setup.walk.plan_latency = mode;
  setup.walk.fixed_plan_latency = latency_s;
  setup.walk.midswing_push = midswing_push;
  setup.walk.seed = 1;
  return setup.experiment(std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf")->run();
}

bool checked(const StepRecord& s) {
  return s.verdict != StepVerdict::kNotChecked && s.verdict != StepVerdict::kCheckError;
}

}  // namespace

TEST(PlanLatency, PauseIsTheReferenceLoop) {
  const WalkResult r = walk(WalkConfig::PlanLatency::kPause, 0.0, 4);
  ASSERT_FALSE(r.records.empty());
  for (const StepRecord& s : r.records) {
    EXPECT_EQ(s.plan_latency_s, 0.0) << s.index;
    EXPECT_FALSE(s.plan_late) << s.index;
  }
  EXPECT_NE(r.summaryLine().find(" late_plans=0 "), std::string::npos) << r.summaryLine();
}

TEST(PlanLatency, APlanAfterTheNominalTouchdownIsDroppedAndTheSwingKeepsItsFoothold) {
  // 0.25 s after the check starts is past the nominal touchdown (check_horizon 0.2 s before it).
  const WalkResult r = walk(WalkConfig::PlanLatency::kFixed, 0.25, 4);
  int late = 0;
  for (const StepRecord& s : r.records) {
    if (!checked(s)) continue;
    EXPECT_TRUE(s.plan_late) << s.index;
    EXPECT_EQ(s.planned, s.planned_tvr) << s.index;  // the plan never took effect
    late += s.plan_late;
  }
  ASSERT_GT(late, 0) << r.summaryLine();
  EXPECT_NE(r.summaryLine().find(" late_plans=" + std::to_string(late) + " "), std::string::npos)
      << r.summaryLine();
}

TEST(PlanLatency, APlanInTimeTakesEffectAfterItsLatency) {
  const WalkResult paused = walk(WalkConfig::PlanLatency::kPause, 0.0, 1);
  const WalkResult delayed = walk(WalkConfig::PlanLatency::kFixed, 0.05, 1);
  ASSERT_FALSE(paused.records.empty());
  ASSERT_FALSE(delayed.records.empty());
  const StepRecord& a = paused.records.front();
  const StepRecord& b = delayed.records.front();
  ASSERT_TRUE(checked(a) && checked(b));
  // The same state at the check: the same plan, taken 50 ms later.
  EXPECT_EQ(b.verdict, a.verdict);
  EXPECT_EQ(b.planned, a.planned);
  EXPECT_DOUBLE_EQ(b.plan_latency_s, 0.05);
  EXPECT_FALSE(b.plan_late);
}

// A plan that pays its latency arrives late in the swing (0.1 to 0.16 s of 0.22 s here). Until
// then the swing goes to the policy's last resort (the TVR step clipped to the heuristic
// bounds), not to a TVR step that can be out of the leg's reach, and the plan then gives its
// foothold, not its trajectory, which starts from a state the robot has left. The oracle is
// Bullet: after half-swing pushes of 0.6 m/s forward and 0.4 m/s backward the walk lands its 8
// steps (no failed controller QP at 0.1 s, two at 0.16 s). Aiming at the TVR step until the
// plan arrives, 2 of these 4 walks fall ("no touchdown"); tracking the trajectory from where it
// would be by now, 3 of 4 (failed controller QPs, the pelvis sinking).
TEST(PlanLatency, ALatePlanGivesItsFootholdToASwingThatStayedWithinReach) {
  for (const double latency_s : {0.1, 0.16}) {
    for (const Eigen::Vector2d push : {Eigen::Vector2d(0.6, 0.0), Eigen::Vector2d(-0.4, 0.0)}) {
      const WalkResult r = walk(WalkConfig::PlanLatency::kFixed, latency_s, 8, push);
      EXPECT_FALSE(r.fell) << latency_s << " s, push " << push.transpose() << ": "
                           << r.summaryLine();
      EXPECT_EQ(r.steps, 8) << r.summaryLine();
    }
  }
}

// The option's string form (walk_experiment --plan-latency, sim_node ~plan_latency).
TEST(PlanLatency, SetFromItsStringFormOrRefusedNamingTheKey) {
  WalkConfig walk;
  walk.setPlanLatency("measured", "--plan-latency");
  EXPECT_EQ(walk.plan_latency, WalkConfig::PlanLatency::kMeasured);
  walk.setPlanLatency("0.05", "--plan-latency");
  EXPECT_EQ(walk.plan_latency, WalkConfig::PlanLatency::kFixed);
  EXPECT_DOUBLE_EQ(walk.fixed_plan_latency, 0.05);
  walk.setPlanLatency("pause", "--plan-latency");
  EXPECT_EQ(walk.plan_latency, WalkConfig::PlanLatency::kPause);
  for (const std::string bad : {"", "fast", "-0.1", "11", "nan", "0.1s"}) {
    try {
      walk.setPlanLatency(bad, "~plan_latency");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("~plan_latency"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(walk.plan_latency, WalkConfig::PlanLatency::kPause)
      << "a refused value changes nothing";
}
