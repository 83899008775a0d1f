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
/// target (default 7 x 7, 0.15 m). Prints one `CASE` line per foothold with --details and
/// ends with
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
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "reach_trajopt/common/cli_args.h"
#include "reach_trajopt/common/cli_options.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/common/text_file.h"
#include "reach_trajopt/step/footstep_plan_request_json.h"
#include "reach_trajopt/step/footstep_planner_setup.h"
#include "reach_trajopt/step/footstep_transition_planner.h"
#include "reach_trajopt/testing/reference_cases.h"
#include "verdict_recheck.h"

using namespace reach_trajopt;
using verdict::Recheck;
using verdict::recheckCertificate;

namespace {

constexpr long long kMaxGrid = 41;      ///< --grid (docs/limits.md): N^2 checks per state
constexpr long long kMaxStates = 1000;  ///< --max-states
/// The most footholds (states x grid^2) one run checks without --force: each is a check (two
/// with --reference-config) and an OCP, about 2-5 s; the bench runs 4 x 49.
constexpr long long kMaxGridChecks = 2000;

/// The tool's options (--help prints them).
const CliTool kTool(
    "verdict_grid", "",
    "The oracle of the reachability verdict: probes a grid of footholds around each state's\n"
    "target with the check and the strict OCP and re-checks every reachable verdict.",
    {configOption("config file (robot, contact, the planner's sections)"),
     urdfOption(),
     {"--requests", "FILE.jsonl", "footstep requests, one JSON per line", ""},
     {"--bench-case", "", "add bench/reach's SS-L -> DS case", ""},
     {"--grid", "N", "N x N footholds per state (1.." + std::to_string(kMaxGrid) + ")", "7"},
     {"--half-width", "M", "the grid's half-width around the target [m, 0..1]", "0.15"},
     {"--max-states", "K", "at most K states of --requests", std::to_string(kMaxStates)},
     {"--details", "", "print a CASE line per foothold (DISAGREE lines with a reference)", ""},
     {"--reach-config", "FILE", "the reach: section of FILE replaces --config's", ""},
     {"--force", "", "check more than " + std::to_string(kMaxGridChecks) + " footholds in all", ""},
     {"--reference-config", "FILE",
      "also check every foothold with the reach: section of FILE and compare", ""}});

/// The command line's values.
struct GridOptions {
  std::string config_path, urdf, requests_path, reach_path, reference_path;
  bool bench_case = false, details = false, force = false;
  int grid = 7;
  double half = 0.15;  ///< [m]
  long long max_states = kMaxStates;
};

/// The options' values, each checked against its range. \throws RequestError naming it.
GridOptions gridOptions(const CliArgs& args) {
  GridOptions o;
  o.config_path = args.value("--config");
  o.urdf = args.value("--urdf");
  o.requests_path = args.value("--requests");
  o.reach_path = args.value("--reach-config");
  o.reference_path = args.value("--reference-config");
  o.bench_case = args.given("--bench-case");
  o.details = args.given("--details");
  o.force = args.given("--force");
  o.grid = static_cast<int>(parseIntOption("--grid", args.value("--grid"), 1, kMaxGrid));
  o.half = parseDoubleOption("--half-width", args.value("--half-width"));
  if (!(o.half >= 0.0 && o.half <= 1.0)) throw ReachError("--half-width: expected [0, 1] m");
  o.max_states = parseIntOption("--max-states", args.value("--max-states"), 1, kMaxStates);
  return o;
}

/// The reach: section of the file of `option` on top of `base`. \throws ReachError naming the
/// option and file when the file has no such section.
ReachConfig reachSectionOf(const std::string& path, const std::string& option,
                           const ReachConfig& base) {
  const YamlSection file = YamlSection::loadFile(path);
  if (!file.has("reach")) throw ReachError(option + " '" + path + "' has no reach: section");
  return ReachConfig::fromYaml(file.section("reach"), base);
}

/// The run's configs, model and planner; the reference's reach config with
/// --reference-config.
struct GridSetup {
  FootstepPlannerSetup setup;
  std::shared_ptr<const RobotModel> model;
  std::unique_ptr<FootstepTransitionPlanner> planner;
  std::optional<ReachConfig> reference;
};

GridSetup gridSetup(const GridOptions& o) {
  GridSetup g;
  g.setup = FootstepPlannerSetup::fromYamlFile(o.config_path);
  FootstepPlannerConfig& cfg = g.setup.planner;
  if (!o.reach_path.empty()) cfg.reach = reachSectionOf(o.reach_path, "--reach-config", cfg.reach);
  g.model = g.setup.loadModel(o.urdf);
  g.planner = std::make_unique<FootstepTransitionPlanner>(g.model, g.setup.contact, cfg);
  if (!o.reference_path.empty())
    g.reference = reachSectionOf(o.reference_path, "--reference-config", cfg.reach);
  return g;
}

/// The states x_0 and where each came from ("FILE:LINE" or "--bench-case", named in the errors
/// a state raises).
struct GridStates {
  std::vector<FootstepPlanRequest> requests;
  std::vector<std::string> sources;
};

/// The states x_0: bench/reach's case (--bench-case), then --requests' lines (at most
/// --max-states in all). \throws ReachError naming the file and line of a bad request.
GridStates loadStates(const GridOptions& o, const GridSetup& g) {
  GridStates out;
  std::vector<FootstepPlanRequest>& states = out.requests;
  const FootstepPlannerConfig& cfg = g.setup.planner;
  if (o.bench_case) {
    states.push_back(benchSwingCase(g.model, cfg, g.setup.contact));
    out.sources.push_back("--bench-case");
  }
  if (!o.requests_path.empty()) {
    std::istringstream in(readTextFile<RequestError>(
        o.requests_path, "--requests file '" + o.requests_path + "'", kMaxJsonRequestBytes));
    std::string line;
    int n = 0;
    while (std::getline(in, line) && static_cast<long long>(states.size()) < o.max_states) {
      ++n;
      if (line.empty()) continue;
      const std::string where = o.requests_path + ":" + std::to_string(n);
      const nlohmann::json j = JsonReader::parse(line, where);
      states.push_back(readFootstepPlanRequest(JsonReader(j, where), g.model->nq(), cfg.reach));
      out.sources.push_back(where);
    }
  }
  if (states.empty()) throw ReachError("no states: give --requests FILE and/or --bench-case");
  return out;
}

/// The reference budget as each state will run it (its horizon), up front: an over-limit one
/// would otherwise name the check's pass mid-run, not the file's key.
void requireReferenceWithinLimits(const GridOptions& o, const GridSetup& g,
                                  const GridStates& states) {
  if (!g.reference) return;
  const std::string where = "--reference-config '" + o.reference_path + "': reach";
  for (const FootstepPlanRequest& st : states.requests) {
    ReachConfig rc = *g.reference;
    if (st.reach) rc.horizon = st.reach->horizon;
    try {
      rc.validate();
      rc.requireResourcesWithinLimits(g.model->nq());  // every budget: full, quick, hull
    } catch (const ReachError& e) {
      throw ConfigError(where + ": " + e.what());
    }
  }
}

/// Without --force, at most kMaxGridChecks footholds in all. \throws RequestError.
void requireGridWithinLimit(const GridOptions& o, std::size_t states) {
  const long long footholds = static_cast<long long>(states) * o.grid * o.grid;
  if (footholds > kMaxGridChecks && !o.force)
    throw RequestError(std::to_string(states) + " states x --grid " + std::to_string(o.grid) +
                       "^2 = " + std::to_string(footholds) +
                       " footholds to check, over the limit of " + std::to_string(kMaxGridChecks) +
                       " (a check and an OCP each, seconds apiece): lower --grid or "
                       "--max-states, or add --force");
}

/// One foothold of the grid: its state, offset and request (the state's target moved).
struct Probe {
  std::size_t state;
  double dx, dy;
  FootstepPlanRequest request;
};

/// The grid's verdicts against the oracles, counted foothold by foothold, and the BENCH lines.
class VerdictGrid {
 public:
  VerdictGrid(const GridSetup& g, bool details) : g_(g), cfg_(g.setup.planner), details_(details) {}

