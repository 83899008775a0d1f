/// \file reach_check.cpp
/// reach_check: runs one reachability check (eq. 13-21) on a URDF, a YAML config and a JSON
/// request, and prints the result as JSON. For tests, and to reproduce a check outside ROS.
///
///   reach_check <robot.urdf> <config.yaml> <request.json> [--threads N] [--samples]
///
/// config.yaml: the sections `contact:` (required), `reach:` and `kinematic_feasibility:`
/// (optional: defaults) as every tool reads them (step/footstep_planner_setup.h).
/// Request (JSON; angles in radians, SI units):
///   "mode":    "SS-L" | "SS-R" (single support, the other sole swings) | "none" (fixed base,
///              no contacts)
///   "x0":      {"q": [...], "qd": [...]}                        the state x_0, or
///   "swing":   {"position": [x,y,z], "velocity": [vx,vy,vz], "yaw": 0, "q_init": [...]}
///              builds x_0 with the swing sole there (swing_state.h)
///   "stance":  {"position": [x,y,z], "yaw": 0}    foothold of the stance sole
///   "target":  {"position": [x,y,z], "yaw": 0}    next foothold of the swing sole
///   "xf":      {"q": [...], "qd": [...]}  optional; without it x_f comes from the kinematic
///              feasibility check of the target (Sec. III-B) with qd_f = 0
///   "config":  {...}  optional overrides of `reach:` keys (e.g. "initial_samples": 1000)
/// Output: {"reachable", "reason", "kinematically_feasible", "budgets", "gave_up" (the adaptive
///   budget of reach.quick_pass: 1 or 2 budgets drawn; gave up after the quick one), "counts",
///   "timings" (both budgets'),
///   "window": [per slice of [t_2, t_1]: t, hausdorff, closest, resolution, overlap, ...],
///   "witness": {time, output, q, qd, junction, gaps, violation}, "slices": {"forward",
///   "backward": [t, count, boundary outputs]} (+ every sample's output with --samples)}.
/// Unknown keys, wrong sizes and non-finite numbers are errors naming the key path
/// (reach_request_json.h); --threads is 0..hardware threads; the limits of docs/limits.md apply.
/// Exit status: 0 when the check ran (reachable or not), 2 on bad input (message on stderr).

#include <cmath>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "reach_trajopt/common/cli_args.h"
#include "reach_trajopt/common/cli_options.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/model/robot_config.h"
#include "reach_trajopt/reach/footstep_reachability.h"
#include "reach_trajopt/reach/reach_request_json.h"
#include "reach_trajopt/step/footstep_planner_setup.h"
#include "reach_trajopt/testing/swing_state.h"

using namespace reach_trajopt;
using nlohmann::json;

