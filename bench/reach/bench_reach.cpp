/// \file bench_reach.cpp
/// The paper's reachability case (Sec. IV-B): one SS-L -> DS transition of the biped, 1e4
/// samples at the first step of each direction, dt = 1 ms. Prints wall times of the forward,
/// backward, boundary and Hausdorff stages and of the whole check, QPs per second, the 1 -> 2
/// thread speed-up, forward-only (the paper's earlier method: forward over the whole horizon)
/// versus bidirectional, and the peak resident memory. Median of `repeats` runs (min_s: the
/// fastest of them, for a machine whose speed drifts between runs); a mode's 1- and 2-thread
/// checks take turns (timeCases), so their ratio compares the same moments.
/// mode=bidirectional is the check as shipped (ReachabilityAnalyzer::check with the adaptive
/// budget of reach.quick_pass: the quick budget, then the full one unless the quick one
/// certified or gave up; budgets= and gave_up= say which), mode=full_budget the full budget
/// alone (1e4 first draws, as before the adaptive budget). Then the same
/// case with the walk's check horizon (0.2 s, walk.check_horizon: the sole 3 cm short 0.2 s
/// before touchdown) at 1 and 2 threads with the full budget alone, for the stage times of the
/// walk's full passes (mode=walk_horizon; the walk itself is scripts/bench_walk_check.sh).
///
///   bench_reach [repeats=3] [initial_samples=0: the configuration's budgets.full] [config.yaml]

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/planner/kinematic_feasibility.h"
#include "reach_trajopt/reach/footstep_reachability.h"
#include "reach_trajopt/testing/reference_cases.h"

using namespace reach_trajopt;

namespace {

double peakRssMiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;  // ru_maxrss is in KiB on Linux
}

/// User + system CPU time of the process so far [s]: the work of a check, less sensitive to
/// other load on the machine than its wall time.
double cpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + 1e-6 * u.ru_utime.tv_usec + u.ru_stime.tv_sec +
         1e-6 * u.ru_stime.tv_usec;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// Median stage times [s] of a check, and its last result.
struct CaseTimes {
  double total = 0.0, total_min = 0.0, cpu = 0.0, forward = 0.0, backward = 0.0, boundary = 0.0,
         hausdorff = 0.0, witness = 0.0;
  FootstepCheckResult result;
};

/// Median stage times [s] of `repeats` checks of `req` with each of `configs`, and the last
/// result of each. The configurations take turns, one check each per repeat, so a machine whose
/// speed drifts between runs slows them alike: their ratio (the 1 -> 2 thread speed-up) is not
/// that of two different moments.
std::vector<CaseTimes> timeCases(const FootstepReachability& check, const ContactTransition& req,
                                 const std::vector<ReachConfig>& configs, int repeats) {
  const std::size_t n = configs.size();
  std::vector<std::vector<double>> tot(n), fw(n), bw(n), bd(n), hd(n), wt(n), cpu(n);
  std::vector<CaseTimes> out(n);
  for (int k = 0; k < repeats; ++k) {
    for (std::size_t c = 0; c < n; ++c) {
      const double c0 = cpuSeconds();
      out[c].result = check.check(req, configs[c]);
      cpu[c].push_back(cpuSeconds() - c0);
      const ReachTimings& t = out[c].result.reach.timings;
      tot[c].push_back(t.total);
      fw[c].push_back(t.forward);
      bw[c].push_back(t.backward);
      bd[c].push_back(t.boundary);
      hd[c].push_back(t.hausdorff);
      wt[c].push_back(t.witness);
    }
  }
  for (std::size_t c = 0; c < n; ++c) {
    out[c].total = median(tot[c]);
    out[c].total_min = *std::min_element(tot[c].begin(), tot[c].end());
    out[c].cpu = median(cpu[c]);
    out[c].forward = median(fw[c]);
    out[c].backward = median(bw[c]);
    out[c].boundary = median(bd[c]);
    out[c].hausdorff = median(hd[c]);
    out[c].witness = median(wt[c]);
  }
  return out;
}

