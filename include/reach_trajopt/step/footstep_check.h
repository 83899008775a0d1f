#pragma once
/// \file footstep_check.h
/// Steps 2-3 of the per-step pipeline (footstep_transition_planner.h) as one call the planner
/// can hand elsewhere (e.g. reachability_node's check_footstep): the kinematic check of the
/// foothold (Sec. III-B) and, when asked, the reachability check (13)-(21), together with what
/// the OCP takes from the check's forward set, its swing sole hulls (eq. 23,
/// reachable_set_constraint.h). With the hulls computed where the sets are, the sets
/// themselves need not travel.

#include <functional>
#include <optional>
#include <vector>

#include "reach_trajopt/ocp/transition_request.h"
#include "reach_trajopt/reach/footstep_reachability.h"
#include "reach_trajopt/reach/reach_config.h"

namespace reach_trajopt {

/// Where the planner checks its footsteps: (request, reachability settings, the pass to run,
/// run the reachability check or the kinematic stage only). It throws ReachError for a
/// request it rejects, as the in-process check does.
using FootstepCheck = std::function<FootstepCheckResult(
    const ContactTransition&, const ReachConfig&, const CheckPass&, bool)>;

/// @brief The in-process check: `footsteps.checkPass(request, config, *pass, progress)` (no
/// pass: `footsteps.check(request, config, progress)`, the check's own pass schedule), or its
/// kinematicStage(request) when `reachability` is false, and the OCP's slices of its forward
/// set grown by the pass's constraint_margin (no pass: config.budgets.full's).
/// \throws ReachError as FootstepReachability::check does.
FootstepCheckResult checkFootstep(const FootstepReachability& footsteps,
                                  const ContactTransition& request, const ReachConfig& config,
                                  const std::optional<CheckPass>& pass, bool reachability,
                                  const ReachProgressCallback& progress = {});

}  // namespace reach_trajopt
