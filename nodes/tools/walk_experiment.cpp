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
#include "reach_trajopt/ocp/transition_request_json.h"
#include "reach_trajopt/step/footstep_plan_request_json.h"
#include "reach_trajopt/walk/walk_setup.h"

using namespace reach_trajopt;

/// Upper bound of --steps (docs/limits.md): each proposed step costs seconds of checks.
constexpr long long kMaxWalkSteps = 1000;
/// Upper bound of --settle [s] (a standing test of an hour is a typo, not a test).
constexpr double kMaxSettleSeconds = 600.0;
/// The largest --push component [m/s] (push_envelope's --magnitudes go to 10).
constexpr double kMaxPushMps = 10.0;

int main(int argc, char** argv) {
  std::string config_path = "config/biped.yaml", urdf, records_path, requests_path,
              ocp_requests_path;
  std::string mode, push, steps, seed, speed, settle;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error("missing value after " + a);
      return argv[++i];
    };
    try {
      if (a == "--config")
        config_path = next();
      else if (a == "--urdf")
        urdf = next();
      else if (a == "--policy" || a == "--mode")
        mode = next();
      else if (a == "--steps")
        steps = next();
      else if (a == "--seed")
        seed = next();
      else if (a == "--push")
        push = next();
      else if (a == "--forward-speed")
        speed = next();
      else if (a == "--settle")
        settle = next();
      else if (a == "--records")
        records_path = next();
      else if (a == "--plan-requests")
        requests_path = next();
      else if (a == "--ocp-requests")
        ocp_requests_path = next();
      else
        throw std::runtime_error("unknown argument '" + a + "'");
    } catch (const std::exception& e) {
      std::cerr << "walk_experiment: " << e.what() << "\n";
      return 2;
    }
  }
  try {
    WalkSetup setup = WalkSetup::fromYamlFile(config_path);
    WalkConfig& walk = setup.walk;
    if (!mode.empty()) walk.policy = WalkingPolicy::parse(mode);
    if (!steps.empty())
      walk.steps = static_cast<int>(parseIntOption("--steps", steps, 0, kMaxWalkSteps));
    if (!seed.empty())
      walk.seed = static_cast<unsigned>(parseIntOption("--seed", seed, 0, 4294967295LL));
    if (!speed.empty()) walk.forward_speed = parseDoubleOption("--forward-speed", speed);
    // Standing before the first lift-off [s]; with --steps 0 the run is a standing test.
    if (!settle.empty()) {
      walk.settle_duration = parseDoubleOption("--settle", settle, 0.0, kMaxSettleSeconds);
      walk.max_sim_time = std::max(walk.max_sim_time, walk.settle_duration + 1.0);
    }
    if (!push.empty()) {
      const auto comma = push.find(',');
      if (comma == std::string::npos)
        throw RequestError("--push: expected vx,vy [m/s], got '" + push + "'");
      // A push is a CoM velocity: beyond 10 m/s (push_envelope's largest magnitude) the
      // simulation leaves the ground at once (1e300 was reported as a NaN base position).
      walk.initial_com_velocity = Eigen::Vector2d(
          parseDoubleOption("--push", push.substr(0, comma), -kMaxPushMps, kMaxPushMps),
          parseDoubleOption("--push", push.substr(comma + 1), -kMaxPushMps, kMaxPushMps));
    }
    walk.validate();
    const std::unique_ptr<WalkingExperiment> experiment = setup.experiment(urdf);
    std::ofstream requests_out;
    if (!requests_path.empty()) {
      requests_out.open(requests_path);
      if (!requests_out)
        throw ReachError("cannot write --plan-requests file '" + requests_path + "'");
    }
    // --plan-requests: each checked footstep's request, one JSON per line (verdict_grid input).
    std::ofstream ocp_requests_out;
    if (!ocp_requests_path.empty()) {
      ocp_requests_out.open(ocp_requests_path);
      if (!ocp_requests_out)
        throw ReachError("cannot write --ocp-requests file '" + ocp_requests_path + "'");
    }
    const auto on_check = [&](const StepRecord&, const FootstepTransition& step) {
      if (ocp_requests_out.is_open() && step.check.kinematically_feasible) {
        TransitionRequest ocp;
        ocp.stance = step.stance;
        ocp.stance_pose = step.stance_contact.pose();
        ocp.swing_target = step.target.pose();
        ocp.horizon = step.horizon;
        ocp.q0 = step.q0;
        ocp.qd0 = step.qd0;
        ocp.qf = step.check.kinematics.q_f;
        ocp.qdf = step.check.qdf;
        ocp.relaxation = RelaxationMode::kStrict;
        ocp_requests_out << transitionRequestToJson(ocp).dump() << "\n";
      }
      if (!requests_out.is_open()) return;
      nlohmann::json j = footstepPlanRequestJson(step.request);
      j["reach_horizon"] = step.horizon;  // the walk's check horizon
      requests_out << j.dump() << "\n";
    };
    const WalkResult r = experiment->run(
        {},
        [](const StepRecord& s) {
          std::printf(
              "step %2d %-5s t=%.3f planned_tvr=(%.3f, %.3f) planned=(%.3f, %.3f)%s "
              "executed=(%.3f, %.3f) err=%.4f m verdict=%s certificate=%s witness_violation=%.3g "
              "junction_gap=%.3g/%.3g x_f_gap=%.3g/%.3g d_H=%.4g check_s=%.3f passes=%d "
              "ocp_s=%.3f ocp=%s%s%s\n",
              s.index, sideName(s.swing), s.touchdown_time, s.planned_tvr.x(), s.planned_tvr.y(),
              s.planned.x(), s.planned.y(), s.offset_clipped ? " clipped" : "", s.executed.x(),
              s.executed.y(), s.touchdown_error, s.verdict.c_str(),
              s.certificate.empty() ? "none" : s.certificate.c_str(), s.witness_violation,
              s.junction_position_gap, s.junction_velocity_gap, s.terminal_position_gap,
              s.terminal_velocity_gap, s.hausdorff_distance, s.check_time_s, s.check_passes,
              s.ocp_time_s, s.ocp_status.c_str(),
              s.reason.empty() ? "" : " reason: ", s.reason.c_str());
          std::fflush(stdout);
        },
        on_check);
    if (!records_path.empty()) {
      std::ofstream out(records_path);
      if (!out) throw ReachError("cannot write records file '" + records_path + "'");
      out << "index,swing,plan_time,touchdown_time,planned_tvr_x,planned_tvr_y,planned_x,"
             "planned_y,executed_x,executed_y,touchdown_error,offset_clipped,verdict,certificate,"
             "witness_violation,junction_position_gap,junction_velocity_gap,"
             "terminal_position_gap,terminal_velocity_gap\n";
      for (const StepRecord& s : r.records)
        out << s.index << "," << sideName(s.swing) << "," << s.plan_time << "," << s.touchdown_time
            << "," << s.planned_tvr.x() << "," << s.planned_tvr.y() << "," << s.planned.x() << ","
            << s.planned.y() << "," << s.executed.x() << "," << s.executed.y() << ","
            << s.touchdown_error << "," << s.offset_clipped << "," << s.verdict << ","
            << s.certificate << "," << s.witness_violation << "," << s.junction_position_gap << ","
            << s.junction_velocity_gap << "," << s.terminal_position_gap << ","
            << s.terminal_velocity_gap << "\n";
    }
    std::printf("%s\n", r.summaryLine().c_str());
  } catch (const std::exception& e) {
    std::cerr << "walk_experiment: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
