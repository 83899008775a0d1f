/// walk_experiment: the walking experiment of the paper's Sec. IV, headless, no ROS master.
///
///   walk_experiment [--config config/biped.yaml] [--urdf urdf/biped.urdf]
///                   [--policy P] [--steps N] [--seed S] [--push vx,vy]
///                   [--forward-speed v] [--settle S] [--records FILE.csv]
///                   [--plan-requests FILE.jsonl] [--ocp-requests FILE.jsonl]
///
/// --config: the robot and its parameters (config/talos.yaml: TALOS legs); --urdf overrides
/// its robot.urdf. --settle S: stand S seconds before the first step (--steps 0: stand only).
///
/// --policy: a walking policy (walk/walking_policy.h), a preset baseline | unbounded | kinematic |
/// proposed, optionally with parts: "kinematic,swing=interpolation"; --mode is the same option.
/// Prints one line per step and ends with `WALK mode=<policy> steps=<n> fell=<yes|no> ...`
/// and the policy's definition.
/// Option values are parsed strictly (cli_args.h): "--steps 5x" is an error naming --steps.
/// --ocp-requests: each checked, kinematically feasible footstep's strict transition OCP request
/// (x_0 as used, x_f and qd_f of the check, no reachable-set hulls, no seed), one JSON per line
/// in plan_transition's format (ocp/transition_request_json.h), e.g. for bench/crocoddyl.
/// Exit status: 0 ran (fallen or not), 2 bad input.

#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

#include "reach_trajopt/common/cli_args.h"
#include "reach_trajopt/common/cli_options.h"
#include "reach_trajopt/ocp/transition_request_json.h"
#include "reach_trajopt/step/footstep_plan_request_json.h"
#include "reach_trajopt/walk/walk_setup.h"

using namespace reach_trajopt;

