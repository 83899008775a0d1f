#pragma once
/// \file transition_ocp.h
/// The transition optimal control problem of eq. (22)-(23), solved with NLopt's LD_SLSQP:
/// from x_0 in single support (SS-L or SS-R) to x_f in double support over a fixed horizon,
///   min  sum_j u_j^T Qu u_j + lambda_j^T Ql lambda_j + (x_j - x_f)^T Qx (x_j - x_f)
///   s.t. eq. (1); stance contact (5) and cone (8); new contact at t_f: phi_2 = phidot_2 =
///        phiddot_2 = 0 and its cone; |u| <= u_max; x(t_0) = x_0, x(t_f) = x_f; the swing sole
///        inside each time slice's reachable-set hull.
/// The transcription (joint B-splines, exact stance contact, torques and stance wrenches by
/// inverse dynamics) is explained in transition_nlp.h.
///
/// Relaxation for an unreachable foothold (docs/method.md Sec. 5): x(t_f) = x_f is dropped and the
/// new contact becomes phi_2 - eps = 0 with eps = [eps_x, eps_y, 0, 0, 0, 0] and cost
/// w_eps |eps|^2: the swing sole lands at the closest point allowed by the dynamics, the limits
/// and the reachable-set hulls, and the result is flagged relaxed. By default the landing also
/// keeps the Sec. III-B posture (base upright at terminal_pelvis_height), so it is a
/// kinematically feasible stance; without that the robot may crouch to reach farther.
///
/// Procedure: validate the request; warm start by the SPQR fit of the seed path; SLSQP; sample
/// the result at output_dt and re-check every constraint family with the full model
/// (transition_check.h); if some cone, torque bound or hull is violated between NLP samples, add
/// those times and re-solve from the last solution (at most max_refinements times; when SLSQP's
/// answer violates its own rows by over 100x the tolerance, more rows cannot help and it goes on
/// only while each round halves the violation, as a restart does). Status:
/// converged (strict) or relaxed when the re-check passes (every family <= tolerance), else
/// failed with the family, the amount and NLopt's code; a wall-clock time_limit bounds it all
/// (and, for the anytime solve, the caller's deadline: see solve()).

#include <chrono>
#include <memory>

#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/ocp/ocp_config.h"
#include "reach_trajopt/ocp/ocp_progress.h"
#include "reach_trajopt/ocp/transition_request.h"
#include "reach_trajopt/ocp/transition_result.h"

namespace reach_trajopt {

/// Eq. (22)-(23) for one contact transition (see file comment). Immutable; solve() is
/// thread-safe (each call builds its own NLP and workspaces).
class TransitionOcp {
 public:
  /// Throws ReachError on an invalid config, a fixed-base model or unknown sole frames.
  TransitionOcp(std::shared_ptr<const RobotModel> model, const TransitionOcpConfig& config = {},
                const ContactConfig& contact = {});

  /// Solves one request. Throws ReachError on bad input (see validate()); solver trouble is a
  /// result with status kFailed and a reason, never an exception. `progress` (ocp_progress.h;
  /// may be empty) hears of every gradient evaluation; \throws ReachCancelled when it
  /// returns false.
  TransitionResult solve(const TransitionRequest& request,
                         const OcpProgressCallback& progress = {}) const;

  /// Anytime: the same with a deadline (e.g. the step's: the plan is needed before the foot
  /// lands), the earlier of it and time_limit after the call. At the deadline the run stops
  /// between two SLSQP iterations with time left to sample and re-check the answer: the last
  /// iterate, or, when that one breaks an NLP row, the lowest-cost iterate that held them all.
  /// Its 1 ms re-check decides the status as always: converged (or relaxed) only when every
  /// family is within tolerance, with the reason "time limit reached at a feasible iterate (not
  /// optimal)"; otherwise failed, "time limit reached: ...". A deadline already past gives a
  /// failed result at once.
  TransitionResult solve(const TransitionRequest& request, const OcpProgressCallback& progress,
                         std::chrono::steady_clock::time_point deadline) const;

  /// RelaxationMode::kAuto's second half for a caller that decides after the strict solve
  /// whether it needs it: the relaxed problem of `request` after `strict` (that request's
  /// strict solve, failed), merged as solve() merges them under kAuto (iterations and solves
  /// summed, the reason "strict problem failed (..); relaxed: .."), within `deadline` and
  /// time_limit from this call; `strict` itself when it ran out of time.
  TransitionResult solveRelaxedAfter(const TransitionRequest& request,
                                     const TransitionResult& strict,
                                     const OcpProgressCallback& progress,
                                     std::chrono::steady_clock::time_point deadline) const;

  /// Throws ReachError naming the problem: wrong sizes or non-finite values, a horizon that is
  /// not positive or shorter than two output samples, slice / seed times outside [0, horizon],
  /// malformed hulls or seeds, invalid poses, x_0 off its stance contact (|phi_s| or
  /// |phidot_s| > input_tolerance) or, for RelaxationMode::kStrict, x_f off its two contacts.
  void validate(const TransitionRequest& request) const;

  /// True when x_f holds both contacts within input_tolerance (strict problem well posed).
  bool finalStateOnContacts(const TransitionRequest& request) const;

  const TransitionOcpConfig& config() const { return config_; }
  const ContactConfig& contact() const { return contact_; }
  const RobotModel& model() const { return *model_; }

 private:
  /// A solve's deadline: the earlier of the caller's and time_limit after `start`.
  std::chrono::steady_clock::time_point deadlineOf(
      std::chrono::steady_clock::time_point start,
      std::chrono::steady_clock::time_point step_deadline) const;
  /// kAuto after the strict solve `strict` failed: see solveRelaxedAfter().
  TransitionResult relaxedAfter(const TransitionRequest& request, const TransitionResult& strict,
                                std::chrono::steady_clock::time_point deadline,
                                const OcpProgressCallback& progress) const;
  TransitionResult solveMode(const TransitionRequest& request, bool relaxed,
                             std::chrono::steady_clock::time_point deadline,
                             const OcpProgressCallback& progress) const;

  std::shared_ptr<const RobotModel> model_;
  TransitionOcpConfig config_;
  ContactConfig contact_;
};

}  // namespace reach_trajopt
