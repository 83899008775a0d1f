/// push_envelope: the push-recovery envelope of walking policies (walk/push_envelope.h),
/// headless, no ROS master.
///
///   push_envelope [--config config/biped.yaml] [--urdf urdf/biped.urdf]
///                 [--policies baseline,unbounded,kinematic,proposed] [--directions 8]
///                 [--magnitudes 0.2,0.4,0.6] [--seeds 1,2] [--steps 20] [--jobs 2] [--fine]
///                 [--protocol standing|midswing] [--forward-speed V] [--standing]
///                 [--plan-latency pause|measured|SECONDS] [--svg FILE.svg] [--csv FILE.csv]
///                 [--force]
///
/// --policies: walking policies separated by ';' or presets by ',' (a policy with parts:
/// --policies "baseline;kinematic,swing=interpolation"). --fine: magnitudes 0.1 to 1.0 m/s by
/// 0.1. --protocol: the push at t = 0 with the feet still (standing) or at half swing of the
/// 4th step (midswing). --standing: first the standing robot's envelope (the reference). --jobs:
/// walks run side by side, each on one thread. --plan-latency: walk.plan_latency of every walk
/// (measured: the plan's wall time; side by side walks would lengthen each other's, so --jobs 1);
/// its BENCH lines then end with plan_latency=<it>. Prints one line per walk and one `BENCH
/// walk.envelope preset=<p> protocol=<standing|midswing> pushes=N survived=K max_lateral_mps=..
/// max_forward_mps=..` per policy; --svg writes the polar figure, --csv every walk. A sweep of more
/// than 20000 footsteps in all is refused unless --force, and --steps whose walks cannot end within
/// the config's walk.max_sim_time is refused. Exit status: 0 ran, 2 bad input.

#include "reach_trajopt/walk/push_envelope.h"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "reach_trajopt/common/cli_args.h"
#include "reach_trajopt/common/cli_options.h"

using namespace reach_trajopt;

namespace {

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string t; std::getline(ss, t, sep);) out.push_back(t);
  return out;
}

// "baseline,proposed" (presets), "baseline;proposed" or "baseline;kinematic,swing=interpolation"
// (policies; a single policy with parts needs no ';').
std::vector<WalkingPolicy> parsePolicies(const std::string& text) {
  std::vector<WalkingPolicy> out;
  const bool policies = text.find_first_of(";=") != std::string::npos;
  for (const std::string& spec : split(text, policies ? ';' : ','))
    out.push_back(WalkingPolicy::parse(spec));
  if (out.empty()) throw RequestError("--policies: no policy given");
  return out;
}

/// The tool's options (--help prints them).
const CliTool kTool("push_envelope", "",
                    "The push-recovery envelope of walking policies: one line per walk, one BENCH\n"
                    "walk.envelope line per policy.",
                    {configOption("the robot and its parameters"),
                     urdfOption(),
                     {"--policies", "LIST", "walking policies separated by ';', or presets by ','",
                      "baseline,unbounded,kinematic,proposed"},
                     {"--directions", "N", "push directions, 1..64", "8"},
                     {"--magnitudes", "LIST", "push magnitudes [m/s], increasing", "0.2,0.4,0.6"},
                     {"--fine", "", "magnitudes 0.1 to 1.0 m/s by 0.1 (instead of --magnitudes)",
                      ""},
                     {"--protocol", "P",
                      "standing (push at t = 0, feet still) or midswing (at half swing of the "
                      "4th step)",
                      "standing"},
                     {"--forward-speed", "V", "commanded forward speed of the walks [m/s]", "0"},
                     {"--standing", "", "first the standing robot's envelope (the reference)", ""},
                     {"--seeds", "LIST", "seeds of each push", "1,2"},
                     {"--steps", "N", "steps per walk, 1..1000", "20"},
                     {"--jobs", "N", "walks run side by side, each on one thread", "2"},
                     {"--plan-latency", "L",
                      "when a step's plan takes effect: pause, measured (its wall time later; "
                      "run with --jobs 1) or a latency in seconds (walk.plan_latency)",
                      ""},
                     {"--svg", "FILE.svg", "write the polar figure", ""},
                     {"--csv", "FILE.csv", "write every walk", ""},
                     {"--force", "", "run a sweep over 20000 footsteps in all", ""}});

/// The most footsteps one sweep may walk without --force (policies x directions x magnitudes
/// x seeds x steps; the bench's default sweep is 3840, --fine 10240; a proposed footstep
/// costs about a second of wall time).
constexpr long long kMaxSweepFootsteps = 20000;

/// Refuses a sweep whose walks cannot end within walk.max_sim_time (the time limit would be
/// counted as a fall), and, without --force, one over kMaxSweepFootsteps.
void requireFeasibleSweep(const PushGrid& grid, const WalkConfig& walk, std::size_t policies,
                          bool force, const std::string& config_path) {
  const double period = walk.single_support_duration + walk.double_support_duration;
  const double needed = walk.settle_duration + grid.steps * period;
  if (needed > walk.max_sim_time) {
    std::ostringstream os;
    os << "--steps " << grid.steps << ": a walk of " << grid.steps << " steps needs " << needed
       << " s of simulated time (settle + steps x " << period
       << " s), over walk.max_sim_time = " << walk.max_sim_time << " s of " << config_path
       << " (it would end every walk as a fall): ask fewer steps or raise walk.max_sim_time";
    throw RequestError(os.str());
  }
  const long long walks = static_cast<long long>(policies) * grid.directions *
                          static_cast<long long>(grid.magnitudes.size()) *
                          static_cast<long long>(grid.seeds.size());
  const long long footsteps = walks * grid.steps;
  if (footsteps > kMaxSweepFootsteps && !force) {
    std::ostringstream os;
    os << "the sweep is " << policies << " policies x " << grid.directions << " directions x "
       << grid.magnitudes.size() << " magnitudes x " << grid.seeds.size() << " seeds = " << walks
       << " walks of " << grid.steps << " steps: " << footsteps << " footsteps, over the limit of "
       << kMaxSweepFootsteps
       << " (about a second each for a checking policy): narrow --policies, --directions, "
          "--magnitudes, --seeds or --steps, or add --force";
    throw RequestError(os.str());
  }
}

