/// \file footstep_check.cpp
/// The in-process footstep check and its OCP slices (see the header).

#include "reach_trajopt/step/footstep_check.h"

#include "reach_trajopt/step/reachable_set_constraint.h"

namespace reach_trajopt {

FootstepCheckResult checkFootstep(const FootstepReachability& footsteps,
                                  const ContactTransition& request, const ReachConfig& config,
                                  const std::optional<CheckPass>& pass, bool reachability,
                                  const ReachProgressCallback& progress) {
  if (!reachability) return footsteps.kinematicStage(request);
  FootstepCheckResult out = pass ? footsteps.checkPass(request, config, *pass, progress)
                                 : footsteps.check(request, config, progress);
  const double margin =
      pass ? pass->budget.constraint_margin : config.budgets.full.constraint_margin;
  if (out.kinematically_feasible)
    out.set_constraint = reachableSetConstraint(out.reach, config.output_axes, margin);
  return out;
}

}  // namespace reach_trajopt
