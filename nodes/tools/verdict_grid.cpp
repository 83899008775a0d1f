/// \file verdict_grid.cpp
/// verdict_grid: the oracle of the reachability verdict. From each x_0 it probes a grid of
/// footholds around the planned one with the check (FootstepTransitionPlanner, seeded strict
/// OCP on its witness) and, independently, with the strict transition OCP seeded without the
/// witness; a "reachable" verdict's witness is re-checked step by step with code of its own
/// (checkTransition of the OCP for eq. 1, the cones, torques and limits; the sole poses and
/// velocities from the model's kinematics for the held contact and the ground; the Euler steps;
/// x(t_0) = x_0 and x(t_f) against x_f).
///
///   verdict_grid [--config config/biped.yaml] [--urdf urdf/biped.urdf]
///                [--requests FILE.jsonl] [--bench-case] [--grid N] [--half-width M]
///                [--max-states K] [--details] [--reach-config FILE]
///                [--reference-config FILE] [--force]
///
/// --requests: footstep requests, one JSON per line (walk_experiment --plan-requests; format
/// in step/footstep_plan_request_json.h); --bench-case adds bench/reach's SS-L -> DS case
/// (horizon of the config's reach section). Each x_0 gets N x N footholds within +-M of its
/// target (default 7 x 7, 0.15 m); more than 2000 footholds in all need --force. Prints one `CASE`
/// line per foothold with --details and ends with
///   BENCH reach.verdict cases=.. states=.. kinematically_infeasible=.. reachable=..
///     certified=.. ocp_converged=.. false_reachable=.. false_unreachable=..
///     bridge_certified=.. reachable_strict_converged=.. check_mean_s=..
/// reachable: the planner's verdict (footstep_transition_planner.h: the check's bridged witness
/// or the local solve); certified / false_reachable (FR): reachable verdicts whose certificate
/// passes / fails this tool's re-check; ocp_converged (K): footholds where the strict OCP seeded
/// without the witness converged within the joint velocity limits (which it reports but does
/// not constrain); false_unreachable (FU): "not shown reachable" kinematically
/// feasible footholds where it converged; bridge_certified: reachable verdicts certified by
/// the bridge alone; reachable_strict_converged: reachable verdicts whose strict OCP converged.
/// --reach-config: the `reach:` section of FILE replaces --config's (e.g. config/reach_fast.yaml).
/// --reference-config: also checks every foothold with the `reach:` section of FILE (a slow
/// reference configuration, e.g. config/reach_reference.yaml: the settings before the fast
/// check) and compares the two verdicts (reachable / unreachable / kinematically infeasible):
///   BENCH reach.verdict_fast ref=reference cases=.. agreement=.. disagreements=..
///     feasible_agreement=.. (over the kinematically feasible footholds)
///     fast_reachable=.. ref_reachable=.. fast_only_reachable=.. ref_only_reachable=..
///     false_reachable=.. fast_check_mean_s=.. ref_check_mean_s=.. speedup=..
/// false_reachable there counts the fast configuration's reachable verdicts whose certificate
/// fails the re-check (the same as in reach.verdict). Then the check on its own
/// (ReachabilityAnalyzer::check, as the check service and bench/reach run it: with quick_pass
/// its adaptive budget, which may give up after the quick budget; reachable only by the bridge)
/// against the reference's check, over the kinematically feasible footholds, the same x_0 and
/// x_f:
///   BENCH reach.verdict_check ref=reference cases=.. agreement=.. own_reachable=..
///     ref_reachable=.. own_only_reachable=.. ref_only_reachable=.. false_reachable=..
///     gave_up=.. both_budgets=.. check_mean_s=.. ref_check_mean_s=.. speedup=..
/// Exit status: 0 ran, 2 bad input.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "reach_trajopt/common/cli_args.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/contact/contact_wrench_cone.h"
#include "reach_trajopt/model/robot_config.h"
#include "reach_trajopt/step/footstep_plan_request_json.h"
#include "reach_trajopt/step/footstep_transition_planner.h"
#include "reach_trajopt/step/reference_cases.h"

using namespace reach_trajopt;

