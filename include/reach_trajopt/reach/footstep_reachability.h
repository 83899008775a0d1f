#pragma once
/// \file footstep_reachability.h
/// The check of one planned footstep as the paper runs it (Sec. III-B then III-C/D): first the
/// kinematic feasibility of the new foothold (joint-limited IK with both soles held); if it
/// fails, the step is unreachable ("we cannot obtain a reachable path toward the next mode if
/// the planned contact location is kinematically infeasible"); otherwise its q_f with
/// qd_f = 0 (or a given touchdown velocity) is x_f of the bidirectional reachability check from
/// the current state x_0 in single support. An x_f derived so (no touchdown velocity given)
/// whose joint velocities exceed their limits cannot be reached: the step is unreachable, not
/// a bad request (a touchdown velocity given outside the limits is one).

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "reach_trajopt/contact/contact_transition.h"
#include "reach_trajopt/planner/kinematic_feasibility.h"
#include "reach_trajopt/reach/reachability_analyzer.h"
#include "reach_trajopt/reach/reachable_slice.h"

namespace reach_trajopt {

/// The one result of the footstep check (FootstepReachability, checkFootstep of
/// step/footstep_check.h, reachability_node's check_footstep): the kinematic stage and, when it
/// passed, the reachability result and the OCP's hulls of its forward set. From another process
/// `reach` holds the verdict, the window's times, distances and overlaps and the witness path
/// (time, q, gaps, violations), not the sets.
struct FootstepCheckResult {
  bool reachable = false;
  bool kinematically_feasible = false;
  std::string reason;                     ///< why (either stage)
  KinematicFeasibilityResult kinematics;  ///< q_f and the IK residuals
  Eigen::VectorXd qdf;                    ///< the touchdown velocity used (size n_q)
  ReachResult reach;                      ///< empty unless kinematically feasible
  /// The OCP's slices of the forward set (eq. 23, step/reachable_set_constraint.h), grown by the
  /// pass's constraint_margin: filled by checkFootstep for a kinematically feasible foothold
  /// whose reachability was checked; empty otherwise (and from FootstepReachability itself).
  std::vector<ReachableSlice> set_constraint;
};

/// The reachability problem (13)-(21) of a contact transition whose foothold passed the
/// kinematic stage, x_f = (q_f, qd_f) (size n_q each): mode m_k = SS-stance from the
/// transition's x_0, the held contact where the transition says, the target the moving sole's
/// next contact. (The transition's qf, qdf and touchdown are not read: x_f is given.)
ReachProblem footstepProblem(const ContactTransition& transition, const Eigen::VectorXd& q_f,
                             const Eigen::VectorXd& qd_f);

/// @brief Kinematic feasibility (III-B) followed by the reachability check (13)-(21).
class FootstepReachability {
 public:
  FootstepReachability(std::shared_ptr<const ReachabilityAnalyzer> analyzer,
                       std::shared_ptr<const KinematicFeasibility> kinematics);
  /// \throws ReachError on bad input (see ReachabilityAnalyzer::check and
  ///     KinematicFeasibility::check); an infeasible foothold is a result, not an error.
  FootstepCheckResult check(const ContactTransition& request) const;
  /// \param progress  the reachability check's (reach_progress.h; may be empty)
  FootstepCheckResult check(const ContactTransition& request, const ReachConfig& config,
                            const ReachProgressCallback& progress = {}) const;
  /// Same with one pass of the check (ReachabilityAnalyzer::checkPass) instead of the check's
  /// pass schedule: one pass of the step planner.
  FootstepCheckResult checkPass(const ContactTransition& request, const ReachConfig& config,
                                const CheckPass& pass,
                                const ReachProgressCallback& progress = {}) const;

  /// The kinematic stage alone: kinematics, kinematically_feasible, qdf (the touchdown
  /// velocity x_f would have) and reason; reach stays empty, reachable false.
  FootstepCheckResult kinematicStage(const ContactTransition& request) const;

  const ReachabilityAnalyzer& analyzer() const { return *analyzer_; }

 private:
  /// qd_f: the request's, else the posture qf moving with the touchdown CoM velocity.
  Eigen::VectorXd touchdownVelocity(const ContactTransition& request,
                                    const Eigen::VectorXd& qf) const;
  /// False, with the reason in `out`, when the derived x_f's velocity (out.qdf) exceeds a
  /// joint's velocity limit by more than config.limit_tolerance.
  bool derivedTouchdownWithinVelocityLimits(const ContactTransition& request,
                                            const ReachConfig& config,
                                            FootstepCheckResult& out) const;
  std::shared_ptr<const ReachabilityAnalyzer> analyzer_;
  std::shared_ptr<const KinematicFeasibility> kinematics_;
};

}  // namespace reach_trajopt