namespace {

/// Upper bound of --steps (docs/limits.md): each proposed step costs seconds of checks.
constexpr long long kMaxWalkSteps = 1000;
/// Upper bound of --settle [s] (a standing test of an hour is a typo, not a test).
constexpr double kMaxSettleSeconds = 600.0;
/// The largest --push component [m/s] (push_envelope's --magnitudes go to 10): beyond, the
/// simulation leaves the ground at once (1e300 was reported as a NaN base position).
constexpr double kMaxPushMps = 10.0;

/// The tool's options (--help prints them).
const CliTool kTool(
    "walk_experiment", "",
    "The walking experiment of the paper's Sec. IV, headless: one line per step, then the WALK\n"
    "summary line and the policy's definition.",
    {configOption("the robot and its parameters"),
     urdfOption(),
     {"--policy", "P",
      "walking policy: baseline | unbounded | kinematic | proposed[,part=value...] (default: "
      "the config's walk.policy)",
      "", 1, "--mode"},
     {"--steps", "N", "steps to walk, 0.." + std::to_string(kMaxWalkSteps) + " (0: stand only)",
      ""},
     {"--seed", "S", "seed of the walk's random perturbations", ""},
     {"--push", "vx,vy", "initial CoM velocity [m/s]", ""},
     {"--midswing-push", "vx,vy",
      "a push while walking: base velocity change [m/s] at half swing of the 4th step", ""},
     {"--forward-speed", "v", "commanded forward speed [m/s]", ""},
     {"--settle", "S", "stand S seconds before the first step", ""},
     {"--plan-latency", "L",
      "when a step's plan takes effect: pause (the simulation waits), measured (after its wall "
      "time), or a fixed latency in seconds (default: the config's walk.plan_latency)",
      ""},
     {"--records", "FILE.csv", "write every step's record", ""},
     {"--plan-requests", "FILE.jsonl", "write each checked footstep's request (verdict_grid)", ""},
     {"--ocp-requests", "FILE.jsonl",
      "write each checked feasible footstep's strict OCP request (plan_transition)", ""}});

/// The walk config of the file with the command line's changes, validated.

/// A push option "vx,vy" [m/s]. \throws RequestError naming the option.
Eigen::Vector2d pushOption(const CliArgs& args, const std::string& option) {
  const std::string push = args.value(option);
  const auto comma = push.find(',');
  if (comma == std::string::npos)
    throw RequestError(option + ": expected vx,vy [m/s], got '" + push + "'");
  return Eigen::Vector2d(
      parseDoubleOption(option, push.substr(0, comma), -kMaxPushMps, kMaxPushMps),
      parseDoubleOption(option, push.substr(comma + 1), -kMaxPushMps, kMaxPushMps));
}

/// \throws ReachError naming a bad option value.
void applyOptions(const CliArgs& args, WalkConfig& walk) {
  if (args.given("--policy")) walk.policy = WalkingPolicy::parse(args.value("--policy"));
  if (args.given("--steps"))
    walk.steps =
        static_cast<int>(parseIntOption("--steps", args.value("--steps"), 0, kMaxWalkSteps));
  if (args.given("--seed"))
    walk.seed =
        static_cast<unsigned>(parseIntOption("--seed", args.value("--seed"), 0, 4294967295LL));
  if (args.given("--forward-speed"))
    walk.forward_speed = parseDoubleOption("--forward-speed", args.value("--forward-speed"));
  // Standing before the first lift-off [s]; with --steps 0 the run is a standing test.
  if (args.given("--settle")) {
    walk.settle_duration =
        parseDoubleOption("--settle", args.value("--settle"), 0.0, kMaxSettleSeconds);
    walk.max_sim_time = std::max(walk.max_sim_time, walk.settle_duration + 1.0);
  }
  if (args.given("--plan-latency"))
    walk.setPlanLatency(args.value("--plan-latency"), "--plan-latency");
  if (args.given("--push")) walk.initial_com_velocity = pushOption(args, "--push");
  if (args.given("--midswing-push")) walk.midswing_push = pushOption(args, "--midswing-push");
  walk.validate();
}

/// An output file of `option`, opened before the walk; not open when the option is not given.
std::ofstream openOutput(const CliArgs& args, const std::string& option) {
  std::ofstream out;
  const std::string path = args.value(option);
  if (path.empty()) return out;
  out.open(path);
  if (!out) throw ReachError("cannot write " + option + " file '" + path + "'");
  return out;
}

/// The strict transition OCP request of a checked, kinematically feasible footstep (x_0 as
/// used, x_f and qd_f of the check, no hulls, no seed).
TransitionRequest ocpRequest(const FootstepTransition& step) {
  TransitionRequest ocp(step.transition);
  ocp.qf = step.check.kinematics.q_f;
  ocp.qdf = step.check.qdf;
  ocp.relaxation = RelaxationMode::kStrict;
  return ocp;
}

/// One line per executed step on stdout.
void printStep(const StepRecord& s) {
  std::printf(
      "step %2d %-5s t=%.3f planned_tvr=(%.3f, %.3f) planned=(%.3f, %.3f)%s from=%s "
      "executed=(%.3f, %.3f) err=%.4f m verdict=%s certificate=%s witness_violation=%.3g "
      "junction_gap=%.3g/%.3g x_f_gap=%.3g/%.3g d_H=%.4g check_s=%.3f passes=%d "
      "ocp_s=%.3f ocp=%s latency_s=%.3f%s replans=%d%s%s\n",
      s.index, sideName(s.swing), s.touchdown_time, s.planned_tvr.x(), s.planned_tvr.y(),
      s.planned.x(), s.planned.y(), s.offset_clipped ? " clipped" : "", s.footholdSourceName(),
      s.executed.x(), s.executed.y(), s.touchdown_error, s.verdictName(),
      s.certificate == Certificate::kNone ? "none" : s.certificateName(), s.witness_violation,
      s.junction_position_gap, s.junction_velocity_gap, s.terminal_position_gap,
      s.terminal_velocity_gap, s.hausdorff_distance, s.check_time_s, s.check_passes, s.ocp_time_s,
      s.ocpStatusName(), s.plan_latency_s, s.plan_late ? " LATE" : "", s.replans,
      s.reason.empty() ? "" : " reason: ", s.reason.c_str());
  std::fflush(stdout);
}

/// --records: every step's record as CSV.
void writeRecords(const std::string& path, const std::vector<StepRecord>& records) {
  std::ofstream out(path);
  if (!out) throw ReachError("cannot write records file '" + path + "'");
  out << "index,swing,plan_time,touchdown_time,planned_tvr_x,planned_tvr_y,planned_x,"
         "planned_y,executed_x,executed_y,touchdown_error,offset_clipped,verdict,certificate,"
         "witness_violation,junction_position_gap,junction_velocity_gap,"
         "terminal_position_gap,terminal_velocity_gap,plan_latency_s,plan_late,swing_duration_s,"
         "foothold_source,replans\n";
  for (const StepRecord& s : records)
    out << s.index << "," << sideName(s.swing) << "," << s.plan_time << "," << s.touchdown_time
        << "," << s.planned_tvr.x() << "," << s.planned_tvr.y() << "," << s.planned.x() << ","
        << s.planned.y() << "," << s.executed.x() << "," << s.executed.y() << ","
        << s.touchdown_error << "," << s.offset_clipped << "," << s.verdictName() << ","
        << s.certificateName() << "," << s.witness_violation << "," << s.junction_position_gap
        << "," << s.junction_velocity_gap << "," << s.terminal_position_gap << ","
        << s.terminal_velocity_gap << "," << s.plan_latency_s << "," << s.plan_late << ","
        << s.swing_duration << "," << s.footholdSourceName() << "," << s.replans << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  return kTool.run(argc, argv, [](const CliArgs& args) {
    if (!args.positional().empty())
      throw RequestError("unknown argument '" + args.positional()[0] + "'");
    WalkSetup setup = WalkSetup::fromYamlFile(args.value("--config"));
    applyOptions(args, setup.walk);
    const std::unique_ptr<WalkingExperiment> experiment = setup.experiment(args.value("--urdf"));
    // --plan-requests: each checked footstep's request, one JSON per line (verdict_grid input).
    std::ofstream requests_out = openOutput(args, "--plan-requests");
    std::ofstream ocp_requests_out = openOutput(args, "--ocp-requests");
    const auto on_check = [&](const StepRecord&, const FootstepTransition& step) {
      if (ocp_requests_out.is_open() && step.check.kinematically_feasible)
        ocp_requests_out << transitionRequestToJson(ocpRequest(step)).dump() << "\n";
      if (!requests_out.is_open()) return;
      nlohmann::json j = footstepPlanRequestJson(step.request);
      j["reach_horizon"] = step.transition.horizon;  // the walk's check horizon
      requests_out << j.dump() << "\n";
    };
    const WalkResult r = experiment->run({}, printStep, on_check);
    if (!args.value("--records").empty()) writeRecords(args.value("--records"), r.records);
    std::printf("%s\n", r.summaryLine().c_str());
    return 0;
  });
}
