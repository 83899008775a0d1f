// Walking policies (walk/walking_policy.h): the presets' parts, the "<preset>[,part=value]"
// grammar, a changed preset named "custom" unless it equals another preset, errors that name
// the bad token, the combination the loop cannot run, which failed steps take the last resort
// (the TVR step clipped to the bounds); the push grid of the envelope sweep.

#include <gtest/gtest.h>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/step/footstep_transition_planner.h"
#include "reach_trajopt/walk/push_envelope.h"
#include "reach_trajopt/walk/walking_policy.h"

using namespace reach_trajopt;
using Check = WalkingPolicy::FootholdCheck;
using OnFail = WalkingPolicy::OnFailedCheck;
using Swing = WalkingPolicy::SwingSource;

TEST(WalkingPolicy, PresetsAreTheIssuesFour) {
  EXPECT_EQ(WalkingPolicy::presetNames(),
            (std::vector<std::string>{"baseline", "unbounded", "kinematic", "proposed"}));
  const WalkingPolicy b = WalkingPolicy::preset("baseline");
  EXPECT_TRUE(b.heuristic_bounds);
  EXPECT_EQ(b.check, Check::kNone);
  EXPECT_EQ(b.swing, Swing::kInterpolation);
  EXPECT_EQ(b.definition(), "bounds=on check=none on_fail=- swing=interpolation");
  const WalkingPolicy u = WalkingPolicy::preset("unbounded");
  EXPECT_FALSE(u.heuristic_bounds);
  EXPECT_EQ(u.check, Check::kNone);
  const WalkingPolicy k = WalkingPolicy::preset("kinematic");
  const WalkingPolicy p = WalkingPolicy::preset("proposed");
  EXPECT_EQ(k.definition(), "bounds=off check=kinematic on_fail=nearest_reachable swing=ocp");
  EXPECT_EQ(p.definition(), "bounds=off check=reachability on_fail=nearest_reachable swing=ocp");
  // kinematic and proposed differ in the check only.
  WalkingPolicy k_with_reach = k;
  k_with_reach.check = Check::kReachability;
  EXPECT_TRUE(k_with_reach == p);
  EXPECT_TRUE(p.solvesOcp());
  EXPECT_FALSE(b.solvesOcp());
}

TEST(WalkingPolicy, PartsChangeAPresetAndNameIt) {
  const WalkingPolicy a = WalkingPolicy::parse("kinematic,swing=interpolation");
  EXPECT_EQ(a.name, "custom");
  EXPECT_EQ(a.check, Check::kKinematic);
  EXPECT_EQ(a.swing, Swing::kInterpolation);
  EXPECT_FALSE(a.solvesOcp());
  const WalkingPolicy r = WalkingPolicy::parse("kinematic,on_fail=relaxed_ocp,swing=interpolation");
  EXPECT_TRUE(r.solvesOcp());  // the relaxed OCP picks the foothold of a failed check
  // A combination equal to a preset is that preset.
  EXPECT_EQ(WalkingPolicy::parse("unbounded,bounds=on").name, "baseline");
  EXPECT_EQ(WalkingPolicy::parse("kinematic,check=reachability").name, "proposed");
  EXPECT_EQ(WalkingPolicy::parse("proposed").name, "proposed");
  // Definitions round-trip through the grammar.
  for (const std::string& n : WalkingPolicy::presetNames()) {
    const WalkingPolicy p = WalkingPolicy::preset(n);
    std::string spec = "baseline";
    std::stringstream ss(p.definition());
    for (std::string part; ss >> part;)
      if (part.find("=-") == std::string::npos) spec += "," + part;
    EXPECT_EQ(WalkingPolicy::parse(spec).name, n) << spec;
  }
}