  /// The check (the strict OCP seeded with its witness when it says reachable), compared with
  /// the reference configuration's, the check on its own and the unseeded strict OCP.
  void probe(const Probe& p) {
    ++cases_;
    FootstepPlanRequest request = p.request;
    request.ocp_policy = OcpPolicy::kStrict;
    const FootstepTransition checked = g_.planner->plan(request);
    check_time_ += checked.check_time_s;
    if (g_.reference) compareReference(p, request, checked);
    if (g_.reference && checked.kinematically_feasible) compareCheck(p, request, checked);
    if (!checked.kinematically_feasible) {
      ++infeasible_;
      if (details_)
        std::printf("CASE state=%zu dx=%.3f dy=%.3f verdict=kinematically_infeasible\n", p.state,
                    p.dx, p.dy);
      return;
    }
    compareOcp(p, request, checked);
  }

  void printBench(std::size_t states) const;

 private:
  /// The same foothold with the reference sampling (the request's horizon kept).
  void compareReference(const Probe& p, const FootstepPlanRequest& request,
                        const FootstepTransition& checked) {
    FootstepPlanRequest ref_request = request;
    ReachConfig rc = *g_.reference;
    if (request.reach) rc.horizon = request.reach->horizon;
    ref_request.reach = rc;
    const FootstepTransition ref = g_.planner->plan(ref_request);
    ref_check_time_ += ref.check_time_s;
    agree_ += ref.verdict == checked.verdict;
    agree_feasible_ += ref.verdict == checked.verdict && checked.kinematically_feasible;
    ref_reachable_ += ref.reachable;
    fast_only_ += checked.reachable && !ref.reachable;
    ref_only_ += ref.reachable && !checked.reachable;
    if (details_ && ref.verdict != checked.verdict)
      std::printf("DISAGREE state=%zu dx=%.3f dy=%.3f fast=%s(%s) reference=%s(%s)\n", p.state,
                  p.dx, p.dy, stepVerdictName(checked.verdict),
                  certificateName(checked.certificate), stepVerdictName(ref.verdict),
                  certificateName(ref.certificate));
  }

