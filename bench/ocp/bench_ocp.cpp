/// \file bench_ocp.cpp
/// Transition OCP (eq. 22-23) on the shipped biped, three footsteps from a static single
/// support (left stance at (0, 0.1); x_0 = the Sec. III-B stance for a step to (start, -0.1)
/// with the right leg folded, its sole lifted):
///   step_015: right sole to (0.15, -0.1), start 0.15, horizon 0.3 s, strict;
///   step_025: right sole to (0.25, -0.1), start 0.25, horizon 0.3 s, strict;
///   relaxed_055: to (0.55, -0.1), start 0.25, the reachable set's t_f hull at x <= 0.25:
///   relaxed (lands on the hull edge, |eps| = 0.3 m).
/// Prints per case, median over `repeats` solves (default 3):
///   BENCH ocp.<case> ours_s=<median wall s> iters=<gradient evaluations> solves=<SLSQP runs>
///         variables=<n> constraints=<m> violation=<max family> status=<...> ref=none
/// No reference solver is linked: IPOPT (coinor-libipopt-dev) is not installed on this
/// machine, so ref=none and no ratio; the lead can add it as a benchmark-only dependency.
///   bench_ocp [repeats]

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/ocp/stance_reduced_dynamics.h"
#include "reach_trajopt/ocp/transition_ocp.h"
#include "reach_trajopt/planner/kinematic_feasibility.h"

using namespace reach_trajopt;

namespace {

FlatContact contactAt(double x, double y) {
  FlatContact c;
  c.position << x, y, 0.0;
  return c;
}

Eigen::VectorXd ikGuess(const RobotModel& m) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(m.nq());
  q[1] = 0.09;
  q[2] = 1.05;
  for (const std::string side : {"l_", "r_"}) {
    q[m.jointIndex(side + "hip_pitch")] = -0.3;
    q[m.jointIndex(side + "knee")] = 0.6;
    q[m.jointIndex(side + "ankle_pitch")] = -0.3;
  }
  return q;
}

TransitionRequest stepRequest(const std::shared_ptr<const RobotModel>& m, double target_x,
                              double start_x) {
  const KinematicFeasibility kf(m);
  const FlatContact left = contactAt(0.0, 0.1);
  const auto start = kf.check(Side::kLeft, left, contactAt(start_x, -0.1), ikGuess(*m));
  const auto final = kf.check(Side::kLeft, left, contactAt(target_x, -0.1), ikGuess(*m));
  TransitionRequest r;
  r.stance = Side::kLeft;
  r.stance_pose = left.pose();
  r.swing_target = contactAt(target_x, -0.1).pose();
  r.horizon = 0.3;
  r.qf = final.q_f;
  r.qdf = final.qd_f;
  StanceReducedDynamics d(m, m->frameId("l_sole"), r.stance_pose, m->frameId("r_sole"),
                          r.swing_target, 0.0);
  StanceReducedDynamics::Scratch s(d);
  Eigen::VectorXd qa = start.q_f.tail(m->nu());
  qa[m->jointIndex("r_knee") - 6] += 0.5;
  qa[m->jointIndex("r_ankle_pitch") - 6] -= 0.25;
  r.q0.resize(m->nq());
  d.configuration(s, qa, r.q0);
  r.qd0 = Eigen::VectorXd::Zero(m->nq());
  return r;
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
  const Case cases[] = {{"step_015", 0.15, 0.15, false}, {"step_025", 0.25, 0.25, false},
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
    std::sort(times.begin(), times.end());
    std::printf(
        "BENCH ocp.%s ours_s=%.3f iters=%d solves=%d variables=%d constraints=%d "
        "violation=%.2e status=%s ref=none\n",
        c.name, times[times.size() / 2], res.iterations, res.solves, res.variables,
        res.constraints, res.violation.max(), ocpStatusName(res.status));
  }
  return 0;
}