TEST(WalkingPolicy, ErrorsNameTheToken) {
  const auto message = [](const std::string& spec) {
    try {
      WalkingPolicy::parse(spec);
    } catch (const ReachError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("fast").find("unknown preset 'fast'"), std::string::npos);
  EXPECT_NE(message("").find("empty"), std::string::npos);
  EXPECT_NE(message("baseline,speed=3").find("unknown part 'speed'"), std::string::npos);
  EXPECT_NE(message("baseline,check=full").find("check=full: expected check=none|kinematic"),
            std::string::npos);
  EXPECT_NE(message("baseline,bounds").find("'bounds': expected part=value"), std::string::npos);
  EXPECT_NE(message("baseline,swing=ocp").find("swing=ocp needs check=kinematic"),
            std::string::npos);
  // From the YAML: the key and the file.
  try {
    WalkConfig::fromYaml(YamlSection::loadString("walk: {policy: fast}", "w.yaml").section("walk"));
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("w.yaml: walk.policy"), std::string::npos) << e.what();
  }
  try {
    WalkConfig::fromYaml(
        YamlSection::loadString("walk: {mode: proposed}", "w.yaml").section("walk"));
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("walk.policy"), std::string::npos) << e.what();
  }
}

namespace {

// A planner's answer for a step whose target failed its check.
FootstepTransition answer(FootholdSource source, bool kinematically_feasible, bool reachable,
                          bool usable, std::optional<StepVerdict> target_verdict) {
  FootstepTransition step;
  step.foothold_source = source;
  step.kinematically_feasible = kinematically_feasible;
  step.reachable = reachable;
  step.trajectory.status = usable ? OcpStatus::kConverged : OcpStatus::kFailed;
  step.target_verdict = target_verdict;
  return step;
}

}  // namespace

TEST(WalkingPolicy, TheLastResortTakesEveryUncertifiedStandInForAnInfeasibleTarget) {
  // The rule of docs/walking.md ("the last resort"), case by case: which answers of the
  // planner to a failed check are "nothing found", so that the loop takes the TVR step clipped
  // to the bounds instead.
  const WalkingPolicy proposed = WalkingPolicy::preset("proposed");
  const WalkingPolicy kinematic = WalkingPolicy::preset("kinematic");
  const WalkingPolicy clip = WalkingPolicy::parse("proposed,on_fail=clip_to_bounds");
  const auto infeasible = StepVerdict::kKinematicallyInfeasible;
  const auto unreachable = StepVerdict::kUnreachable;
  struct Case {
    const char* what;
    FootstepTransition step;
    bool proposed_clips, kinematic_clips;
  };
  const std::vector<Case> cases = {
      {"the target itself, no usable plan",
       answer(FootholdSource::kTarget, false, false, false, std::nullopt), true, true},
      {"the target's relaxed landing (Sec. III-E)",
       answer(FootholdSource::kRelaxed, true, false, true, std::nullopt), false, false},
      {"a certified ring point",
       answer(FootholdSource::kNearestReachable, true, true, true, infeasible), false, false},
      {"an uncertified ring point for an infeasible target",
       answer(FootholdSource::kNearestFeasible, true, false, true, infeasible), true, false},
      {"the relaxed landing moved from the ring point of an infeasible target",
       answer(FootholdSource::kRelaxed, true, false, true, infeasible), true, false},
      {"the same from the kinematic ring search (fields of the infeasible target)",
       answer(FootholdSource::kRelaxed, false, false, true, std::nullopt), true, false},
      {"the relaxed landing of an unreachable target's stand-in",
       answer(FootholdSource::kRelaxed, true, false, true, unreachable), false, false},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(proposed.clipsFailedStep(c.step), c.proposed_clips) << c.what;
    EXPECT_EQ(kinematic.clipsFailedStep(c.step), c.kinematic_clips) << c.what;
    EXPECT_TRUE(clip.clipsFailedStep(c.step)) << c.what;
  }
}