namespace {

constexpr long long kMaxGrid = 41;      ///< --grid (docs/limits.md): N^2 checks per state
constexpr long long kMaxStates = 1000;  ///< --max-states
/// The most footholds (states x grid^2) one run checks without --force: each is a check (two
/// with --reference-config) and an OCP, about 2-5 s; the bench runs 4 x 49.
constexpr long long kMaxGridChecks = 2000;

/// A path to re-check: samples k = 0..L-1 at time[k]; step k (k < L-1) has the acceleration
/// qdd[k], torques u[k] and the stance wrench lambda[k] (world orientation at the sole centre).
struct CheckedPath {
  std::vector<double> time;
  Eigen::MatrixXd q, qd, qdd, u, lambda;
  bool euler = false;  ///< a 1 ms Euler path (the bridge): q_{k+1} = q_k + dt qd_{k+1} (or qd_k)
  std::vector<char> semi_implicit;
};

/// The re-check's verdict: a sentence naming the first family beyond its tolerance.
struct Recheck {
  bool passed = true;
  std::string failure;
  void require(const char* family, double value, double tolerance) {
    if (passed && !(value <= tolerance)) {
      passed = false;
      failure =
          std::string(family) + " " + std::to_string(value) + " > " + std::to_string(tolerance);
    }
  }
};

/// The bridge's witness as a CheckedPath (step k: qdd = (qd_{k+1} - qd_k) / dt).
CheckedPath fromWitness(const WitnessPath& w, double dt) {
  CheckedPath p;
  p.time = w.time;
  p.q = w.q;
  p.qd = w.qd;
  p.u = w.u;
  p.lambda = w.lambda.topRows(6);
  p.qdd.resize(w.q.rows(), w.u.cols());
  for (int k = 0; k + 1 < w.q.cols(); ++k) p.qdd.col(k) = (w.qd.col(k + 1) - w.qd.col(k)) / dt;
  p.euler = true;
  p.semi_implicit = w.semi_implicit_step;
  return p;
}

/// The OCP's trajectory as a CheckedPath (its 1 ms samples, analytic qdd).
CheckedPath fromTrajectory(const TransitionResult& t, Side stance) {
  CheckedPath p;
  p.time.assign(t.time.data(), t.time.data() + t.time.size());
  p.q = t.q;
  p.qd = t.qd;
  const Eigen::Index steps = t.q.cols() - 1;
  p.qdd = t.qdd.leftCols(steps);
  p.u = t.u.leftCols(steps);
  p.lambda = t.lambda.block(stance == Side::kLeft ? 0 : 6, 0, 6, steps);
  return p;
}

/// The oracle's own 1 ms re-check: eq. (1) assembled from M, b and the sole Jacobian; the
/// stance cone (8) in the held sole's orientation; torque, position and velocity limits; the
/// held sole's pose and velocity and the swing sole's height from the forward kinematics; the
/// Euler steps of an Euler path; x(0) = x_0, t_f and x(t_f) against x_f.
Recheck recheckPath(const RobotModel& model, const ContactConfig& contact, const ReachConfig& reach,
                    double dynamics_tolerance, const FootstepTransition& step,
                    const CheckedPath& p) {
  Recheck out;
  const int L = static_cast<int>(p.time.size()), nq = model.nq(), nu = model.nu();
  if (L < 2) {
    out.require("samples", 0, 2);
    return out;
  }
  const double dt = L > 1 ? p.time[1] - p.time[0] : 0.0;
  const FrameId stance = model.frameId(contact.soleFrame(step.stance));
  const FrameId swing = model.frameId(contact.soleFrame(opposite(step.stance)));
  const Eigen::Isometry3d held = step.stance_contact.pose();
  const ContactWrenchCone::Matrix C = ContactWrenchCone(contact).worldMatrix(held.linear());
  const Eigen::VectorXd u_max = model.effortLimits(), qd_max = model.velocityLimits();
  const Eigen::VectorXd q_lo = model.positionLowerLimits(), q_hi = model.positionUpperLimits();
  Workspace ws(model);
  Eigen::MatrixXd M(nq, nq), J(6, nq);
  Eigen::VectorXd b(nq);
  double dyn = 0, cone = 0, torque = 0, pos = 0, vel = 0, sole = 0, sole_v = 0, depth = 0,
         euler = 0;
  for (int k = 0; k < L; ++k) {
    const auto q = p.q.col(k), qd = p.qd.col(k);
    model.update(ws, q, qd);
    const Eigen::Isometry3d X = model.framePose(ws, stance);
    const Eigen::AngleAxisd rot(held.linear().transpose() * X.linear());
    sole = std::max({sole, (X.translation() - held.translation()).norm(), std::abs(rot.angle())});
    model.frameJacobian(ws, stance, J);
    sole_v = std::max(sole_v, (J * qd).cwiseAbs().maxCoeff());
    depth =
        std::max(depth, step.target.position.z() - model.framePose(ws, swing).translation().z());
    pos = std::max({pos, (q_lo - q).maxCoeff(), (q - q_hi).maxCoeff()});
    for (int i = 0; i < nq; ++i)
      if (std::isfinite(qd_max[i]) && qd_max[i] > 0)
        vel = std::max(vel, std::abs(qd[i]) - qd_max[i]);
    if (k + 1 == L) break;
    model.massMatrix(ws, M);
    model.bias(ws, b);
    Eigen::VectorXd r = M * p.qdd.col(k) + b - J.transpose() * p.lambda.col(k);
    r.tail(nu) -= p.u.col(k);
    dyn = std::max(dyn, r.cwiseAbs().maxCoeff());
    cone = std::max(cone, -(C * p.lambda.col(k)).minCoeff());
    torque = std::max(torque, (p.u.col(k).cwiseAbs() - u_max).maxCoeff());
    if (p.euler) {
      const Eigen::VectorXd v = p.semi_implicit[k] ? p.qd.col(k + 1) : p.qd.col(k);
      euler = std::max(euler, (p.q.col(k + 1) - q - dt * v).cwiseAbs().maxCoeff());
    }
  }
  const double W = model.totalMass() * model.gravity().norm();
  out.require("eq. (1) [N, Nm]", dyn, dynamics_tolerance);
  // The cone is written in the held (planned) sole orientation; the sole may be tilted from
  // it by up to the contact tolerance, which moves a row by at most |lambda| times that.
  out.require("stance cone [N]", cone, dynamics_tolerance + 2.0 * W * reach.contact_tolerance);
  out.require("torque limits [Nm]", torque, 1e-6);
  out.require("position limits [m, rad]", pos, 1e-6);
  out.require("velocity limits [m/s, rad/s]", vel, 1e-6);
  out.require("held sole pose [m, rad]", sole, 2.0 * reach.contact_tolerance);
  out.require("held sole velocity [m/s, rad/s]", sole_v,
              reach.certificate_contact_velocity_tolerance);
  out.require("swing sole below the ground [m]", depth, reach.certificate_tolerance);
  out.require("Euler steps [m, rad]", euler, 1e-9);
  out.require("x(0) - x_0",
              std::max((p.q.col(0) - step.q0).cwiseAbs().maxCoeff(),
                       (p.qd.col(0) - step.qd0).cwiseAbs().maxCoeff()),
              1e-9);
  out.require("t_f", std::abs(p.time[L - 1] - step.horizon), 1e-9);
  out.require("|q(t_f) - q_f|", (p.q.col(L - 1) - step.check.kinematics.q_f).cwiseAbs().maxCoeff(),
              reach.terminal_position_tolerance);
  out.require("|qd(t_f) - qd_f|", (p.qd.col(L - 1) - step.check.qdf).cwiseAbs().maxCoeff(),
              reach.terminal_velocity_tolerance);
  return out;
}

/// The re-check of a "reachable" step's certificate: the bridged witness, or the local solve.
Recheck recheckCertificate(const RobotModel& model, const ContactConfig& contact,
                           const FootstepPlannerConfig& cfg, const ReachConfig& reach,
                           const FootstepTransition& step) {
  if (step.certificate == "bridge")
    return recheckPath(model, contact, reach, reach.certificate_tolerance, step,
                       fromWitness(step.check.reach.witness, reach.dt));
  // The OCP's tolerance is relative to m g and u_max; in newtons that is at most this.
  const double W = model.totalMass() * model.gravity().norm();
  const double tol = cfg.ocp.tolerance * std::max(W, model.effortLimits().maxCoeff());
  return recheckPath(model, contact, reach, tol, step,
                     fromTrajectory(step.trajectory, step.stance));
}

}  // namespace