/// Times `configs` (one mode at 1 and 2 threads, taking turns) and prints a
/// `BENCH reach.check mode=<mode>` line per configuration, then, when `speedup` is not null,
/// `BENCH reach.speedup<speedup> threads=2 ratio=<first / second>`.
void benchMode(const FootstepReachability& check, const ContactTransition& req, const char* mode,
               const std::vector<ReachConfig>& configs, int repeats, const char* speedup) {
  const std::vector<CaseTimes> times = timeCases(check, req, configs, repeats);
  for (std::size_t c = 0; c < configs.size(); ++c) {
    const CaseTimes& m = times[c];
    const FootstepCheckResult& r = m.result;
    const ReachCounts& n = r.reach.counts;
    const long qps = n.forward_qps + n.backward_qps;
    std::printf(
        "BENCH reach.check mode=%s horizon_s=%.3f ours_s=%.4f min_s=%.4f cpu_s=%.4f "
        "forward_s=%.4f backward_s=%.4f boundary_s=%.4f hausdorff_s=%.4f witness_s=%.4f "
        "samples=%d threads=%d qps=%ld qps_per_s=%.0f kept=%ld reachable=%d budgets=%d "
        "gave_up=%d peak_rss_mib=%.1f\n",
        mode, configs[c].horizon, m.total, m.total_min, m.cpu, m.forward, m.backward, m.boundary,
        m.hausdorff, m.witness, configs[c].budgets.full.initial_samples, configs[c].threads, qps,
        qps / (m.forward + m.backward), n.forward_samples + n.backward_samples, r.reachable ? 1 : 0,
        r.reach.budgets, r.reach.gave_up ? 1 : 0, peakRssMiB());
  }
  if (speedup != nullptr && times.size() == 2)
    std::printf("BENCH reach.speedup%s threads=2 ratio=%.2f\n", speedup,
                times[0].total / times[1].total);
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  // The reach: section of a YAML file (e.g. config/reach_reference.yaml) on top of the
  // defaults (= config/biped.yaml's); budgets.full.initial_samples 0 keeps the configuration's.
  ReachConfig base;
  if (argc > 3) base = ReachConfig::fromYaml(YamlSection::loadFile(argv[3]).section("reach"), base);
  base.threads = 0;
  if (argc > 2 && std::atoi(argv[2]) > 0) base.budgets.full.initial_samples = std::atoi(argv[2]);
  const auto model = RobotModel::fromUrdfFile(std::string(REACH_REPO) + "/urdf/biped.urdf");
  const ContactConfig contact;
  const KinematicFeasibilityConfig kfc;
  // testing/reference_cases.h (test/support/): left stance at (0, 0.1); the right sole 3 cm short
  // of its target (0.25, -0.12) and 2 cm up, moving to stop there at t_f = 0.08 s.
  FootstepPlannerConfig planner_config;
  planner_config.reach = base;
  planner_config.kinematics = kfc;
  const FootstepPlanRequest bench_case = benchSwingCase(model, planner_config, contact);
  ContactTransition req = bench_case;            // the planned step's transition
  req.qdf = Eigen::VectorXd::Zero(model->nq());  // x_f at rest
  const auto analyzer = std::make_shared<ReachabilityAnalyzer>(model, contact, base);
  const FootstepReachability check(analyzer,
                                   std::make_shared<KinematicFeasibility>(model, kfc, contact));

  // Each mode at 1 and 2 threads, the two taking turns (timeCases).
  struct Mode {
    const char* name;
    bool bidirectional;
    bool adaptive;        ///< the shipped adaptive budget (else the full budget alone)
    const char* speedup;  ///< the suffix of its reach.speedup line (nullptr: none)
  };
  const Mode modes[] = {{"bidirectional", true, true, ""},
                        {"full_budget", true, false, " mode=full_budget"},
                        {"forward_only", false, false, nullptr}};
  for (const Mode& mode : modes) {
    std::vector<ReachConfig> configs;
    for (int threads : {1, 2}) {
      ReachConfig cfg = base;
      cfg.quick_pass = mode.adaptive;  // false: budgets.full alone
      cfg.threads = threads;
      if (!mode.bidirectional) cfg.window_start = cfg.window_end = cfg.horizon;
      configs.push_back(cfg);
    }
    benchMode(check, req, mode.name, configs, repeats, mode.speedup);
  }
  // The walk's horizon: x_0 0.2 s before touchdown, the same window, the full budget alone.
  FootstepPlannerConfig walk_config = planner_config;
  walk_config.reach.horizon = 0.2;
  const FootstepPlanRequest walk_case = benchSwingCase(model, walk_config, contact);
  req.q0 = walk_case.q0;
  req.qd0 = walk_case.qd0;
  std::vector<ReachConfig> walk_configs;
  for (int threads : {1, 2}) {
    ReachConfig cfg = walk_config.reach;
    cfg.quick_pass = false;  // budgets.full alone
    cfg.threads = threads;
    walk_configs.push_back(cfg);
  }
  benchMode(check, req, "walk_horizon", walk_configs, repeats, " mode=walk_horizon");
  return 0;
}