TEST(PushGrid, DirectionsMagnitudesAndErrors) {
  PushGrid g;
  g.directions = 8;
  g.magnitudes = {0.2, 0.4};
  EXPECT_NO_THROW(g.validate());
  EXPECT_EQ(g.push(0, 1), Eigen::Vector2d(0.4, 0.0));   // forward
  EXPECT_EQ(g.push(2, 0), Eigen::Vector2d(0.0, 0.2));   // to the left
  EXPECT_EQ(g.push(6, 1), Eigen::Vector2d(0.0, -0.4));  // to the right
  EXPECT_NEAR(g.push(1, 1).norm(), 0.4, 1e-12);
  PushGrid bad = g;
  bad.magnitudes = {0.4, 0.2};
  EXPECT_THROW(bad.validate(), RequestError);
  bad = g;
  bad.directions = 0;
  EXPECT_THROW(bad.validate(), RequestError);
  bad = g;
  bad.seeds.clear();
  EXPECT_THROW(bad.validate(), RequestError);
}

TEST(PushEnvelope, RadiusIsTheLargestPushBelowTheFirstFall) {
  // The envelope of a hand-made sweep: direction 0 survives 0.2 and 0.4 but one seed falls at
  // 0.6; direction 1 falls at 0.2 although it survives 0.4 (the radius stops at the first fall).
  PushEnvelope e;
  e.grid.directions = 4;
  e.grid.magnitudes = {0.2, 0.4, 0.6};
  e.grid.seeds = {1, 2};
  for (int d = 0; d < 4; ++d)
    for (int m = 0; m < 3; ++m)
      for (int s = 0; s < 2; ++s) {
        PushWalk w;
        w.direction = d;
        w.magnitude = m;
        w.seed = s;
        w.fell = (d == 0 && m == 2 && s == 1) || (d == 1 && m == 0) || d == 3;
        e.walks.push_back(w);
      }
  EXPECT_DOUBLE_EQ(e.radius(0), 0.4);
  EXPECT_DOUBLE_EQ(e.radius(1), 0.0);
  EXPECT_DOUBLE_EQ(e.radius(2), 0.6);
  EXPECT_DOUBLE_EQ(e.radius(3), 0.0);
  EXPECT_DOUBLE_EQ(e.maxForward(), 0.4);
  EXPECT_DOUBLE_EQ(e.maxLateral(), 0.0);  // +y (d = 1) and -y (d = 3)
  EXPECT_EQ(e.pushes(), 24);
  EXPECT_EQ(e.survived(), 24 - 1 - 2 - 6);
  const std::string line = e.benchLine();
  EXPECT_EQ(line.rfind("BENCH walk.envelope preset=baseline protocol=standing forward_mps=0 "
                       "pushes=24 survived=15 ",
                       0),
            0u)
      << line;
  // With the capture limits of each direction: the radius as a fraction of the one-step limit.
  for (int d = 0; d < 4; ++d) e.capture.push_back(CaptureLimits{0.0, 0.5, 0.8, 1.6});
  const std::string with_capture = e.benchLine();
  EXPECT_NE(with_capture.find(" capture1_mps=0.8/0.8/0.8/0.8 "), std::string::npos) << with_capture;
  EXPECT_NE(with_capture.find(" fraction_of_capture1=0.5/0/0.75/0 "), std::string::npos)
      << with_capture;
  EXPECT_EQ(with_capture.find("plan_latency="), std::string::npos) << "pause: the reference";
  // Paying for its plans' time, the line says so (beside the reference's, which does not).
  WalkConfig paying;
  paying.setPlanLatency("measured", "--plan-latency");
  e.plan_latency = paying.planLatencyName();
  EXPECT_NE(e.benchLine().find(" plan_latency=measured "), std::string::npos) << e.benchLine();
  paying.setPlanLatency("0.05", "--plan-latency");
  EXPECT_EQ(paying.planLatencyName(), "0.05");
  paying.setPlanLatency(paying.planLatencyName(), "--plan-latency");  // its own form reads back
  EXPECT_DOUBLE_EQ(paying.fixed_plan_latency, 0.05);
  const std::string svg = envelopeSvg({e});
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("15/24 survived"), std::string::npos);
}