int main(int argc, char** argv) {
  // The state being probed ("FILE:LINE" or "--bench-case"): named in an error it raises (a
  // target far outside the workspace was reported without it).
  std::string state_source;
  try {
    std::string config_path = "config/biped.yaml", urdf, requests_path;
    std::string grid_s, half_s, max_s, reference_path, reach_path;
    bool bench_case = false, details = false, force = false;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto next = [&]() -> std::string {
        if (i + 1 >= argc) throw ReachError(a + ": missing value");
        return argv[++i];
      };
      if (a == "--config")
        config_path = next();
      else if (a == "--urdf")
        urdf = next();
      else if (a == "--requests")
        requests_path = next();
      else if (a == "--bench-case")
        bench_case = true;
      else if (a == "--grid")
        grid_s = next();
      else if (a == "--half-width")
        half_s = next();
      else if (a == "--max-states")
        max_s = next();
      else if (a == "--details")
        details = true;
      else if (a == "--force")
        force = true;
      else if (a == "--reference-config")
        reference_path = next();
      else if (a == "--reach-config")
        reach_path = next();
      else
        throw ReachError("unknown option '" + a + "'");
    }
    const int grid =
        grid_s.empty() ? 7 : static_cast<int>(parseIntOption("--grid", grid_s, 1, kMaxGrid));
    const double half = half_s.empty() ? 0.15 : parseDoubleOption("--half-width", half_s);
    if (!(half >= 0.0 && half <= 1.0)) throw ReachError("--half-width: expected [0, 1] m");
    const long long max_states =
        max_s.empty() ? kMaxStates : parseIntOption("--max-states", max_s, 1, kMaxStates);
    const YamlSection file = YamlSection::loadFile(config_path);
    const ContactConfig contact =
        file.has("contact") ? ContactConfig::fromYaml(file.section("contact")) : ContactConfig();
    FootstepPlannerConfig cfg = FootstepPlannerConfig::fromYaml(file);
    if (!reach_path.empty()) {
      const YamlSection reach_file = YamlSection::loadFile(reach_path);
      if (!reach_file.has("reach"))
        throw ReachError("--reach-config '" + reach_path + "' has no reach: section");
      cfg.reach = ReachConfig::fromYaml(reach_file.section("reach"), cfg.reach);
    }
    const auto model = RobotConfig::fromConfigFile(file).loadModel(urdf);
    const FootstepTransitionPlanner planner(model, contact, cfg);
    std::optional<ReachConfig> reference;
    if (!reference_path.empty()) {
      const YamlSection ref_file = YamlSection::loadFile(reference_path);
      if (!ref_file.has("reach"))
        throw ReachError("--reference-config '" + reference_path + "' has no reach: section");
      reference = ReachConfig::fromYaml(ref_file.section("reach"), cfg.reach);
    }

    std::vector<FootstepPlanRequest> states;
    std::vector<std::string> sources;
    if (bench_case) {
      states.push_back(benchSwingCase(model, cfg, contact));
      sources.push_back("--bench-case");
    }
    if (!requests_path.empty()) {
      std::ifstream in(requests_path);
      if (!in) throw ReachError("cannot read --requests file '" + requests_path + "'");
      std::string line;
      int n = 0;
      while (std::getline(in, line) && static_cast<long long>(states.size()) < max_states) {
        ++n;
        if (line.empty()) continue;
        const nlohmann::json j = JsonReader::parse(line, requests_path + ":" + std::to_string(n));
        states.push_back(readFootstepPlanRequest(
            JsonReader(j, requests_path + ":" + std::to_string(n)), model->nq(), cfg.reach));
        sources.push_back(requests_path + ":" + std::to_string(n));
      }
    }
    if (states.empty()) throw ReachError("no states: give --requests FILE and/or --bench-case");
    // The reference budget, as each state will run it (its horizon), up front: an over-limit
    // one named the check's pass mid-run, not the file's key.
    if (reference) {
      for (const FootstepPlanRequest& st : states) {
        ReachConfig rc = *reference;
        if (st.reach) rc.horizon = st.reach->horizon;
        const std::string where = "--reference-config '" + reference_path + "': reach";
        try {
          rc.validate();
          rc.requireResourcesWithinLimits(model->nq());
        } catch (const ReachError& e) {
          throw ConfigError(where + ": " + e.what());
        }
        try {
          if (rc.hull_pass) rc.hullPassConfig().requireResourcesWithinLimits(model->nq());
        } catch (const ReachError& e) {
          throw ConfigError(where + ": the hull pass's budget (hull_initial_samples " +
                            std::to_string(rc.hull_initial_samples) +
                            ", hull_children_per_parent " +
                            std::to_string(rc.hull_children_per_parent) + "): " + e.what());
        }
      }
    }
    const long long footholds = static_cast<long long>(states.size()) * grid * grid;
    if (footholds > kMaxGridChecks && !force)
      throw RequestError(std::to_string(states.size()) + " states x --grid " +
                         std::to_string(grid) + "^2 = " + std::to_string(footholds) +
                         " footholds to check, over the limit of " +
                         std::to_string(kMaxGridChecks) +
                         " (a check and an OCP each, seconds apiece): lower --grid or "
                         "--max-states, or add --force");

    int cases = 0, infeasible = 0, reachable = 0, certified = 0, bridge = 0, converged = 0, fr = 0,
        fu = 0, seeded = 0;
    double check_time = 0.0, ref_check_time = 0.0;
    int agree = 0, agree_feasible = 0, ref_reachable = 0, fast_only = 0, ref_only = 0;
    // The check on its own (reach.verdict_check).
    struct OwnCheck {
      int cases = 0, agree = 0, reachable = 0, ref_reachable = 0, only = 0, ref_only = 0, fr = 0,
          gave_up = 0, both = 0;
      double time_s = 0.0, ref_time_s = 0.0;
    } own;
    for (size_t s = 0; s < states.size(); ++s) {
      state_source = sources[s];
      for (int ix = 0; ix < grid; ++ix) {
        for (int iy = 0; iy < grid; ++iy) {
          const double dx = grid > 1 ? -half + 2.0 * half * ix / (grid - 1) : 0.0;
          const double dy = grid > 1 ? -half + 2.0 * half * iy / (grid - 1) : 0.0;
          FootstepPlanRequest r = states[s];
          r.target += Eigen::Vector3d(dx, dy, 0.0);
          ++cases;
          // The check; the strict OCP seeded with its witness when it says reachable.
          FootstepPlanRequest probe = r;
          probe.ocp_policy = OcpPolicy::kStrict;
          const FootstepTransition checked = planner.plan(probe);
          check_time += checked.check_time_s;
          if (reference) {
            // The same foothold with the reference sampling (the request's horizon kept).
            FootstepPlanRequest ref_probe = probe;
            ReachConfig rc = *reference;
            if (probe.reach) rc.horizon = probe.reach->horizon;
            ref_probe.reach = rc;
            const FootstepTransition ref = planner.plan(ref_probe);
            ref_check_time += ref.check_time_s;
            agree += ref.verdict == checked.verdict;
            agree_feasible += ref.verdict == checked.verdict && checked.kinematically_feasible;
            ref_reachable += ref.reachable;
            fast_only += checked.reachable && !ref.reachable;
            ref_only += ref.reachable && !checked.reachable;
            if (details && ref.verdict != checked.verdict)
              std::printf("DISAGREE state=%zu dx=%.3f dy=%.3f fast=%s(%s) reference=%s(%s)\n", s,
                          dx, dy, checked.verdict.c_str(), checked.certificate.c_str(),
                          ref.verdict.c_str(), ref.certificate.c_str());
          }
          if (reference && checked.kinematically_feasible) {
            // The same x_0 and x_f (the planner's IK) through the check alone.
            const ReachProblem problem =
                footstepProblem(FootstepTransitionPlanner::checkRequest(checked),
                                checked.check.kinematics.q_f, checked.check.qdf);
            ReachConfig own_config = probe.reach ? *probe.reach : cfg.reach;
            ReachConfig ref_config = *reference;
            ref_config.horizon = own_config.horizon;
            const ReachResult a = planner.analyzer().check(problem, own_config);
            const ReachResult b = planner.analyzer().check(problem, ref_config);
            ++own.cases;
            own.agree += a.reachable == b.reachable;
            own.reachable += a.reachable;
            own.ref_reachable += b.reachable;
            own.only += a.reachable && !b.reachable;
            own.ref_only += b.reachable && !a.reachable;
            own.gave_up += a.gave_up;
            own.both += a.budgets == 2;
            own.time_s += a.timings.total;
            own.ref_time_s += b.timings.total;
            if (a.reachable) {
              FootstepTransition bridged = checked;
              bridged.check.reach = a;
              bridged.certificate = "bridge";
              own.fr += !recheckCertificate(*model, contact, cfg, own_config, bridged).passed;
            }
            if (details && a.reachable != b.reachable)
              std::printf(
                  "DISAGREE_CHECK state=%zu dx=%.3f dy=%.3f own=%d(budgets %d%s) "
                  "reference=%d\n",
                  s, dx, dy, a.reachable ? 1 : 0, a.budgets, a.gave_up ? ", gave up" : "",
                  b.reachable ? 1 : 0);
          }
          if (!checked.kinematically_feasible) {
            ++infeasible;
            if (details)
              std::printf("CASE state=%zu dx=%.3f dy=%.3f verdict=kinematically_infeasible\n", s,
                          dx, dy);
            continue;
          }
          // The unseeded strict OCP.
          FootstepPlanRequest plain = r;
          plain.check_reachability = false;
          plain.ocp_policy = OcpPolicy::kStrict;
          const FootstepTransition ocp = planner.plan(plain);
          // Converged within the joint velocity limits: a feasible path (as a certificate).
          const bool ocp_ok = ocp.trajectory.reachesTargetWithinLimits(cfg.ocp.tolerance);
          converged += ocp_ok;
          std::string recheck = "-";
          if (checked.reachable) {
            ++reachable;
            bridge += checked.certificate == "bridge";
            seeded += checked.trajectory.status == OcpStatus::kConverged;
            const ReachConfig& reach = probe.reach ? *probe.reach : cfg.reach;
            const Recheck rc = recheckCertificate(*model, contact, cfg, reach, checked);
            (rc.passed ? certified : fr) += 1;
            recheck = rc.passed ? "passed" : "failed(" + rc.failure + ")";
          } else if (ocp_ok) {
            ++fu;
          }
          if (details) {
            const WitnessPath& w = checked.check.reach.witness;
            std::printf(
                "CASE state=%zu dx=%.3f dy=%.3f verdict=%s certificate=%s recheck=%s seeded_ocp=%s "
                "ocp=%s "
                "witness_violation=%.3g (dynamics %.2g cone %.2g torque %.2g limits %.2g/%.2g "
                "contact %.2g/%.2g ground %.2g) x_f_gap=%.3g/%.3g check_s=%.2f reason: %s\n",
                s, dx, dy, checked.verdict.c_str(),
                checked.certificate.empty() ? "none" : checked.certificate.c_str(), recheck.c_str(),
                ocpStatusName(checked.trajectory.status), ocpStatusName(ocp.trajectory.status),
                w.valid ? w.violation.max() : -1.0, w.violation.dynamics, w.violation.cone,
                w.violation.torque, w.violation.position_limit, w.violation.velocity_limit,
                w.violation.contact, w.violation.contact_velocity, w.violation.ground,
                w.terminal_position_gap, w.terminal_velocity_gap, checked.check_time_s,
                checked.check.reach.reason.c_str());
            std::fflush(stdout);
          }
        }
      }
    }
    std::printf(
        "BENCH reach.verdict cases=%d states=%zu kinematically_infeasible=%d reachable=%d "
        "certified=%d ocp_converged=%d false_reachable=%d false_unreachable=%d "
        "bridge_certified=%d reachable_strict_converged=%d check_mean_s=%.3f\n",
        cases, states.size(), infeasible, reachable, certified, converged, fr, fu, bridge, seeded,
        check_time / std::max(1, cases));
    if (reference)
      std::printf(
          "BENCH reach.verdict_fast ref=reference cases=%d agreement=%.4f disagreements=%d "
          "feasible_agreement=%.4f "
          "fast_reachable=%d ref_reachable=%d fast_only_reachable=%d ref_only_reachable=%d "
          "false_reachable=%d fast_check_mean_s=%.3f ref_check_mean_s=%.3f speedup=%.2f\n",
          cases, static_cast<double>(agree) / std::max(1, cases), cases - agree,
          static_cast<double>(agree_feasible) / std::max(1, cases - infeasible), reachable,
          ref_reachable, fast_only, ref_only, fr, check_time / std::max(1, cases),
          ref_check_time / std::max(1, cases), ref_check_time / std::max(1e-12, check_time));
    if (reference)
      std::printf(
          "BENCH reach.verdict_check ref=reference cases=%d agreement=%.4f own_reachable=%d "
          "ref_reachable=%d own_only_reachable=%d ref_only_reachable=%d false_reachable=%d "
          "gave_up=%d both_budgets=%d check_mean_s=%.3f ref_check_mean_s=%.3f speedup=%.2f\n",
          own.cases, static_cast<double>(own.agree) / std::max(1, own.cases), own.reachable,
          own.ref_reachable, own.only, own.ref_only, own.fr, own.gave_up, own.both,
          own.time_s / std::max(1, own.cases), own.ref_time_s / std::max(1, own.cases),
          own.ref_time_s / std::max(1e-12, own.time_s));
  } catch (const std::exception& e) {
    std::cerr << "verdict_grid: " << (state_source.empty() ? "" : state_source + ": ") << e.what()
              << "\n";
    return 2;
  }
  return 0;
}
