#pragma once
/// \file walking_policy.h
/// What the stepping loop of Sec. IV does with the footstep the TVR planner proposes, as four
/// independent parts, so that one run changes one of them:
///   - heuristic bounds on the TVR step (Sec. IV-A) on or off;
///   - the foothold check, `check_horizon` before the nominal touchdown: none, kinematic
///     (Sec. III-B only) or reachability (the certified check, Sec. III-B to III-D);
///   - what a failed check does:
///       clip_to_bounds: the TVR step clipped to the heuristic bounds, interpolated swing;
///       nearest_feasible: the nearest foothold that passes: for an infeasible foothold the
///         nearest kinematically feasible one (planner/nearest_feasible_foothold.h, its OCP
///         strict then relaxed); for an unreachable one the relaxed OCP's closest reachable
///         foothold (Sec. III-E);
///       relaxed_ocp: the relaxed OCP of Sec. III-E toward the target in both cases (an
///         infeasible target too: the IK's best posture as x_f);
///       nearest_reachable: the nearest foothold the policy's check passes, checked before it
///         is taken: with the reachability check, the nearest ring point it certifies with a
///         strict trajectory (step/footstep_transition_planner.h,
///         InfeasibleFootholdPolicy::kNearestReachable; none within
///         nearest_foothold.max_checked candidates: nearest_feasible's answer, reported as
///         such); with the kinematic check, nearest_feasible's ring search;
///   - the swing: interpolated (swing_trajectory.h) or the OCP's trajectory with its
///     feed-forward (needs a check: the OCP's x_f is the check's IK posture).
/// A check "fails" when the foothold is kinematically infeasible, or, for the reachability
/// check, when it is not shown reachable (no bridged witness and no converged local solve).
///
/// With an OCP swing and a check that passed, the strict OCP's trajectory is tracked (a strict
/// OCP that fails gets the relaxed one, as for an unreachable foothold).
///
/// Presets: baseline (Sec. IV-A: bounds, no check, interpolated swing), unbounded (TVR
/// alone), kinematic (TVR + kinematic check + nearest passing, OCP swing) and proposed
/// (Sec. IV-B: TVR + reachability check + nearest reachable, OCP swing): kinematic and proposed
/// differ in the reachability check only (its verdict, its sets in the OCP, eq. 23, and its
/// witness as the OCP's seed). The paper's planner never proposes an infeasible foothold; for
/// ours the proposed preset takes the ring search, because the relaxed OCP toward an infeasible
/// target (on_fail=relaxed_ocp) lands the swing sole on the stance foot (docs/walking.md).
/// Written "<preset>[,part=value...]", e.g. "kinematic,swing=interpolation".

#include <string>
#include <vector>

namespace reach_trajopt {

struct FootstepTransition;

/// @brief One walking policy: bounds, foothold check, failure handling, swing source.
struct WalkingPolicy {
  enum class FootholdCheck { kNone, kKinematic, kReachability };
  enum class OnFailedCheck { kClipToBounds, kNearestFeasible, kRelaxedOcp, kNearestReachable };
  enum class SwingSource { kInterpolation, kOcp };

  /// The preset it was made from, "custom" when a part was changed.
  std::string name = "baseline";
  bool heuristic_bounds = true;
  FootholdCheck check = FootholdCheck::kNone;
  OnFailedCheck on_failed_check = OnFailedCheck::kClipToBounds;  ///< unused without a check
  SwingSource swing = SwingSource::kInterpolation;

  /// The presets' names, in the order of the comparison: baseline, unbounded, kinematic,
  /// proposed.
  static const std::vector<std::string>& presetNames();
  /// A preset by name. \throws RequestError listing the presets.
  static WalkingPolicy preset(const std::string& name);
  /// "<preset>[,part=value...]" with parts bounds=on|off, check=none|kinematic|reachability,
  /// on_fail=clip_to_bounds|nearest_feasible|relaxed_ocp|nearest_reachable,
  /// swing=interpolation|ocp; validated.
  /// \throws RequestError naming the bad token.
  static WalkingPolicy parse(const std::string& spec);
  /// "clip_to_bounds", "nearest_feasible" or "relaxed_ocp" (the on_fail part's values).
  static const char* actionName(OnFailedCheck action);
  /// "bounds=on check=none on_fail=- swing=interpolation" (the WALK line's definition).
  std::string definition() const;
  /// For a step whose check failed (`step` the planner's answer): true when the loop takes the
  /// TVR step clipped to the heuristic bounds, reached by interpolation. That is the
  /// clip_to_bounds fallback, and the last resort of every other one when it found nothing,
  /// where the swing would otherwise go to the very foothold the check rejected: no usable
  /// plan for the target itself; or, with the reachability check, an uncertified stand-in for
  /// the target (a ring point, or the relaxed OCP's landing moved from the ring point that
  /// stands in for a kinematically infeasible target): it lies at the edge of the leg's reach
  /// beside the rejected target, and the relaxed landing there only guesses (docs/walking.md,
  /// "the last resort").
  bool clipsFailedStep(const FootstepTransition& step) const;
  /// \throws ConfigError on a combination the loop cannot run (an OCP swing without a check).
  void validate() const;
  bool checksFoothold() const { return check != FootholdCheck::kNone; }
  /// The loop needs the transition OCP: for the swing, or for a failed check's relaxed OCP.
  bool solvesOcp() const {
    return checksFoothold() &&
           (swing == SwingSource::kOcp || on_failed_check == OnFailedCheck::kRelaxedOcp);
  }
  bool operator==(const WalkingPolicy& o) const {
    return heuristic_bounds == o.heuristic_bounds && check == o.check &&
           (check == FootholdCheck::kNone || on_failed_check == o.on_failed_check) &&
           swing == o.swing;
  }
};

}  // namespace reach_trajopt
