/// \file check_transition.cpp
/// Re-checks a sampled transition trajectory (e.g. plan_transition's output, or a reference
/// solver's trajectory converted to our coordinates) with the full-model checker of the OCP
/// (checkTransition, ocp/transition_check.h: eq. 1, the stance contact, the cones, torque and
/// joint limits, the reachable-set hulls, x(t_0) = x_0 and x(t_f) = x_f):
///   check_transition request.json trajectory.json [--config config/biped.yaml] [--urdf path]
///                    [--threshold v]
/// request.json: plan_transition's request (transition_request_json.h) with "qf" (and "qdf",
///   default zeros): the x_f the trajectory must end at.
/// trajectory.json: {"time": [N s], "q": [N rows of n_q], "qd": [N x n_q], "qdd": [N x n_q],
///   "u": [N x n_u], "lambda": [N x 12: left f, tau; right f, tau, world, at the sole centres],
///   "relaxed": false, "eps": [eps_x, eps_y]} in our coordinates (q = [x, y, z, yaw, pitch, roll,
///   joints in model_info's order], qd and qdd their time derivatives; SI units, radians);
///   plan_transition's other output keys are accepted and ignored.
/// --threshold: violation above which a sample time / slice is listed (default: the config's
///   ocp.tolerance).
/// Prints {"violation": {family: value, ..., "max"}, "violating_times": [s],
///   "violating_slices": [...], "samples": N}. Bad input: {"status": "error", "reason": ...}
///   naming the file and key, exit status 2.

#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "json_error.h"
#include "reach_trajopt/common/cli_args.h"
#include "reach_trajopt/common/cli_options.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/model/robot_config.h"
#include "reach_trajopt/ocp/transition_check.h"
#include "reach_trajopt/ocp/transition_request_json.h"
#include "reach_trajopt/step/footstep_planner_setup.h"
#include "violations_json.h"

using json = nlohmann::json;

namespace {

/// Upper bound of the trajectory's samples (docs/limits.md: 1 ms over the longest horizon).
constexpr std::size_t kMaxTrajectorySamples = 1000000;

/// Reads an N x `cols` matrix stored as N rows into a cols x N matrix (one column per sample).
Eigen::MatrixXd samplesOf(const reach_trajopt::JsonReader& r, const std::string& key,
                          Eigen::Index n, Eigen::Index cols) {
  return r.at(key).matrix(n, cols).transpose();
}

reach_trajopt::TransitionResult readTrajectory(const reach_trajopt::JsonReader& r, int nq, int nu) {
  using reach_trajopt::TransitionResult;
  r.requireObject("a trajectory object");
  r.requireOnlyKeys({"time", "q", "qd", "qdd", "u", "lambda", "relaxed", "eps",
                     // plan_transition's other output keys, and a note of who made it
                     "status", "reason", "nlopt_status", "landing_position", "dt", "violation",
                     "cost", "iterations", "solves", "variables", "constraints", "solve_time", "qf",
                     "qdf", "solver"});
  TransitionResult t;
  const reach_trajopt::JsonReader time = r.at("time");
  const Eigen::Index n = static_cast<Eigen::Index>(time.requireArray(2, kMaxTrajectorySamples));
  t.time = time.vector(n);
  for (Eigen::Index k = 1; k < n; ++k) {
    if (!(t.time[k] > t.time[k - 1])) time.at(k).fail("sample times must increase");
  }
  t.q = samplesOf(r, "q", n, nq);
  t.qd = samplesOf(r, "qd", n, nq);
  t.qdd = samplesOf(r, "qdd", n, nq);
  t.u = samplesOf(r, "u", n, nu);
  t.lambda = samplesOf(r, "lambda", n, 12);
  if (r.has("relaxed")) t.relaxed = r.at("relaxed").boolean();
  if (r.has("eps")) t.eps = r.vector("eps", 2);
  t.dt = n > 1 ? t.time[1] - t.time[0] : 0.0;
  return t;
}

/// The tool's options (--help prints them).
const reach_trajopt::CliTool kTool(
    "check_transition", "request.json trajectory.json",
    "Re-checks a sampled transition trajectory with the OCP's full-model checker and prints the\n"
    "violations as JSON.",
    {reach_trajopt::configOption("config file (robot, contact, ocp)"),
     reach_trajopt::urdfOption(),
     {"--threshold", "v",
      "violation above which a sample time / slice is listed (default: the config's "
      "ocp.tolerance)",
      ""}});

/// The trajectory must span the request's [0, horizon]: a time axis scaled (x10) or shifted
/// (by 1 s) would be checked against the wrong x_0 and x_f times and pass with 1e-10.
void requireTimeAxisOfRequest(const reach_trajopt::TransitionResult& traj, double horizon,
                              const std::string& traj_file, const std::string& request_file) {
  const double tol = 1e-6 + 1e-6 * std::abs(horizon);
  const double t0 = traj.time[0], t1 = traj.time[traj.time.size() - 1];
  if (std::abs(t0) <= tol && std::abs(t1 - horizon) <= tol) return;
  std::ostringstream os;
  os << traj_file << ": time: the trajectory spans [" << t0 << ", " << t1
     << "] s, not the request's [0, " << horizon << "] s (horizon of " << request_file << ")";
  throw reach_trajopt::RequestError(os.str());
}

/// The two input files of the command line. \throws RequestError for another count.
void requireTwoFiles(const std::vector<std::string>& files) {
  if (files.size() != 2)
    throw reach_trajopt::RequestError(
        "check_transition: expected request.json and trajectory.json (got " +
        std::to_string(files.size()) + " files)");
}

/// --threshold: the option's value, or the config's ocp.tolerance when not given.
double thresholdOption(const reach_trajopt::CliArgs& args,
                       const reach_trajopt::FootstepPlannerSetup& setup) {
  if (!args.given("--threshold")) return setup.planner.ocp.tolerance;
  return reach_trajopt::parseDoubleOption("--threshold", args.value("--threshold"), 0.0, 1e9);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace reach_trajopt;
  return runJsonTool(kTool, argc, argv, [](const CliArgs& args) {
    const std::vector<std::string>& files = args.positional();
    requireTwoFiles(files);
    const FootstepPlannerSetup setup = FootstepPlannerSetup::fromYamlFile(args.value("--config"));
    const double threshold = thresholdOption(args, setup);
    const auto model = setup.loadModel(args.value("--urdf"));

    const json request_doc = JsonReader::parseFile(files[0]);
    const JsonReader request_reader(request_doc, files[0]);
    TransitionRequestJson in = readTransitionRequest(request_reader, model->nq());
    if (!in.has_qf) request_reader.at("qf");  // throws "missing key qf" naming the file
    const json traj_doc = JsonReader::parseFile(files[1]);
    const TransitionResult traj =
        readTrajectory(JsonReader(traj_doc, files[1]), model->nq(), model->nu());

    requireTimeAxisOfRequest(traj, in.request.horizon, files[1], files[0]);
    const TransitionCheck check =
        checkTransition(*model, setup.contact, in.request, traj, threshold);
    json out;
    out["violation"] = violationsJson(check.violation);
    out["violating_times"] = check.violating_times;
    out["violating_slices"] = check.violating_slices;
    out["samples"] = traj.time.size();
    std::cout << out.dump() << "\n";
    return 0;
  });
}
