#pragma once
/// \file step_verdict.h
/// What the check of one footstep concluded, and what certifies a "reachable" verdict, as
/// enums; their names (nameOf(stepVerdictNames(), ...)) appear only at the edges: step records
/// (CSV), WALK lines, messages, JSON.

#include "reach_trajopt/common/enum_names.h"

namespace reach_trajopt {

/// The verdict of a footstep's check.
enum class StepVerdict {
  kNotChecked,               ///< "not_checked": the policy checks nothing
  kKinematicallyFeasible,    ///< "kinematically_feasible": the kinematic check (Sec. III-B)
                             ///< passed and no reachability check was asked for
  kKinematicallyInfeasible,  ///< "kinematically_infeasible": no joint-limited IK posture holds
                             ///< both soles on their footholds (Sec. III-B)
  kReachable,                ///< "reachable": a checked path x_0 -> x_f exists (Certificate)
  kUnreachable,              ///< "unreachable": not shown reachable (no certificate)
  kCheckError,               ///< "check_error": the check threw (bad state, a worker's error);
                             ///< the step goes to the TVR step clipped to the heuristic bounds
};
const EnumNames<StepVerdict>& stepVerdictNames();
inline const char* stepVerdictName(StepVerdict v) { return nameOf(stepVerdictNames(), v); }

/// What certifies a kReachable verdict.
enum class Certificate {
  kNone,        ///< "": not shown reachable
  kBridge,      ///< "bridge": the check's bridged witness path (ReachResult::reachable)
  kLocalSolve,  ///< "local_solve": the strict OCP seeded with the check's closest bridged path
                ///< and held in its sets, converged through its 1 ms re-check
};
const EnumNames<Certificate>& certificateNames();
inline const char* certificateName(Certificate c) { return nameOf(certificateNames(), c); }

/// Where the foothold a step lands on came from.
enum class FootholdSource {
  kTarget,            ///< "target": the proposed foothold itself (TVR's, bounded or not)
  kClippedToBounds,   ///< "clipped_to_bounds": the TVR step clipped to the heuristic bounds
  kNearestFeasible,   ///< "nearest_feasible": the nearest kinematically feasible ring point,
                      ///< not certified by a reachability check
  kNearestReachable,  ///< "nearest_reachable": the nearest ring point the reachability check
                      ///< certified (with a strict trajectory)
  kRelaxed,           ///< "relaxed": the relaxed OCP's closest reachable landing (Sec. III-E)
};
const EnumNames<FootholdSource>& footholdSourceNames();
inline const char* footholdSourceName(FootholdSource s) { return nameOf(footholdSourceNames(), s); }

}  // namespace reach_trajopt
