/// \file junction_bridge.cpp
/// The QP-controlled segment that closes a witness path's junction (see the header).

#include "reach_trajopt/reach/junction_bridge.h"

#include <algorithm>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

namespace {
/// The gap is closed this long before t_f [s]; then the bridge follows the chain (see header).
constexpr double kSettleTime = 0.02;
}  // namespace

ForwardStepCost junctionBridgeCost() {
  ForwardStepCost c;
  c.w_qdd = 1.0;
  c.w_du = 1e-8;
  c.w_lambda = 1e-10;
  c.bridge = true;
  return c;
}

BackwardChain hermiteChain(const Eigen::Ref<const Eigen::VectorXd>& q_a,
                           const Eigen::Ref<const Eigen::VectorXd>& qd_a,
                           const Eigen::Ref<const Eigen::VectorXd>& q_f,
                           const Eigen::Ref<const Eigen::VectorXd>& qd_f, int N, double dt,
                           const Eigen::Ref<const Eigen::VectorXd>& u_nominal) {
  const double T = N * dt;
  BackwardChain c;
  c.q.resize(q_a.size(), N + 1);
  c.qd.resize(q_a.size(), N + 1);
  c.u = u_nominal.replicate(1, N);
  for (int k = 0; k <= N; ++k) {
    const double s = static_cast<double>(k) / N;
    const double h00 = 2 * s * s * s - 3 * s * s + 1, h10 = s * s * s - 2 * s * s + s;
    const double h01 = -2 * s * s * s + 3 * s * s, h11 = s * s * s - s * s;
    const double d00 = 6 * s * s - 6 * s, d10 = 3 * s * s - 4 * s + 1;
    const double d01 = -6 * s * s + 6 * s, d11 = 3 * s * s - 2 * s;
    c.q.col(k) = h00 * q_a + (T * h10) * qd_a + h01 * q_f + (T * h11) * qd_f;
    c.qd.col(k) = (d00 / T) * q_a + d10 * qd_a + (d01 / T) * q_f + d11 * qd_f;
  }
  return c;
}

BridgeSegment bridgeJunction(const ReachContext& ctx, ForwardStep& step,
                             const Eigen::Ref<const Eigen::VectorXd>& q_a,
                             const Eigen::Ref<const Eigen::VectorXd>& qd_a,
                             const BackwardChain& chain) {
  const int n = ctx.n, nu = ctx.nu;
  const int N = static_cast<int>(chain.q.cols()) - 1;
  if (N < 2 || chain.qd.cols() != N + 1 || chain.u.cols() != N || chain.q.rows() != n ||
      chain.qd.rows() != n || chain.u.rows() != nu)
    throw ReachError(
        "bridgeJunction: the backward chain needs n_q x (N + 1) states and "
        "n_u x N torques, N >= 2");
  const double dt = ctx.config.dt;
  BridgeSegment seg;
  seg.q.resize(n, N + 1);
  seg.qd.resize(n, N + 1);
  seg.u.setZero(nu, N);
  seg.lambda.setZero(ctx.m(), N);
  seg.output.resize(ctx.ny(), N + 1);
  seg.q.col(0) = q_a;
  seg.qd.col(0) = qd_a;
  Eigen::VectorXd y_rate(ctx.ny()), qdd_des(n);
  ctx.model->update(step.workspace(), q_a, qd_a);
  ctx.output(step.workspace(), seg.output.col(0), y_rate);
  const double settle = std::min(kSettleTime, 0.5 * N * dt);
  const auto& q_f = chain.q.col(N);
  const auto& qd_f = chain.qd.col(N);
  for (int k = 0; k < N; ++k) {
    const auto q = seg.q.col(k);
    const auto qd = seg.qd.col(k);
    if (k >= N - 2) {
      // Discrete deadbeat onto x_f: two steps with accelerations a1, a2 end at (q_f, qd_f)
      // when a1 + a2 = A and (semi-implicit) 2 a1 + a2 = B, (explicit) a1 = B; the last step
      // is then a2 = A.
      const Eigen::VectorXd A = (qd_f - qd) / dt;
      if (k == N - 1) {
        qdd_des = A;
      } else {
        const Eigen::VectorXd B = (q_f - q - 2.0 * dt * qd) / (dt * dt);
        qdd_des = ctx.config.semiImplicit() ? Eigen::VectorXd(B - A) : B;
      }
    } else {
      // The chain's acceleration plus the start of the cubic that takes the gap to (0, 0) in
      // T_go, re-planned from the actual gap at every step.
      const double T_go = std::max((N - k) * dt - settle, 3.0 * dt);
      qdd_des = (chain.qd.col(k + 1) - chain.qd.col(k)) / dt -
                (6.0 / (T_go * T_go)) * (q - chain.q.col(k)) -
                (4.0 / T_go) * (qd - chain.qd.col(k));
    }
    if (!step.setParent(q, qd)) return seg;
    if (!step.trackChild(chain.u.col(k), qdd_des, seg.q.col(k + 1), seg.qd.col(k + 1),
                         seg.output.col(k + 1), y_rate, seg.u.col(k), seg.lambda.col(k)))
      return seg;
    seg.steps_done = k + 1;
  }
  return seg;
}

}  // namespace reach_trajopt
