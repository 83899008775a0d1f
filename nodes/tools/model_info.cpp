/// model_info: inspect any robot as reach_trajopt sees it (no ROS master needed).
///
///   model_info <urdf> [--fixed-base] [--json] [--state FILE] [--frames a,b,...]
///              [--rnea-derivatives]
///
/// Without --state: a summary (mass, CoM at the neutral configuration, dofs, joint order and
/// limits, frames); as text, or with --json as one JSON object for scripts:
///   {"robot", "source", "floating_base", "nq", "nu", "mass" [kg], "com" [m],
///    "joint_names" (q order), "joints": [{"name", "type" (virtual|revolute|continuous|prismatic),
///    "q_min", "q_max" [m|rad], "qd_max" [m/s|rad/s], "effort_max" [N|Nm]}] (null = unlimited),
///    "frames": [{"name", "parent" (parent link, "" for the root), "position" [m]}]}
/// (positions at the neutral configuration, floating base at the origin). With --state FILE ({"q":
/// [...], "qd": [...]} or {"states": [{...}, ...]}, our coordinates: floating base [x y z yaw pitch
/// roll] then the joints): JSON with M, b, the CoM and its Jacobian, and for each frame of --frames
/// its pose, Jacobian and Jdot*qd (6 x n_q at the frame origin, world orientation, rows [linear;
/// angular]). With --rnea-derivatives also "rnea_derivatives": {"qdd" (the state's "qdd", zeros
/// when it has none), "tau" (M qdd + b), "dtau_dq", "dtau_dqd" (n_q x n_q, column k = d tau /
/// d q_k, model/rnea_derivatives.h)}. Exit status: 0 ok, 2 bad input (the message on stderr names
/// the problem).

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "reach_trajopt/common/cli_options.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/common/state_json.h"
#include "reach_trajopt/model/rnea_derivatives.h"
#include "reach_trajopt/model/robot_config.h"
#include "reach_trajopt/model/robot_model.h"

using reach_trajopt::ReachError;
using reach_trajopt::RobotModel;
using Json = nlohmann::json;

namespace {

/// The tool's options (--help prints them).
const reach_trajopt::CliTool kTool(
    "model_info", "<urdf>",
    "Inspect a robot as reach_trajopt sees it: a summary, or with --state the dynamics and\n"
    "frame kinematics at given states (JSON). With --config the URDF may be omitted (the\n"
    "robot section's URDF and locked joints).",
    {{"--fixed-base", "", "load the robot with a fixed base", ""},
     {"--json", "", "print the summary as one JSON object", ""},
     {"--state", "FILE", "states {\"q\", \"qd\"} or {\"states\": [...]} to evaluate", ""},
     {"--frames", "a,b,...", "frames whose pose and Jacobians --state prints", ""},
     {"--rnea-derivatives", "", "--state also prints d tau / d q and d tau / d qd at its qdd", ""},
     {"--config", "FILE", "config file whose robot section gives the URDF and locked joints", ""}});

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, sep))
    if (!item.empty()) out.push_back(item);
  return out;
}

Json matrixToJson(const Eigen::MatrixXd& A) {
  Json rows = Json::array();
  for (int r = 0; r < A.rows(); ++r) {
    Json row = Json::array();
    for (int c = 0; c < A.cols(); ++c) row.push_back(A(r, c));
    rows.push_back(row);
  }
  return rows;
}

Json vectorToJson(const Eigen::VectorXd& v) {
  return Json(std::vector<double>(v.data(), v.data() + v.size()));
}

/// JSON has no infinity: an unlimited bound is null.
Json boundToJson(double x) { return std::isfinite(x) ? Json(x) : Json(nullptr); }

const char* jointType(const reach_trajopt::JointInfo& j) {
  if (j.is_virtual) return "virtual";
  if (j.is_prismatic) return "prismatic";
  return j.is_continuous ? "continuous" : "revolute";
}

void printSummaryJson(const RobotModel& model) {
  reach_trajopt::Workspace ws(model);
  model.update(ws, model.neutralConfiguration(), Eigen::VectorXd::Zero(model.nq()));
  Json out;
  out["robot"] = model.name();
  out["source"] = model.source();
  out["floating_base"] = model.floatingBase();
  out["nq"] = model.nq();
  out["nu"] = model.nu();
  out["mass"] = model.totalMass();
  out["com"] = vectorToJson(model.centerOfMass(ws));
  Json names = Json::array(), joints = Json::array();
  for (const auto& j : model.joints()) {
    names.push_back(j.name);
    joints.push_back({{"name", j.name},
                      {"type", jointType(j)},
                      {"q_min", boundToJson(j.q_min)},
                      {"q_max", boundToJson(j.q_max)},
                      {"qd_max", boundToJson(j.qd_max)},
                      {"effort_max", boundToJson(j.effort_max)}});
  }
  out["joint_names"] = names;
  out["joints"] = joints;
  Json frames = Json::array();
  for (const auto& name : model.frameNames()) {
    const Eigen::Vector3d p = model.framePose(ws, model.frameId(name)).translation();
    frames.push_back(
        {{"name", name}, {"parent", model.parentLink(name)}, {"position", vectorToJson(p)}});
  }
  out["frames"] = frames;
  std::cout << out.dump() << "\n";
}

