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
  return std::max({maxWithoutContact(), contact, contact_velocity});
}

double PathViolation::maxWithoutContact() const {
  return std::max(
      {dynamics, cone, torque, position_limit, velocity_limit, integration, ground, leg_clearance});
}

std::vector<std::pair<int, int>> chainToRoot(const std::vector<SampleSlice>& slices, int slice,
                                             int index) {
  std::vector<std::pair<int, int>> chain;
  for (int s = slice, i = index; s >= 0; i = slices[s].parent[i], --s) chain.push_back({s, i});
  return chain;
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
    if (ctx.swing_frame >= 0)
      v.ground = std::max(
          v.ground, ctx.ground_height - model.framePose(ws, ctx.swing_frame).translation().z());
    if (ctx.leg_margin > -HUGE_VAL)
      v.leg_clearance =
          std::max(v.leg_clearance, ctx.leg_margin - ctx.legs.closest(model, ws).distance);
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
