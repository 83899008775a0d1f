/// \file step_verdict.cpp
/// The name tables of the footstep verdicts, certificates and foothold sources (see the header).

#include "reach_trajopt/step/step_verdict.h"

namespace reach_trajopt {

const EnumNames<StepVerdict>& stepVerdictNames() {
  static const EnumNames<StepVerdict> n = {
      {"not_checked", StepVerdict::kNotChecked},
      {"kinematically_feasible", StepVerdict::kKinematicallyFeasible},
      {"kinematically_infeasible", StepVerdict::kKinematicallyInfeasible},
      {"reachable", StepVerdict::kReachable},
      {"unreachable", StepVerdict::kUnreachable},
      {"check_error", StepVerdict::kCheckError}};
  return n;
}

const EnumNames<Certificate>& certificateNames() {
  static const EnumNames<Certificate> n = {{"", Certificate::kNone},
                                           {"bridge", Certificate::kBridge},
                                           {"local_solve", Certificate::kLocalSolve}};
  return n;
}

const EnumNames<FootholdSource>& footholdSourceNames() {
  static const EnumNames<FootholdSource> n = {
      {"target", FootholdSource::kTarget},
      {"clipped_to_bounds", FootholdSource::kClippedToBounds},
      {"nearest_feasible", FootholdSource::kNearestFeasible},
      {"nearest_reachable", FootholdSource::kNearestReachable},
      {"relaxed", FootholdSource::kRelaxed}};
  return n;
}

}  // namespace reach_trajopt
