/// \file witness_path.cpp
/// The witness path of a reachability check and its measured violations (see the header).

#include "reach_trajopt/reach/witness_path.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "reach_trajopt/contact/contact_constraint.h"
#include "reach_trajopt/reach/forward_step.h"
#include "reach_trajopt/reach/set_propagation.h"

namespace reach_trajopt {

double PathViolation::max() const {
  return std::max({dynamics, cone, torque, position_limit, velocity_limit, contact,
                   contact_velocity, integration});
}

WitnessPath buildWitnessPath(const ReachContext& ctx, const std::vector<SampleSlice>& forward,
                             const std::vector<SampleSlice>& backward, const SliceComparison& c,
                             bool semi_implicit) {
  // Witness: x_0 -> a (forward chain), b -> x_f (backward chain).
  WitnessPath w;
  const double dt = ctx.config.dt;
  std::vector<std::pair<int, int>> fchain, bchain;
  for (int s = c.forward_slice, i = c.distance.closest_a; s >= 0; i = forward[s].parent[i], --s)
    fchain.push_back({s, i});
  std::reverse(fchain.begin(), fchain.end());
  for (int s = c.backward_slice, i = c.distance.closest_b; s >= 0; i = backward[s].parent[i], --s)
    bchain.push_back({s, i});
  const int L = static_cast<int>(fchain.size() + bchain.size());
  const int n = ctx.n;
  w.q.resize(n, L);
  w.qd.resize(n, L);
  w.output.resize(ctx.ny(), L);
  w.u = Eigen::MatrixXd::Zero(ctx.nu, L - 1);
  w.lambda = Eigen::MatrixXd::Zero(ctx.m(), L - 1);
  w.semi_implicit_step.assign(L - 1, 1);
  w.junction = static_cast<int>(fchain.size()) - 1;
  int k = 0;
  for (const auto& [s, i] : fchain) {
    w.time.push_back(forward[s].time);
    w.q.col(k) =
        sampleConfigurationOf(forward, PropagationDirection::kForward, dt, semi_implicit, s, i);
    w.qd.col(k) = forward[s].qd.col(i);
    w.output.col(k) = forward[s].output.col(i);
    if (k > 0) {
      w.u.col(k - 1) = forward[s].u.col(i);
      w.lambda.col(k - 1) = forward[s].lambda.col(i);
      w.semi_implicit_step[k - 1] = semi_implicit ? 1 : 0;
    }
    ++k;
  }
  for (const auto& [s, i] : bchain) {
    w.time.push_back(backward[s].time);
    w.q.col(k) = sampleConfigurationOf(backward, PropagationDirection::kBackward, dt, true, s, i);
    w.qd.col(k) = backward[s].qd.col(i);
    w.output.col(k) = backward[s].output.col(i);
    if (k < L - 1) {
      w.u.col(k) = backward[s].u.col(i);
      w.lambda.col(k) = backward[s].lambda.col(i);
    }
    ++k;
  }
  const int a = w.junction;
  w.output_gap = (w.output.col(a) - w.output.col(a + 1)).norm();
  w.position_gap = (w.q.col(a) - w.q.col(a + 1)).cwiseAbs().maxCoeff();
  w.velocity_gap = (w.qd.col(a) - w.qd.col(a + 1)).cwiseAbs().maxCoeff();
  measurePath(ctx, w);
  w.valid = true;
  return w;
}

/// Largest violations of the path's states and steps (see PathViolation).
void measurePath(const ReachContext& ctx, WitnessPath& w) {
  const RobotModel& model = *ctx.model;
  Workspace ws(model);
  const int n = ctx.n, nu = ctx.nu;
  const int L = static_cast<int>(w.q.cols());
  Eigen::MatrixXd M(n, n), J(6, n);
  Eigen::VectorXd b(n), r(n);
  ContactConstraintTerms t(n);
  ContactWrenchCone::Matrix C;
  PathViolation& v = w.violation;
  const double dt = ctx.config.dt;
  for (int k = 0; k < L; ++k) {
    const auto q = w.q.col(k);
    const auto qd = w.qd.col(k);
    for (int i : ctx.finite_position)
      v.position_limit = std::max({v.position_limit, q[i] - ctx.q_max[i], ctx.q_min[i] - q[i]});
    for (int i : ctx.finite_velocity)
      v.velocity_limit = std::max(v.velocity_limit, std::abs(qd[i]) - ctx.qd_max[i]);
    model.update(ws, q, qd);
    for (const ContactConstraint& c : ctx.contacts) {
      c.evaluate(model, ws, t);
      v.contact = std::max(v.contact, t.phi.cwiseAbs().maxCoeff());
      v.contact_velocity = std::max(v.contact_velocity, t.phidot.cwiseAbs().maxCoeff());
    }
    if (k + 1 >= L || k == w.junction) continue;
    // Step k -> k+1: eq. (1) at state k.
    model.massMatrix(ws, M);
    model.bias(ws, b);
    const Eigen::VectorXd qdd = (w.qd.col(k + 1) - qd) / dt;
    r = M * qdd + b;
    r.tail(nu) -= w.u.col(k);
    for (int c = 0; c < ctx.nc; ++c) {
      const FrameId f = ctx.contacts[c].frame();
      model.frameJacobian(ws, f, J);
      const Vector6d lam = w.lambda.col(k).segment<6>(6 * c);
      r -= J.transpose() * lam;
      ctx.cone.worldMatrix(model.framePose(ws, f).linear(), C);
      v.cone = std::max(v.cone, -(C * lam).minCoeff());
    }
    v.dynamics = std::max(v.dynamics, r.cwiseAbs().maxCoeff());
    for (int i = 0; i < nu; ++i) v.torque = std::max(v.torque, std::abs(w.u(i, k)) - ctx.u_max[i]);
    Eigen::VectorXd qn(n);
    forwardConfiguration(q, qd, w.qd.col(k + 1), dt, w.semi_implicit_step[k] != 0, qn);
    v.integration = std::max(v.integration, (w.q.col(k + 1) - qn).cwiseAbs().maxCoeff());
  }
}

}  // namespace reach_trajopt
