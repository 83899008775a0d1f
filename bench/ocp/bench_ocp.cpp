/// \file bench_ocp.cpp
/// Transition OCP (eq. 22-23) on the shipped biped, three footsteps from a static single
/// support (left stance at (0, 0.1); x_0 = the Sec. III-B stance for a step to (start, -0.1)
/// with the right leg folded, its sole lifted):
///   step_015: right sole to (0.15, -0.1), start 0.15, horizon 0.3 s, strict;
///   step_025: right sole to (0.25, -0.1), start 0.25, horizon 0.3 s, strict;
///   relaxed_055: to (0.55, -0.1), start 0.25, the reachable set's t_f hull at x <= 0.25:
///   relaxed (lands on the hull edge, |eps| = 0.3 m).
/// Ours: TransitionOcp::solve (NLopt SLSQP, the 1 ms re-check, refinement re-solves).
/// Reference: IPOPT (coinor-libipopt-dev, the paper's NLP solver; ipopt_transition_nlp.h) on
/// the same NLP: a TransitionNlp built as TransitionOcp builds it (same request, config and
/// relaxed flag as our final solve), from its initial guess (where our first SLSQP run
/// starts). It must also have the sample set our solver ended with: refinements only add
/// samples or hulls, each adding rows, so equal variable and row counts prove it; otherwise
/// IPOPT is not run (ref_status=different_nlp) rather than run on another NLP. IPOPT runs with a
/// limited-memory Hessian, stops on its own KKT test or on the counterpart of SLSQP's ftol_rel
/// test, and has SLSQP's budget (max_evaluations iterations, time_limit CPU seconds); see
/// ipopt_transition_nlp.h. Prints per case, medians over `repeats` solves (default 3):
///   BENCH ocp.<case> ours_s=<wall s> iters=<gradient evaluations> solves=<SLSQP runs>
///         variables=<n> constraints=<m> violation=<max family, 1 ms re-check> status=<...>
///         ref=ipopt ref_s=<wall s> ref_iters=<IPOPT iterations> ref_evals=<gradient evals>
///         ref_status=<IPOPT status> ref_violation=<max family, 1 ms re-check>
///         ref_nlp_violation=<max NLP row / bound violation> ratio=<ours_s / ref_s>
///         cost=<ours, NLP cost> ref_cost=<IPOPT, NLP cost> ref_solver_s=<OptimizeTNLP alone>
/// ref_s covers what one TransitionOcp round does around its solver (build the NLP, initial
/// guess, solve, sample at 1 ms and re-check), so ratio compares like with like when solves=1.
///   bench_ocp [repeats]

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "ipopt_transition_nlp.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/ocp/stance_reduced_dynamics.h"
#include "reach_trajopt/ocp/transition_check.h"
#include "reach_trajopt/ocp/transition_nlp.h"
#include "reach_trajopt/ocp/transition_ocp.h"
#include "reach_trajopt/planner/kinematic_feasibility.h"
#include "reach_trajopt/testing/reference_cases.h"

using namespace reach_trajopt;