  void compareCheck(const Probe& p, const FootstepPlanRequest& request,
                    const FootstepTransition& checked);
  void compareOcp(const Probe& p, const FootstepPlanRequest& request,
                  const FootstepTransition& checked);
  void printCase(const Probe& p, const FootstepTransition& checked, const std::string& recheck,
                 const FootstepTransition& ocp) const;

  /// The check on its own (reach.verdict_check).
  struct OwnCheck {
    int cases = 0, agree = 0, reachable = 0, ref_reachable = 0, only = 0, ref_only = 0, fr = 0,
        gave_up = 0, both = 0;
    double time_s = 0.0, ref_time_s = 0.0;
  };

  const GridSetup& g_;
  const FootstepPlannerConfig& cfg_;
  const bool details_;
  int cases_ = 0, infeasible_ = 0, reachable_ = 0, certified_ = 0, bridge_ = 0, converged_ = 0,
      fr_ = 0, fu_ = 0, seeded_ = 0;
  double check_time_ = 0.0, ref_check_time_ = 0.0;
  int agree_ = 0, agree_feasible_ = 0, ref_reachable_ = 0, fast_only_ = 0, ref_only_ = 0;
  OwnCheck own_;
};

/// The same x_0 and x_f (the planner's IK) through the check alone, with the request's and
/// the reference's config; a reachable verdict's bridge re-checked.
void VerdictGrid::compareCheck(const Probe& p, const FootstepPlanRequest& request,
                               const FootstepTransition& checked) {
  const ReachProblem problem =
      footstepProblem(checked.transition, checked.check.kinematics.q_f, checked.check.qdf);
  ReachConfig own_config = request.reach ? *request.reach : cfg_.reach;
  ReachConfig ref_config = *g_.reference;
  ref_config.horizon = own_config.horizon;
  const ReachResult a = g_.planner->analyzer().check(problem, own_config);
  const ReachResult b = g_.planner->analyzer().check(problem, ref_config);
  ++own_.cases;
  own_.agree += a.reachable == b.reachable;
  own_.reachable += a.reachable;
  own_.ref_reachable += b.reachable;
  own_.only += a.reachable && !b.reachable;
  own_.ref_only += b.reachable && !a.reachable;
  own_.gave_up += a.gave_up;
  own_.both += a.budgets == 2;
  own_.time_s += a.timings.total;
  own_.ref_time_s += b.timings.total;
  if (a.reachable) {
    FootstepTransition bridged = checked;
    bridged.check.reach = a;
    bridged.certificate = Certificate::kBridge;
    own_.fr += !recheckCertificate(*g_.model, g_.setup.contact, cfg_, own_config, bridged).passed;
  }
  if (details_ && a.reachable != b.reachable)
    std::printf("DISAGREE_CHECK state=%zu dx=%.3f dy=%.3f own=%d(budgets %d%s) reference=%d\n",
                p.state, p.dx, p.dy, a.reachable ? 1 : 0, a.budgets, a.gave_up ? ", gave up" : "",
                b.reachable ? 1 : 0);
}

/// The unseeded strict OCP of a kinematically feasible foothold; the re-check of a reachable
/// verdict's certificate.
void VerdictGrid::compareOcp(const Probe& p, const FootstepPlanRequest& request,
                             const FootstepTransition& checked) {
  FootstepPlanRequest plain = p.request;
  plain.check_reachability = false;
  plain.ocp_policy = OcpPolicy::kStrict;
  const FootstepTransition ocp = g_.planner->plan(plain);
  // Converged within the joint velocity limits: a feasible path (as a certificate).
  const bool ocp_ok = ocp.trajectory.reachesTargetWithinLimits(cfg_.ocp.tolerance);
  converged_ += ocp_ok;
  std::string recheck = "-";
  if (checked.reachable) {
    ++reachable_;
    bridge_ += checked.certificate == Certificate::kBridge;
    seeded_ += checked.trajectory.status == OcpStatus::kConverged;
    const ReachConfig& reach = request.reach ? *request.reach : cfg_.reach;
    const Recheck rc = recheckCertificate(*g_.model, g_.setup.contact, cfg_, reach, checked);
    (rc.passed ? certified_ : fr_) += 1;
    recheck = rc.passed ? "passed" : "failed(" + rc.failure + ")";
  } else if (ocp_ok) {
    ++fu_;
  }
  if (details_) printCase(p, checked, recheck, ocp);
}

void VerdictGrid::printCase(const Probe& p, const FootstepTransition& checked,
                            const std::string& recheck, const FootstepTransition& ocp) const {
  const WitnessPath& w = checked.check.reach.witness;
  std::printf(
      "CASE state=%zu dx=%.3f dy=%.3f verdict=%s certificate=%s recheck=%s seeded_ocp=%s "
      "ocp=%s "
      "witness_violation=%.3g (dynamics %.2g cone %.2g torque %.2g limits %.2g/%.2g "
      "contact %.2g/%.2g ground %.2g) x_f_gap=%.3g/%.3g check_s=%.2f reason: %s\n",
      p.state, p.dx, p.dy, stepVerdictName(checked.verdict),
      checked.certificate == Certificate::kNone ? "none" : certificateName(checked.certificate),
      recheck.c_str(), ocpStatusName(checked.trajectory.status),
      ocpStatusName(ocp.trajectory.status), w.valid ? w.violation.max() : -1.0,
      w.violation.dynamics, w.violation.cone, w.violation.torque, w.violation.position_limit,
      w.violation.velocity_limit, w.violation.contact, w.violation.contact_velocity,
      w.violation.ground, w.terminal_position_gap, w.terminal_velocity_gap, checked.check_time_s,
      checked.check.reach.reason.c_str());
  std::fflush(stdout);
}

void VerdictGrid::printBench(std::size_t states) const {
  std::printf(
      "BENCH reach.verdict cases=%d states=%zu kinematically_infeasible=%d reachable=%d "
      "certified=%d ocp_converged=%d false_reachable=%d false_unreachable=%d "
      "bridge_certified=%d reachable_strict_converged=%d check_mean_s=%.3f\n",
      cases_, states, infeasible_, reachable_, certified_, converged_, fr_, fu_, bridge_, seeded_,
      check_time_ / std::max(1, cases_));
  if (!g_.reference) return;
  std::printf(
      "BENCH reach.verdict_fast ref=reference cases=%d agreement=%.4f disagreements=%d "
      "feasible_agreement=%.4f "
      "fast_reachable=%d ref_reachable=%d fast_only_reachable=%d ref_only_reachable=%d "
      "false_reachable=%d fast_check_mean_s=%.3f ref_check_mean_s=%.3f speedup=%.2f\n",
      cases_, static_cast<double>(agree_) / std::max(1, cases_), cases_ - agree_,
      static_cast<double>(agree_feasible_) / std::max(1, cases_ - infeasible_), reachable_,
      ref_reachable_, fast_only_, ref_only_, fr_, check_time_ / std::max(1, cases_),
      ref_check_time_ / std::max(1, cases_), ref_check_time_ / std::max(1e-12, check_time_));
  std::printf(
      "BENCH reach.verdict_check ref=reference cases=%d agreement=%.4f own_reachable=%d "
      "ref_reachable=%d own_only_reachable=%d ref_only_reachable=%d false_reachable=%d "
      "gave_up=%d both_budgets=%d check_mean_s=%.3f ref_check_mean_s=%.3f speedup=%.2f\n",
      own_.cases, static_cast<double>(own_.agree) / std::max(1, own_.cases), own_.reachable,
      own_.ref_reachable, own_.only, own_.ref_only, own_.fr, own_.gave_up, own_.both,
      own_.time_s / std::max(1, own_.cases), own_.ref_time_s / std::max(1, own_.cases),
      own_.ref_time_s / std::max(1e-12, own_.time_s));
}

/// The grid's footholds of state `s`: N x N offsets within +-half of its target, row by row.
std::vector<Probe> gridProbes(std::size_t s, const FootstepPlanRequest& state,
                              const GridOptions& o) {
  std::vector<Probe> probes;
  for (int ix = 0; ix < o.grid; ++ix) {
    for (int iy = 0; iy < o.grid; ++iy) {
      const double dx = o.grid > 1 ? -o.half + 2.0 * o.half * ix / (o.grid - 1) : 0.0;
      const double dy = o.grid > 1 ? -o.half + 2.0 * o.half * iy / (o.grid - 1) : 0.0;
      Probe p{s, dx, dy, state};
      p.request.target.position += Eigen::Vector3d(dx, dy, 0.0);
      probes.push_back(std::move(p));
    }
  }
  return probes;
}

}  // namespace

int main(int argc, char** argv) {
  std::string state_source;  // the state being probed, named in an error it raises
  try {
    const CliArgs args = kTool.parse(argc, argv);
    if (args.help()) {
      std::cout << kTool.usage();
      return 0;
    }
    if (!args.positional().empty())
      throw ReachError("unknown option '" + args.positional()[0] + "'");
    const GridOptions options = gridOptions(args);
    const GridSetup setup = gridSetup(options);
    const GridStates states = loadStates(options, setup);
    requireReferenceWithinLimits(options, setup, states);
    requireGridWithinLimit(options, states.requests.size());
    VerdictGrid grid(setup, options.details);
    for (std::size_t s = 0; s < states.requests.size(); ++s) {
      state_source = states.sources[s];
      for (const Probe& p : gridProbes(s, states.requests[s], options)) grid.probe(p);
    }
    state_source.clear();
    grid.printBench(states.requests.size());
  } catch (const std::exception& e) {
    std::cerr << "verdict_grid: " << (state_source.empty() ? "" : state_source + ": ") << e.what()
              << "\n";
    return 2;
  }
  return 0;
}