/// The push grid of the command line, validated. \throws RequestError naming the option.
PushGrid pushGrid(const CliArgs& args) {
  PushGrid grid;
  grid.directions =
      static_cast<int>(parseIntOption("--directions", args.value("--directions"), 1, 64));
  if (args.given("--fine") && args.given("--magnitudes"))
    throw RequestError("--fine and --magnitudes: give one of them");
  grid.magnitudes.clear();
  if (args.given("--fine"))
    grid.magnitudes = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
  else
    for (const std::string& m : split(args.value("--magnitudes"), ','))
      grid.magnitudes.push_back(parseDoubleOption("--magnitudes", m, 1e-3, 10.0));
  grid.seeds.clear();
  for (const std::string& s : split(args.value("--seeds"), ','))
    grid.seeds.push_back(static_cast<unsigned>(parseIntOption("--seeds", s, 0, 4294967295LL)));
  grid.steps = static_cast<int>(parseIntOption("--steps", args.value("--steps"), 1, 1000));
  const std::string protocol = args.value("--protocol");
  if (protocol == "midswing")
    grid.protocol = PushGrid::Protocol::kMidswing;
  else if (protocol != "standing")
    throw RequestError("--protocol: 'standing' or 'midswing', got '" + protocol + "'");
  grid.forward_speed =
      parseDoubleOption("--forward-speed", args.value("--forward-speed"), -2.0, 2.0);
  grid.validate();
  return grid;
}

/// The output files, opened before hours of walking; not open when not asked for.
struct Outputs {
  std::ofstream svg, csv;
};

Outputs openOutputs(const CliArgs& args) {
  Outputs out;
  const std::string svg_path = args.value("--svg"), csv_path = args.value("--csv");
  if (!svg_path.empty()) {
    out.svg.open(svg_path);
    if (!out.svg) throw ReachError("cannot write --svg file '" + svg_path + "'");
  }
  if (!csv_path.empty()) {
    out.csv.open(csv_path);
    if (!out.csv) throw ReachError("cannot write --csv file '" + csv_path + "'");
    out.csv << "policy,direction_deg,magnitude_mps,push_x_mps,push_y_mps,seed,fell,steps,"
               "repeated,wall_s,end\n";
  }
  return out;
}

/// The walks of one policy's envelope as CSV rows.
void writeCsv(std::ostream& csv, const std::string& name, const PushGrid& grid,
              const PushEnvelope& env) {
  for (const PushWalk& w : env.walks)
    csv << name << "," << grid.angle(w.direction) * 180.0 / M_PI << ","
        << grid.magnitudes[w.magnitude] << "," << w.push.x() << "," << w.push.y() << ","
        << grid.seeds[w.seed] << "," << w.fell << "," << w.steps << "," << w.repeated << ","
        << w.wall_s << ",\"" << w.end_reason << "\"\n";
}

/// One policy's envelope: a line per walk as it ends, then its BENCH line.
PushEnvelope sweepPolicy(const WalkSetup& setup, const std::string& urdf,
                         const WalkingPolicy& policy, const PushGrid& grid, int jobs) {
  const PushEnvelope env = sweepPushes(setup, urdf, policy, grid, jobs, [&](const PushWalk& w) {
    std::printf("walk %s push=(%.3f, %.3f) seed=%u steps=%d fell=%s wall_s=%.1f end=%s\n",
                grid.standing ? "standing" : policy.name.c_str(), w.push.x(), w.push.y(),
                grid.seeds[w.seed], w.steps, w.fell ? "yes" : "no", w.wall_s, w.end_reason.c_str());
    std::fflush(stdout);
  });
  std::printf("%s\n", env.benchLine().c_str());
  std::fflush(stdout);
  return env;
}

}  // namespace

int main(int argc, char** argv) {
  return kTool.run(argc, argv, [](const CliArgs& args) {
    if (!args.positional().empty())
      throw RequestError("unknown argument '" + args.positional()[0] + "'");
    const PushGrid grid = pushGrid(args);
    const int jobs =
        static_cast<int>(parseIntOption("--jobs", args.value("--jobs"), 1, hardwareThreads()));
    const std::vector<WalkingPolicy> list = parsePolicies(args.value("--policies"));
    WalkSetup setup = WalkSetup::fromYamlFile(args.value("--config"));
    if (args.given("--plan-latency"))
      setup.walk.setPlanLatency(args.value("--plan-latency"), "--plan-latency");
    requireFeasibleSweep(grid, setup.walk, list.size(), args.given("--force"),
                         args.value("--config"));
    Outputs out = openOutputs(args);
    std::vector<PushEnvelope> envelopes;
    if (args.given("--standing")) {
      PushGrid standing = grid;
      standing.standing = true;
      envelopes.push_back(sweepPolicy(setup, args.value("--urdf"), list.front(), standing, jobs));
      if (out.csv.is_open()) writeCsv(out.csv, "standing", grid, envelopes.back());
    }
    for (const WalkingPolicy& policy : list) {
      envelopes.push_back(sweepPolicy(setup, args.value("--urdf"), policy, grid, jobs));
      if (out.csv.is_open()) writeCsv(out.csv, policy.name, grid, envelopes.back());
    }
    if (out.svg.is_open()) out.svg << envelopeSvg(envelopes);
    return 0;
  });
}
