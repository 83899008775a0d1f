#pragma once
/// \file reference_cases.h
/// Footsteps shared by the benchmarks, the verdict oracle and the tests, so each is written once.

#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/step/footstep_transition_planner.h"

namespace reach_trajopt {

/// bench/reach's SS-L -> DS case (the paper's Sec. IV-B transition): left stance sole at
/// (0, 0.1, 0), the right sole 3 cm short of its target (0.25, -0.12, 0) and 2 cm up, moving
/// to stop there at t_f = config.reach.horizon (x_f at rest). For the biped of urdf/biped.urdf.
/// \throws ReachError when the model lacks the biped's joints or the swing state has no IK.
FootstepPlanRequest benchSwingCase(const std::shared_ptr<const RobotModel>& model,
                                   const FootstepPlannerConfig& config,
                                   const ContactConfig& contact);

}  // namespace reach_trajopt