namespace {

TransitionRequest stepRequest(const std::shared_ptr<const RobotModel>& m, double target_x,
                              double start_x) {
  return ocpStepCase(m, target_x, start_x, 0.3);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// IPOPT on the NLP of one request, timed like one TransitionOcp round (see file comment).
struct RefRun {
  IpoptBenchResult ipopt;
  double total_s = 0.0;    ///< build + initial guess + IPOPT + 1 ms re-check [s]
  double violation = 0.0;  ///< 1 ms re-check, max family
};

RefRun runReference(const TransitionOcp& ocp, const std::shared_ptr<const RobotModel>& model,
                    const TransitionRequest& req, bool relaxed, const IpoptBenchSettings& set) {
  const auto start = std::chrono::steady_clock::now();
  TransitionNlp nlp(model, ocp.config(), ocp.contact(), req, relaxed);
  RefRun run;
  run.ipopt = solveWithIpopt(nlp, nlp.initialGuess(), set);
  TransitionResult traj;
  nlp.sampleSolution(run.ipopt.x, ocp.config().output_dt, traj);
  run.violation = checkTransition(*model, ocp.contact(), req, traj, 0.5 * ocp.config().tolerance)
                      .violation.max();
  run.total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  const auto model =
      RobotModel::fromUrdfFile(std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf");
  const TransitionOcp ocp(model);
  struct Case {
    const char* name;
    double target, start;
    bool hull;
  };
  const Case cases[] = {{"step_015", 0.15, 0.15, false},
                        {"step_025", 0.25, 0.25, false},
                        {"relaxed_055", 0.55, 0.25, true}};
  for (const Case& c : cases) {
    TransitionRequest req = stepRequest(model, c.target, c.start);
    if (c.hull) {
      ReachableSlice s;
      s.time = req.horizon;
      s.A.resize(4, 2);
      s.A << 1, 0, -1, 0, 0, 1, 0, -1;
      s.b.resize(4);
      s.b << 0.25, 0.5, 0.0, 0.4;
      req.slices.push_back(s);
      req.relaxation = RelaxationMode::kRelaxed;
    }
    std::vector<double> times;
    TransitionResult res;
    for (int i = 0; i < repeats; ++i) {
      res = ocp.solve(req);
      times.push_back(res.solve_time);
    }
    const double ours_s = median(times);
    std::printf(
        "BENCH ocp.%s ours_s=%.3f iters=%d solves=%d variables=%d constraints=%d "
        "violation=%.2e status=%s",
        c.name, ours_s, res.iterations, res.solves, res.variables, res.constraints,
        res.violation.max(), ocpStatusName(res.status));

    // The same NLP: as TransitionOcp builds it for our last solve (res.relaxed says which
    // problem that was); equal sizes mean no refinement sample was added (file comment).
    const TransitionNlp probe(model, ocp.config(), ocp.contact(), req, res.relaxed);
    const int rows = probe.equalityCount() + probe.inequalityCount();
    if (probe.variableCount() != res.variables || rows != res.constraints) {
      std::printf(" ref=ipopt ref_status=different_nlp ref_variables=%d ref_constraints=%d\n",
                  probe.variableCount(), rows);
      std::fflush(stdout);
      continue;
    }
    IpoptBenchSettings set;
    set.acceptable_obj_change_tol =
        res.relaxed ? ocp.config().relaxed_ftol_rel : ocp.config().ftol_rel;
    set.max_iter = ocp.config().max_evaluations;
    set.max_cpu_time = ocp.config().time_limit;
    std::vector<double> ref_times, solver_times;
    RefRun ref;
    for (int i = 0; i < repeats; ++i) {
      ref = runReference(ocp, model, req, res.relaxed, set);
      ref_times.push_back(ref.total_s);
      solver_times.push_back(ref.ipopt.wall_time);
    }
    const double ref_s = median(ref_times);
    std::printf(
        " ref=ipopt ref_s=%.3f ref_iters=%d ref_evals=%d ref_status=%s ref_violation=%.2e "
        "ref_nlp_violation=%.2e ratio=%.2f cost=%.6g ref_cost=%.6g ref_solver_s=%.3f\n",
        ref_s, ref.ipopt.iterations, ref.ipopt.gradient_evaluations, ref.ipopt.status.c_str(),
        ref.violation, ref.ipopt.nlp_violation, ours_s / ref_s, res.cost, ref.ipopt.cost,
        median(solver_times));
    if (!ref.ipopt.error.empty()) {
      std::fprintf(stderr, "[bench_ocp] %s: TransitionNlp::evaluate threw inside IPOPT: %s\n",
                   c.name, ref.ipopt.error.c_str());
    }
    std::fflush(stdout);
  }
  return 0;
}