void printSummary(const RobotModel& model) {
  reach_trajopt::Workspace ws(model);
  const Eigen::VectorXd q = model.neutralConfiguration();
  model.update(ws, q, Eigen::VectorXd::Zero(model.nq()));
  const Eigen::Vector3d com = model.centerOfMass(ws);
  std::printf("robot        %s (%s)\n", model.name().c_str(), model.source().c_str());
  std::printf("base         %s\n", model.floatingBase() ? "floating (6 virtual joints)" : "fixed");
  std::printf("dofs         n_q = %d, n_u = %d\n", model.nq(), model.nu());
  std::printf("total mass   %.3f kg\n", model.totalMass());
  std::printf("CoM          [%.4f, %.4f, %.4f] m at the neutral configuration (base at origin)\n",
              com.x(), com.y(), com.z());
  std::printf("joints (index, name, type, q range [m|rad], |qd| max, |effort| max):\n");
  for (int i = 0; i < model.nq(); ++i) {
    const auto& j = model.joints()[i];
    std::printf("  %2d %-18s %-10s [%8.3f, %8.3f] %8.3g %8.3g\n", i, j.name.c_str(), jointType(j),
                j.q_min, j.q_max, j.qd_max, j.effort_max);
  }
  std::printf("frames:\n");
  for (const auto& name : model.frameNames()) {
    const Eigen::Vector3d p = model.framePose(ws, model.frameId(name)).translation();
    std::printf("  %-22s at [%.4f, %.4f, %.4f] m\n", name.c_str(), p.x(), p.y(), p.z());
  }
}

/// The largest |q| or |qd| a state may hold [m, rad, m/s, rad/s]: beyond, the sines of an angle
/// are rounding noise and products overflow (q = 1e300 printed null for b).
constexpr double kMaxStateMagnitude = 1e9;

/// A state beyond kMaxStateMagnitude, or so large that M, b, the CoM or a frame are not finite,
/// is an error naming its largest coordinate, not a JSON null.
void requireFiniteOutputs(const reach_trajopt::JointSpaceState& state, bool finite) {
  if (finite && state.q.cwiseAbs().maxCoeff() <= kMaxStateMagnitude &&
      state.qd.cwiseAbs().maxCoeff() <= kMaxStateMagnitude)
    return;
  Eigen::Index iq = 0, iqd = 0;
  const double q = state.q.cwiseAbs().maxCoeff(&iq), qd = state.qd.cwiseAbs().maxCoeff(&iqd);
  std::ostringstream os;
  os << "the dynamics are not finite at this state: its largest coordinate is "
     << (q >= qd ? "q[" + std::to_string(iq) + "] = " : "qd[" + std::to_string(iqd) + "] = ")
     << (q >= qd ? state.q[iq] : state.qd[iqd]) << " (beyond " << kMaxStateMagnitude
     << ": out of any meaningful range)";
  throw reach_trajopt::RequestError(os.str());
}

Json evaluate(const RobotModel& model, reach_trajopt::Workspace& ws,
              const reach_trajopt::JointSpaceState& state, const std::vector<std::string>& frames) {
  const Eigen::VectorXd& q = state.q;
  const Eigen::VectorXd& qd = state.qd;
  model.update(ws, q, qd);
  const int n = model.nq();
  Eigen::MatrixXd M(n, n);
  Eigen::VectorXd b(n);
  model.massMatrix(ws, M);
  model.bias(ws, b);
  Eigen::Matrix3Xd Jc(3, n);
  model.centerOfMassJacobian(ws, Jc);
  Json out;
  out["M"] = matrixToJson(M);
  out["b"] = vectorToJson(b);
  out["com"] = vectorToJson(model.centerOfMass(ws));
  out["com_jacobian"] = matrixToJson(Jc);
  requireFiniteOutputs(state, M.allFinite() && b.allFinite() && Jc.allFinite() &&
                                  model.centerOfMass(ws).allFinite());
  Json jf = Json::object();
  reach_trajopt::Matrix6Xd J(6, n);
  for (const auto& name : frames) {
    const reach_trajopt::FrameId id = model.frameId(name);
    const Eigen::Isometry3d T = model.framePose(ws, id);
    model.frameJacobian(ws, id, J);
    requireFiniteOutputs(
        state, T.matrix().allFinite() && J.allFinite() && model.frameJdotQd(ws, id).allFinite());
    Json f;
    f["position"] = vectorToJson(T.translation());
    f["rotation"] = matrixToJson(T.linear());
    f["jacobian"] = matrixToJson(J);
    f["jdot_qd"] = vectorToJson(model.frameJdotQd(ws, id));
    jf[name] = f;
  }
  out["frames"] = jf;
  return out;
}

