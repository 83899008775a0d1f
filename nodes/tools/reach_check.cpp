/// \file reach_check.cpp
/// reach_check: runs one reachability check (eq. 13-21) on a URDF, a YAML config and a JSON
/// request, and prints the result as JSON. For tests, and to reproduce a check outside ROS.
///
///   reach_check <robot.urdf> <config.yaml> <request.json> [--threads N] [--samples]
///
/// config.yaml: the sections `contact:`, `reach:` and `kinematic_feasibility:` are read when
/// present (config/biped.yaml has all three); missing sections keep the defaults.
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
#include <sstream>
#include <string>

#include "reach_trajopt/common/cli_args.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/model/robot_config.h"
#include "reach_trajopt/reach/footstep_reachability.h"
#include "reach_trajopt/reach/reach_request_json.h"
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

}  // namespace

int main(int argc, char** argv) {
  std::string paths[3];
  int n_paths = 0;
  std::string threads_arg, config_arg;
  bool samples = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--threads" && i + 1 < argc) {
      threads_arg = argv[++i];
    } else if (a == "--config" && i + 1 < argc) {
      config_arg = argv[++i];
    } else if (a == "--samples") {
      samples = true;
    } else if (n_paths < 3) {
      paths[n_paths++] = a;
    } else {
      n_paths = 4;
    }
  }
  // --config FILE request.json: the URDF is the config's robot.urdf.
  if (!config_arg.empty() && n_paths == 1) {
    paths[2] = paths[0];
    paths[1] = config_arg;
    paths[0].clear();
    n_paths = 3;
  } else if (!config_arg.empty()) {
    n_paths = 0;
  }
  if (n_paths != 3) {
    std::cerr << "usage: reach_check <robot.urdf> <config.yaml> <request.json> [--threads N] "
                 "[--samples]\n"
                 "       reach_check --config <config.yaml> <request.json> [...] (the URDF: "
                 "robot.urdf)\n";
    return 2;
  }
  try {
    const YamlSection yaml = YamlSection::loadFile(paths[1]);
    const auto model = RobotConfig::fromConfigFile(yaml).loadModel(paths[0]);
    ContactConfig contact;
    if (yaml.has("contact")) contact = ContactConfig::fromYaml(yaml.section("contact"));
    ReachConfig config;
    if (yaml.has("reach")) config = ReachConfig::fromYaml(yaml.section("reach"));
    KinematicFeasibilityConfig kf_config;
    if (yaml.has("kinematic_feasibility"))
      kf_config = KinematicFeasibilityConfig::fromYaml(yaml.section("kinematic_feasibility"));
    const json doc = JsonReader::parseFile(paths[2]);
    const ReachCheckRequest req =
        readReachCheckRequest(JsonReader(doc, paths[2]), model->nq(), config);
    config = req.config;
    if (!threads_arg.empty()) config.threads = parseThreadsOption("--threads", threads_arg);
    config.validate();
    config.requireResourcesWithinLimits(model->nq());  // before the IK and any sample
    if (samples && config.estimatedQps() > kMaxPrintedSamples) {
      std::ostringstream os;
      os << "--samples: the check would print about " << config.estimatedQps()
         << " samples, over the limit of " << kMaxPrintedSamples
         << " (docs/limits.md): lower initial_samples or max_boundary";
      throw RequestError(os.str());
    }
    const bool contacts = req.mode != "none";
    const ContactMode mode = contacts ? ContactMode::fromName(req.mode) : ContactMode{false, false};

    ReachProblem p;
    p.mode = mode;
    const FlatContact& stance = req.stance;
    const FlatContact& target = req.target;
    if (contacts) {
      p.footholds[mode.stance() == Side::kLeft ? 0 : 1] = stance.pose();
      p.target = target.pose();
    }
    if (req.has_x0) {
      p.q0 = req.q0;
      p.qd0 = req.qd0;
    } else {
      const RobotState x0 =
          swingState(model, kf_config, contact, mode.stance(), stance, req.swing_position,
                     req.swing_yaw, req.swing_velocity, req.q_init);
      p.q0 = x0.q;
      p.qd0 = x0.qd;
    }
    json out;
    const auto analyzer = std::make_shared<ReachabilityAnalyzer>(model, contact, config);
    ReachResult r;
    if (req.has_xf) {
      p.qf = req.qf;
      p.qdf = req.qdf;
      r = analyzer->check(p);
    } else {
      FootstepRequest fr;
      fr.stance = mode.stance();
      fr.stance_foothold = stance;
      fr.target = target;
      fr.q0 = p.q0;
      fr.qd0 = p.qd0;
      const FootstepReachability check(
          analyzer, std::make_shared<KinematicFeasibility>(model, kf_config, contact));
      FootstepResult f = check.check(fr);
      out["kinematically_feasible"] = f.kinematically_feasible;
      if (!f.kinematically_feasible) {
        out["reachable"] = false;
        out["reason"] = f.reason;
        std::cout << out.dump() << "\n";
        return 0;
      }
      r = std::move(f.reach);
    }
    out["reachable"] = r.reachable;
    out["reason"] = r.reason;
    out["budgets"] = r.budgets;
    out["gave_up"] = r.gave_up;
    out["dt"] = r.dt;
    out["joint_names"] = r.joint_names;
    out["counts"] = {{"forward_samples", r.counts.forward_samples},
                     {"backward_samples", r.counts.backward_samples},
                     {"forward_qps", r.counts.forward_qps},
                     {"backward_qps", r.counts.backward_qps},
                     {"forward_rejected", r.counts.forward_rejected},
                     {"backward_rejected", r.counts.backward_rejected},
                     {"backward_prefiltered", r.counts.backward_prefiltered},
                     {"threads", r.counts.threads}};
    out["timings"] = {{"forward_s", r.timings.forward},   {"backward_s", r.timings.backward},
                      {"boundary_s", r.timings.boundary}, {"hausdorff_s", r.timings.hausdorff},
                      {"witness_s", r.timings.witness},   {"total_s", r.timings.total}};
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
    out["window"] = window;
    out["best"] = r.best;
    if (r.witness.valid) {
      const WitnessPath& w = r.witness;
      const PathViolation& v = w.violation;
      out["witness"] = {{"time", w.time},
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
                        {"max_violation", v.max()},
                        {"violation",
                         {{"dynamics", v.dynamics},
                          {"cone", v.cone},
                          {"torque", v.torque},
                          {"position_limit", v.position_limit},
                          {"velocity_limit", v.velocity_limit},
                          {"contact", v.contact},
                          {"contact_velocity", v.contact_velocity},
                          {"integration", v.integration},
                          {"ground", v.ground}}}};
    }
    for (int dir = 0; dir < 2; ++dir) {
      json list = json::array();
      for (const SampleSlice& s : dir == 0 ? r.forward : r.backward) {
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
      out["slices"][dir == 0 ? "forward" : "backward"] = list;
    }
    std::cout << out.dump() << "\n";
    return 0;
  } catch (const ReachError& e) {
    std::cerr << "reach_check: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "reach_check: " << e.what() << "\n";
    return 2;
  }
}
