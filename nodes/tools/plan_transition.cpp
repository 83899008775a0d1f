/// \file plan_transition.cpp
/// Solves one transition OCP (eq. 22-23) from a JSON request and prints the trajectory as JSON:
///   plan_transition [request.json | -] [--urdf urdf/biped.urdf] [--config config/biped.yaml]
///                   [--stride k]
/// Request (SI units, radians; q vectors of size n_q in the model's order):
///   {"stance": "left"|"right", "stance_pose": {"position": [x,y,z], "yaw": 0},
///    "swing_target": {"position": [x,y,z], "yaw": 0}, "horizon": 0.3,
///    "q0": [...], "qd0": [...],                    x_0 (qd0 defaults to zeros)
///    "qf": [...], "qdf": [...],                    x_f; omitted: the Sec. III-B IK solution
///    "relaxation": "auto"|"strict"|"relaxed",
///    "slices": [{"time": t, "A": [[ax, ay], ...], "b": [...]}, ...],   optional hulls
///    "seed": {"time": [...], "q": [[...], ...]}}                      optional warm start
/// Output: {"status": "converged"|"relaxed"|"failed", "reason", "nlopt_status", "relaxed",
///   "eps", "landing_position", "dt", "time", "q", "qd", "qdd", "u", "lambda" (one row per
///   sample; lambda = [left f, tau; right f, tau] world), "violation": {family: value},
///   "cost", "iterations", "solves", "variables", "constraints", "solve_time", "qf", "qdf" (the
///   x_f solved for)}.
/// --stride k keeps every k-th sample (and the last) in the output arrays.
/// Read by readTransitionRequest (transition_request_json.h): unknown keys, wrong sizes, a horizon
/// over its bound and an IK-infeasible target without "qf" are errors naming the key.
/// Bad input (unreadable JSON, wrong sizes, NaN, x_0 off its contact, ...): {"status": "error",
/// "reason": ...} on stdout and exit status 2. A failed solve is exit status 1.

#include <Eigen/Geometry>
#include <fstream>
#include <iostream>
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
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/ocp/ocp_config.h"
#include "reach_trajopt/ocp/transition_ocp.h"
#include "reach_trajopt/ocp/transition_request_json.h"
#include "reach_trajopt/planner/kinematic_feasibility.h"
#include "reach_trajopt/step/footstep_planner_setup.h"
#include "violations_json.h"

using reach_trajopt::ReachError;
using json = nlohmann::json;

namespace {

/// Sample indices 0, k, 2k, ... and always the last one.
std::vector<Eigen::Index> strided(Eigen::Index n, int stride) {
  std::vector<Eigen::Index> idx;
  for (Eigen::Index c = 0; c < n; c += stride) idx.push_back(c);
  if (n > 0 && idx.back() != n - 1) idx.push_back(n - 1);
  return idx;
}

json matrixRows(const Eigen::MatrixXd& m, int stride) {
  json rows = json::array();
  for (Eigen::Index c : strided(m.cols(), stride)) {
    rows.push_back(std::vector<double>(m.col(c).data(), m.col(c).data() + m.rows()));
  }
  return rows;
}

/// The tool's options (--help prints them).
const reach_trajopt::CliTool kTool(
    "plan_transition", "[request.json | -]",
    "Solves one transition OCP (eq. 22-23) from a JSON request (standard input: -) and prints\n"
    "the trajectory as JSON.",
    {reach_trajopt::urdfOption(),
     reach_trajopt::configOption("config file (robot, contact, kinematic_feasibility, ocp)"),
     {"--stride", "k", "keep every k-th sample (and the last) in the output arrays", "1"}});

/// The solve's result as plan_transition's output JSON (header comment), samples by `stride`.
json resultJson(const reach_trajopt::TransitionResult& res,
                const reach_trajopt::TransitionRequest& r, int stride) {
  json out;
  out["status"] = reach_trajopt::ocpStatusName(res.status);
  out["reason"] = res.reason;
  out["nlopt_status"] = res.nlopt_status;
  out["relaxed"] = res.relaxed;
  out["eps"] = {res.eps.x(), res.eps.y()};
  out["landing_position"] = {res.landing_position.x(), res.landing_position.y(),
                             res.landing_position.z()};
  out["dt"] = res.dt;
  json times = json::array();
  for (Eigen::Index k : strided(res.time.size(), stride)) times.push_back(res.time[k]);
  out["time"] = times;
  out["q"] = matrixRows(res.q, stride);
  out["qd"] = matrixRows(res.qd, stride);
  out["qdd"] = matrixRows(res.qdd, stride);
  out["u"] = matrixRows(res.u, stride);
  out["lambda"] = matrixRows(res.lambda, stride);
  out["violation"] = violationsJson(res.violation);
  out["cost"] = res.cost;
  out["iterations"] = res.iterations;
  out["solves"] = res.solves;
  out["variables"] = res.variables;
  out["constraints"] = res.constraints;
  out["solve_time"] = res.solve_time;
  // x_f the OCP was given (the request's, or the Sec. III-B IK solution): a reference solver
  // and check_transition can start from the same one.
  out["qf"] = std::vector<double>(r.qf.data(), r.qf.data() + r.qf.size());
  out["qdf"] = std::vector<double>(r.qdf.data(), r.qdf.data() + r.qdf.size());
  return out;
}

/// Without "qf" in the request: x_f from the kinematic feasibility check (Sec. III-B).
void solveTerminalState(const reach_trajopt::FootstepPlannerSetup& setup,
                        std::shared_ptr<const reach_trajopt::RobotModel> model,
                        reach_trajopt::TransitionRequestJson& in) {
  using namespace reach_trajopt;
  const KinematicFeasibility kf(model, setup.planner.kinematics, setup.contact);
  const auto ik = kf.check(in.request.stance, in.request.stance_contact, in.request.target);
  // Planning to a foothold the IK rejected (e.g. inside the stance sole) would "succeed"
  // with a relaxed landing elsewhere: refuse it, as the services do.
  if (!ik.feasible)
    throw RequestError("swing_target: kinematically infeasible foothold: " + ik.reason);
  in.request.qf = ik.q_f;
  in.request.qdf = ik.qd_f;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace reach_trajopt;
  return runJsonTool(kTool, argc, argv, [](const CliArgs& args) {
    if (args.positional().size() > 1)
      throw RequestError("expected one request file (got " +
                         std::to_string(args.positional().size()) + ")");
    const std::string input = args.positional().empty() ? "-" : args.positional()[0];
    const int stride =
        static_cast<int>(parseIntOption("--stride", args.value("--stride"), 1, 1000000));
    const json doc = JsonReader::parseFile(input);
    // The OCP's landing height is the IK's pelvis height (FootstepPlannerConfig::fromYaml).
    const FootstepPlannerSetup setup = FootstepPlannerSetup::fromYamlFile(args.value("--config"));
    const auto model = setup.loadModel(args.value("--urdf"));
    TransitionRequestJson in = readTransitionRequest(JsonReader(doc, input), model->nq());
    if (!in.has_qf) solveTerminalState(setup, model, in);
    const TransitionOcp ocp(model, setup.planner.ocp, setup.contact);
    const TransitionResult res = ocp.solve(in.request);
    std::cout << resultJson(res, in.request, stride).dump() << "\n";
    return res.status == OcpStatus::kFailed ? 1 : 0;
  });
}