namespace {

/// Upper bound on the samples --samples prints (output size, docs/limits.md): about 0.5 GB.
constexpr double kMaxPrintedSamples = 1.0e6;

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json vec(const Eigen::Ref<const Eigen::VectorXd>& v) {
  json a = json::array();
  for (int i = 0; i < v.size(); ++i) a.push_back(number(v[i]));
  return a;
}

json columns(const Eigen::Ref<const Eigen::MatrixXd>& M) {
  json a = json::array();
  for (int j = 0; j < M.cols(); ++j) a.push_back(vec(M.col(j)));
  return a;
}

/// The tool's options (--help prints them).
const CliTool kTool(
    "reach_check",
    "<robot.urdf> <config.yaml> <request.json> | --config <config.yaml> <request.json>",
    "Runs one reachability check (eq. 13-21) and prints the result as JSON. With --config the\n"
    "URDF is the config's robot.urdf.",
    {{"--config", "FILE", "config file, the URDF then being its robot.urdf", ""},
     {"--threads", "N", "threads of the check, 0..hardware threads (default: reach.threads)", ""},
     {"--samples", "", "print every sample's output and velocity per slice", ""}});

/// The three input files: URDF ("" with --config: the config's robot.urdf), config, request.
struct InputFiles {
  std::string urdf, config, request;
};

/// The input files of the command line; nothing when they do not match the usage.
std::optional<InputFiles> inputFiles(const CliArgs& args) {
  const std::vector<std::string>& p = args.positional();
  if (args.given("--config")) {
    if (p.size() != 1) return std::nullopt;
    return InputFiles{"", args.value("--config"), p[0]};
  }
  if (p.size() != 3) return std::nullopt;
  return InputFiles{p[0], p[1], p[2]};
}

/// --samples would print about config.estimatedQps() samples: refused over the output limit.
void requirePrintableSamples(const ReachConfig& config) {
  if (config.estimatedQps() <= kMaxPrintedSamples) return;
  std::ostringstream os;
  os << "--samples: the check would print about " << config.estimatedQps()
     << " samples, over the limit of " << kMaxPrintedSamples
     << " (docs/limits.md): lower initial_samples or max_boundary";
  throw RequestError(os.str());
}

/// The check's inputs: the setup of the config file, the model, the request and its config
/// (the file's reach: section, the request's overrides, --threads).
struct CheckInputs {
  FootstepPlannerSetup setup;
  std::shared_ptr<const RobotModel> model;
  ReachCheckRequest request;
  ReachConfig config;
};

CheckInputs readInputs(const InputFiles& files, const CliArgs& args) {
  CheckInputs in;
  in.setup = FootstepPlannerSetup::fromYamlFile(files.config);
  in.model = in.setup.loadModel(files.urdf);
  const json doc = JsonReader::parseFile(files.request);
  in.request =
      readReachCheckRequest(JsonReader(doc, files.request), in.model->nq(), in.setup.planner.reach);
  in.config = in.request.config;
  if (args.given("--threads"))
    in.config.threads = parseThreadsOption("--threads", args.value("--threads"));
  in.config.validate();
  in.config.requireResourcesWithinLimits(in.model->nq());  // before the IK and any sample
  if (args.given("--samples")) requirePrintableSamples(in.config);
  return in;
}

/// The request's problem: its mode and footholds, x_0 given or built from the swing sole.
ReachProblem problemOf(const CheckInputs& in) {
  const ReachCheckRequest& req = in.request;
  const bool contacts = req.mode != "none";
  ReachProblem p;
  p.mode = contacts ? ContactMode::fromName(req.mode) : ContactMode{false, false};
  if (contacts) {
    p.footholds[p.mode.stance() == Side::kLeft ? 0 : 1] = req.stance.pose();
    p.target = req.target.pose();
  }
  if (req.has_x0) {
    p.q0 = req.q0;
    p.qd0 = req.qd0;
  } else {
    const RobotState x0 =
        swingState(in.model, in.setup.planner.kinematics, in.setup.contact, p.mode.stance(),
                   req.stance, req.swing_position, req.swing_yaw, req.swing_velocity, req.q_init);
    p.q0 = x0.q;
    p.qd0 = x0.qd;
  }
  if (req.has_xf) {
    p.qf = req.qf;
    p.qdf = req.qdf;
  }
  return p;
}

json countsJson(const ReachResult& r) {
  return {{"forward_samples", r.counts.forward_samples},
          {"backward_samples", r.counts.backward_samples},
          {"forward_qps", r.counts.forward_qps},
          {"backward_qps", r.counts.backward_qps},
          {"forward_rejected", r.counts.forward_rejected},
          {"backward_rejected", r.counts.backward_rejected},
          {"backward_prefiltered", r.counts.backward_prefiltered},
          {"threads", r.counts.threads}};
}

json timingsJson(const ReachResult& r) {
  return {{"forward_s", r.timings.forward},   {"backward_s", r.timings.backward},
          {"boundary_s", r.timings.boundary}, {"hausdorff_s", r.timings.hausdorff},
          {"witness_s", r.timings.witness},   {"total_s", r.timings.total}};
}

json windowJson(const ReachResult& r) {
  json window = json::array();
  for (const SliceComparison& c : r.window)
    window.push_back({{"t", c.time},
                      {"hausdorff", number(c.distance.hausdorff)},
                      {"forward_to_backward", number(c.distance.a_to_b)},
                      {"backward_to_forward", number(c.distance.b_to_a)},
                      {"resolution", number(c.distance.resolution())},
                      {"closest", number(c.distance.closest)},
                      {"overlap_tolerance", number(c.overlap_tolerance)},
                      {"backward_inside_forward", c.backward_inside_forward},
                      {"forward_inside_backward", c.forward_inside_backward},
                      {"overlap", c.overlap},
                      {"within_delta", c.within_delta}});
  return window;
}

json violationJson(const PathViolation& v) {
  return {{"dynamics", v.dynamics},
          {"cone", v.cone},
          {"torque", v.torque},
          {"position_limit", v.position_limit},
          {"velocity_limit", v.velocity_limit},
          {"contact", v.contact},
          {"contact_velocity", v.contact_velocity},
          {"integration", v.integration},
          {"ground", v.ground},
          {"leg_clearance", v.leg_clearance}};
}

json witnessJson(const WitnessPath& w) {
  return {{"time", w.time},
          {"output", columns(w.output)},
          {"q", columns(w.q)},
          {"qd", columns(w.qd)},
          {"u", columns(w.u)},
          {"lambda", columns(w.lambda)},
          {"junction", w.junction},
          {"output_gap", w.output_gap},
          {"position_gap", w.position_gap},
          {"velocity_gap", w.velocity_gap},
          {"certified", w.certified},
          {"bridge_start", w.bridge_start},
          {"candidates_tried", w.candidates_tried},
          {"terminal_position_gap", number(w.terminal_position_gap)},
          {"terminal_velocity_gap", number(w.terminal_velocity_gap)},
          {"terminal_output_gap", number(w.terminal_output_gap)},
          {"max_violation", w.violation.max()},
          {"violation", violationJson(w.violation)}};
}

/// One direction's slices: time, count, boundary outputs (+ every sample with `samples`).
json slicesJson(const std::vector<SampleSlice>& slices, bool samples) {
  json list = json::array();
  for (const SampleSlice& s : slices) {
    json e = {{"t", s.time}, {"count", s.size()}};
    Eigen::MatrixXd b(s.output.rows(), s.boundary.size());
    for (std::size_t k = 0; k < s.boundary.size(); ++k) b.col(k) = s.output.col(s.boundary[k]);
    e["boundary"] = columns(b);
    if (samples) {
      e["outputs"] = columns(s.output);
      e["qd"] = columns(s.qd);
    }
    list.push_back(e);
  }
  return list;
}

/// The check's result into `out` (the keys of the header comment).
void addResult(const ReachResult& r, bool samples, json& out) {
  out["reachable"] = r.reachable;
  out["reason"] = r.reason;
  out["budgets"] = r.budgets;
  out["gave_up"] = r.gave_up;
  out["dt"] = r.dt;
  out["joint_names"] = r.joint_names;
  out["counts"] = countsJson(r);
  out["timings"] = timingsJson(r);
  out["window"] = windowJson(r);
  out["best"] = r.best;
  if (r.witness.valid) out["witness"] = witnessJson(r.witness);
  out["slices"]["forward"] = slicesJson(r.forward, samples);
  out["slices"]["backward"] = slicesJson(r.backward, samples);
}

/// Runs the check: with the request's x_f, or with x_f from the kinematic feasibility check of
/// the target (then "kinematically_feasible" is in the output; an infeasible target ends it).
json runCheck(const CheckInputs& in, const ReachProblem& p, bool samples) {
  json out;
  const auto analyzer =
      std::make_shared<ReachabilityAnalyzer>(in.model, in.setup.contact, in.config);
  if (in.request.has_xf) {
    addResult(analyzer->check(p), samples, out);
    return out;
  }
  ContactTransition fr;
  fr.stance = p.mode.stance();
  fr.stance_contact = in.request.stance;
  fr.target = in.request.target;
  fr.q0 = p.q0;
  fr.qd0 = p.qd0;
  const FootstepReachability check(
      analyzer, std::make_shared<KinematicFeasibility>(in.model, in.setup.planner.kinematics,
                                                       in.setup.contact));
  const FootstepCheckResult f = check.check(fr);
  out["kinematically_feasible"] = f.kinematically_feasible;
  if (!f.kinematically_feasible) {
    out["reachable"] = false;
    out["reason"] = f.reason;
    return out;
  }
  addResult(f.reach, samples, out);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  return kTool.run(argc, argv, [](const CliArgs& args) {
    const std::optional<InputFiles> files = inputFiles(args);
    if (!files) {
      std::cerr << kTool.usageLine() << "\n";
      return 2;
    }
    const CheckInputs in = readInputs(*files, args);
    const ReachProblem problem = problemOf(in);
    std::cout << runCheck(in, problem, args.given("--samples")).dump() << "\n";
    return 0;
  });
}
