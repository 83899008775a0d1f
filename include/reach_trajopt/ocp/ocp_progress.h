#pragma once
/// \file ocp_progress.h
/// Progress of a transition OCP solve (transition_ocp.h) while it runs, for a caller that
/// reports it (an action server's feedback) or cancels a solve that is no longer wanted.
/// Reported after each gradient evaluation of SLSQP (one per QP subproblem it solves), from the
/// thread that called solve(); the solution does not depend on whether anyone listens.

#include <functional>

namespace reach_trajopt {

/// Where a solve is.
struct OcpProgress {
  bool relaxed = false;  ///< the problem being solved: strict or relaxed (eq. 23)
  int evaluations = 0;   ///< gradient evaluations (SLSQP's QP subproblems) of this solve so far
};

/// Called with each OcpProgress; returns false to cancel the solve (solve() then throws
/// ReachCancelled, common/cancelled.h).
using OcpProgressCallback = std::function<bool(const OcpProgress&)>;

}  // namespace reach_trajopt
