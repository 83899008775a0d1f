#pragma once
/// \file junction_bridge.h
/// Closes the junction of a witness path (docs/method.md Sec. 4.5). A forward sample a at
/// time t_a (reached from x_0) and a backward sample b of the same time (from which x_f is
/// reached) are different states: the path x_0 -> a | b -> x_f jumps at a | b. The bridge
/// replaces b -> x_f by a QP-controlled segment that starts at a and ends on x_f.
///
///   gap         e = q - q_c(t), de = qd - qd_c(t) against the backward chain b -> x_f
///               (states (q_c, qd_c), torques u_c; it ends on x_f), T_r = t_f - t;
///   each 1 ms   qdd_des = qdd_c - 6 e / T_go^2 - 4 de / T_go: the start of the cubic that
///               takes the gap to (0, 0) in T_go = max(T_r - 20 ms, 3 dt), re-planned from
///               the actual state at every step (a time-to-go feedback: gentle at first; over
///               the last 20 ms it follows the chain with deadbeat-like gains, the error
///               shrinking by about 0.57 per step), and the forward QP (15) in bridge mode
///               (ForwardStepCost::bridge) with the cost |qdd - qdd_des|^2
///               (ForwardStep::trackChild) under eq. (1), (5), (8), the torque, position and
///               velocity limits and the ground;
///   last steps  qdd_des puts (q, qd) on x_f in two steps (discrete deadbeat), same QP.
///
/// Measured on the walk's checks: the QP follows qdd_des closely except where a stance cone
/// binds; the base's velocity gap between the two sets (about 1 rad/s of pelvis rotation)
/// is what most often leaves x(t_f) off x_f.
///
/// The segment satisfies the constraints by construction; how close it ends to x_f is what
/// the certificate (witness_certificate.h) checks.

#include <Eigen/Core>

#include "reach_trajopt/reach/forward_step.h"
#include "reach_trajopt/reach/reach_context.h"

namespace reach_trajopt {

/// A state path of the bridge: states 0..N at t_a + k dt (state 0 = a), steps 0..N-1.
struct BridgeSegment {
  Eigen::MatrixXd q, qd;      ///< n_q x (N + 1)
  Eigen::MatrixXd u, lambda;  ///< n_u x N, 6 n_c x N: torques and wrenches of each step
  Eigen::MatrixXd output;     ///< n_y x (N + 1)
  int steps_done = 0;         ///< steps whose QP succeeded (N when the bridge completed)
  bool completed() const { return steps_done == static_cast<int>(u.cols()); }
};

/// The backward chain b -> x_f: states 0..N (b at t_a, ..., x_f at t_f) and the torques of its
/// steps 0..N-1.
struct BackwardChain {
  Eigen::MatrixXd q, qd;  ///< n_q x (N + 1)
  Eigen::MatrixXd u;      ///< n_u x N
};

/// The cubic Hermite from (q_a, qd_a) to (q_f, qd_f) over N steps of dt as a chain to track
/// (the direct bridge, for when tracking the backward chain fails: e.g. a chain of bang-bang
/// draws leaves no torque to close a gap); its torques are u_nominal.
BackwardChain hermiteChain(const Eigen::Ref<const Eigen::VectorXd>& q_a,
                           const Eigen::Ref<const Eigen::VectorXd>& qd_a,
                           const Eigen::Ref<const Eigen::VectorXd>& q_f,
                           const Eigen::Ref<const Eigen::VectorXd>& qd_f, int N, double dt,
                           const Eigen::Ref<const Eigen::VectorXd>& u_nominal);

/// Runs the bridge from (q_a, qd_a) along `chain`.
/// \param step  a forward step of ctx made with junctionBridgeCost()
/// \returns the segment; it stops early (steps_done < N) where a QP has no solution.
/// \throws ReachError when the chain's sizes are inconsistent or N < 2.
BridgeSegment bridgeJunction(const ReachContext& ctx, ForwardStep& step,
                             const Eigen::Ref<const Eigen::VectorXd>& q_a,
                             const Eigen::Ref<const Eigen::VectorXd>& qd_a,
                             const BackwardChain& chain);

/// The QP weights of a bridge step: the acceleration error dominates, torque changes and
/// wrenches only regularize.
ForwardStepCost junctionBridgeCost();

}  // namespace reach_trajopt
