/// \file reference_cases.cpp
/// The shared reference footsteps (see the header).

#include "reach_trajopt/testing/reference_cases.h"

#include <fstream>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/ocp/stance_reduced_dynamics.h"
#include "reach_trajopt/planner/kinematic_feasibility.h"
#include "reach_trajopt/step/footstep_plan_request_json.h"
#include "reach_trajopt/testing/swing_state.h"

namespace reach_trajopt {

ShippedBiped::ShippedBiped(const std::string& repo) {
  const YamlSection file = YamlSection::loadFile(repo + "/config/biped.yaml");
  contact = ContactConfig::fromYaml(file.section("contact"));
  config = FootstepPlannerConfig::fromYaml(file);
  model = RobotModel::fromUrdfFile(repo + "/urdf/biped.urdf");
}

std::shared_ptr<const RobotModel> shippedBipedModel(const std::string& repo) {
  static const auto model = RobotModel::fromUrdfFile(repo + "/urdf/biped.urdf");
  return model;
}

std::unique_ptr<FootstepTransitionPlanner> ShippedBiped::makePlanner() const {
  return std::make_unique<FootstepTransitionPlanner>(model, contact, config);
}

ShippedPipeline::ShippedPipeline(const std::string& repo_dir)
    : ShippedBiped(repo_dir), repo(repo_dir), planner(makePlanner()) {}

std::vector<FootstepPlanRequest> ShippedPipeline::requests(const std::string& fixture) const {
  return readPlanRequests(repo + "/test/fixtures/" + fixture, model->nq(), config.reach);
}

const ShippedPipeline& shippedPipeline(const std::string& repo) {
  static const ShippedPipeline p(repo);
  return p;
}

std::vector<FootstepPlanRequest> readPlanRequests(const std::string& path, int nq,
                                                  const ReachConfig& reach) {
  std::ifstream in(path);
  if (!in) throw RequestError("cannot read '" + path + "'");
  std::vector<FootstepPlanRequest> out;
  std::string line;
  while (std::getline(in, line)) {
    const nlohmann::json j = JsonReader::parse(line, path);
    out.push_back(readFootstepPlanRequest(JsonReader(j, path), nq, reach));
  }
  return out;
}

FlatContact contactAt(double x, double y) {
  FlatContact c;
  c.position << x, y, 0.0;
  return c;
}

Eigen::VectorXd bipedPosture(const RobotModel& m, const Eigen::Vector3d& base, double bend) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(m.nq());
  q.head<3>() = base;
  for (const std::string side : {"l_", "r_"}) {
    q[m.jointIndex(side + "hip_pitch")] = -bend;
    q[m.jointIndex(side + "knee")] = 2.0 * bend;
    q[m.jointIndex(side + "ankle_pitch")] = -bend;
  }
  return q;
}

Eigen::VectorXd bipedIkGuess(const RobotModel& m) {
  return bipedPosture(m, Eigen::Vector3d(0.0, 0.09, 1.05), 0.3);
}

TransitionRequest ocpStepCase(const std::shared_ptr<const RobotModel>& m, double target_x,
                              double start_x, double horizon) {
  const KinematicFeasibility kf(m);
  const FlatContact left = contactAt(0.0, 0.1);
  const auto start = kf.check(Side::kLeft, left, contactAt(start_x, -0.1), bipedIkGuess(*m));
  if (!start.feasible) throw ReachError("ocpStepCase: no IK for the start: " + start.reason);
  const auto final = kf.check(Side::kLeft, left, contactAt(target_x, -0.1), bipedIkGuess(*m));
  TransitionRequest r;
  r.stance = Side::kLeft;
  r.stance_contact = left;
  r.target = contactAt(target_x, -0.1);
  r.horizon = horizon;
  r.qf = final.q_f;
  r.qdf = final.qd_f;
  StanceReducedDynamics d(m, m->frameId("l_sole"), r.heldPose(), m->frameId("r_sole"),
                          r.targetPose(), 0.0);
  StanceReducedDynamics::Scratch s(d);
  Eigen::VectorXd qa = start.q_f.tail(m->nu());
  qa[m->jointIndex("r_knee") - 6] += 0.5;
  qa[m->jointIndex("r_ankle_pitch") - 6] -= 0.25;
  r.q0.resize(m->nq());
  d.configuration(s, qa, r.q0);
  r.qd0 = Eigen::VectorXd::Zero(m->nq());
  return r;
}

FootstepPlanRequest benchSwingCase(const std::shared_ptr<const RobotModel>& model,
                                   const FootstepPlannerConfig& config,
                                   const ContactConfig& contact) {
  FootstepPlanRequest r;
  r.stance = Side::kLeft;
  FlatContact stance;
  stance.position << 0.0, 0.1, 0.0;
  r.stance_contact = stance;
  r.target = {Eigen::Vector3d(0.25, -0.12, 0.0), stance.yaw};
  const Eigen::Vector3d p0 = r.target.position + Eigen::Vector3d(-0.03, 0.0, 0.02);
  const Eigen::VectorXd guess =
      bipedPosture(*model, Eigen::Vector3d(0.5 * p0.x(), 0.5 * (0.1 + p0.y()), 1.1), 0.4);
  const RobotState x0 = swingState(model, config.kinematics, contact, Side::kLeft, stance, p0, 0.0,
                                   2.0 * (r.target.position - p0) / config.reach.horizon, guess);
  r.q0 = x0.q;
  r.qd0 = x0.qd;
  return r;
}

}  // namespace reach_trajopt