/// --rnea-derivatives: inverse dynamics and its derivatives at the state (qdd: zeros if absent).
Json rneaDerivativesJson(const reach_trajopt::RneaDerivatives& rd,
                         reach_trajopt::RneaDerivatives::Data& data,
                         const reach_trajopt::JointSpaceState& state) {
  const int n = rd.model().nq();
  const Eigen::VectorXd qdd = state.qdd.size() ? state.qdd : Eigen::VectorXd::Zero(n);
  Eigen::VectorXd tau(n);
  Eigen::MatrixXd dq(n, n), dqd(n, n);
  rd.compute(data, state.q, state.qd, qdd, tau, dq, dqd);
  requireFiniteOutputs(state, tau.allFinite() && dq.allFinite() && dqd.allFinite());
  Json out;
  out["qdd"] = vectorToJson(qdd);
  out["tau"] = vectorToJson(tau);
  out["dtau_dq"] = matrixToJson(dq);
  out["dtau_dqd"] = matrixToJson(dqd);
  return out;
}

/// The model of the command line: the URDF argument or the config's robot.urdf, with the
/// config's locked joints and --fixed-base.
std::shared_ptr<const RobotModel> loadModel(const reach_trajopt::CliArgs& args) {
  reach_trajopt::ModelOptions options;
  if (args.given("--fixed-base")) options.base = reach_trajopt::ModelOptions::Base::kFixed;
  std::string urdf = args.positional().empty() ? "" : args.positional()[0];
  // --config: the robot section's URDF (unless one is given) and its locked joints.
  if (!args.value("--config").empty()) {
    const reach_trajopt::RobotConfig robot = reach_trajopt::RobotConfig::fromConfigFile(
        reach_trajopt::YamlSection::loadFile(args.value("--config")));
    if (urdf.empty()) urdf = robot.urdfPath();
    options.locked_joints = robot.locked_joints;
  }
  return RobotModel::fromUrdfFile(urdf, options);
}

/// --state: the model's sizes, joints and limits, and evaluate() of each state, as JSON.
Json statesJson(const std::shared_ptr<const RobotModel>& model_ptr,
                const reach_trajopt::CliArgs& args) {
  const RobotModel& model = *model_ptr;
  const std::string state_file = args.value("--state");
  const Json input = reach_trajopt::JsonReader::parseFile(state_file);
  const auto states =
      reach_trajopt::readStates(reach_trajopt::JsonReader(input, state_file), model.nq());
  const std::vector<std::string> frames = split(args.value("--frames"), ',');
  for (const auto& f : frames) model.frameId(f);  // unknown frames fail before any output
  Json out;
  out["nq"] = model.nq();
  out["nu"] = model.nu();
  out["mass"] = model.totalMass();
  Json names = Json::array();
  for (const auto& j : model.joints()) names.push_back(j.name);
  out["joint_names"] = names;
  out["q_min"] = vectorToJson(model.positionLowerLimits());
  out["q_max"] = vectorToJson(model.positionUpperLimits());
  reach_trajopt::Workspace ws(model);
  const bool derivatives = args.given("--rnea-derivatives");
  const reach_trajopt::RneaDerivatives rd(model_ptr);
  reach_trajopt::RneaDerivatives::Data rd_data(model);
  Json results = Json::array();
  for (std::size_t i = 0; i < states.size(); ++i) {
    try {
      results.push_back(evaluate(model, ws, states[i], frames));
      if (derivatives)
        results.back()["rnea_derivatives"] = rneaDerivativesJson(rd, rd_data, states[i]);
    } catch (const reach_trajopt::RequestError& e) {
      throw reach_trajopt::RequestError(state_file + ": state " + std::to_string(i) + ": " +
                                        e.what());
    }
  }
  out["results"] = results;
  return out;
}

/// The command line's arguments: at most one URDF, and a URDF or --config. Prints what is
/// wrong and the usage line to stderr. \return false when they do not fit.
bool argumentsFit(const reach_trajopt::CliArgs& args) {
  const std::vector<std::string>& p = args.positional();
  if (p.size() > 1) {
    std::cerr << "model_info: unexpected argument '" << p[1] << "'\n";
  } else if (p.empty() && args.value("--config").empty()) {
    std::cerr << "model_info: give a URDF or --config FILE\n";
  } else if (!args.value("--frames").empty() && args.value("--state").empty()) {
    std::cerr
        << "model_info: --frames needs --state FILE: the frames are evaluated at its states\n";
  } else {
    return true;
  }
  std::cerr << kTool.usageLine() << "\n";
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  return kTool.run(argc, argv, [](const reach_trajopt::CliArgs& args) {
    if (!argumentsFit(args)) return 2;
    const auto model = loadModel(args);
    if (args.value("--state").empty()) {
      if (args.given("--json"))
        printSummaryJson(*model);
      else
        printSummary(*model);
      return 0;
    }
    std::cout << statesJson(model, args).dump() << "\n";
    return 0;
  });
}
