#pragma once
/// \file reference_cases.h
/// Footsteps shared by the benchmarks, the verdict oracle and the tests, so each is written once.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/contact/contact_transition.h"
#include "reach_trajopt/ocp/transition_request.h"
#include "reach_trajopt/step/footstep_transition_planner.h"

namespace reach_trajopt {

/// The shipped biped as the walk plans with it: urdf/biped.urdf with config/biped.yaml's
/// contact and planner sections, below the repository root `repo`.
struct ShippedBiped {
  std::shared_ptr<const RobotModel> model;
  ContactConfig contact;
  FootstepPlannerConfig config;
  explicit ShippedBiped(const std::string& repo);
  std::unique_ptr<FootstepTransitionPlanner> makePlanner() const;
};

/// urdf/biped.urdf below the repository root `repo`, loaded once per process (by the first
/// call; the tests' shared read-only model).
std::shared_ptr<const RobotModel> shippedBipedModel(const std::string& repo);

/// The shipped biped with its footstep planner, built once per test binary (shippedPipeline()).
struct ShippedPipeline : ShippedBiped {
  explicit ShippedPipeline(const std::string& repo);
  std::string repo;
  std::unique_ptr<FootstepTransitionPlanner> planner;
  /// The requests of test/fixtures/`fixture` (readPlanRequests with this config's reach).
  std::vector<FootstepPlanRequest> requests(const std::string& fixture) const;
};
/// One ShippedPipeline of `repo` for the whole test binary.
const ShippedPipeline& shippedPipeline(const std::string& repo);

/// The footstep requests of a JSON-lines file (`walk_experiment --plan-requests`, e.g.
/// test/fixtures/pushed_walk_requests.jsonl) for a model with `nq` coordinates, their
/// reach_horizon over `reach`. \throws RequestError naming the file on a bad line.
std::vector<FootstepPlanRequest> readPlanRequests(const std::string& path, int nq,
                                                  const ReachConfig& reach);

/// A flat contact at (x, y, 0), heading 0.
FlatContact contactAt(double x, double y);

/// A posture of the biped: the base at `base` [m], upright; both legs' hips and ankles pitched by
/// -bend and knees by 2 bend [rad] (an IK start with bent knees: the IK's own converges to
/// stretched legs).
Eigen::VectorXd bipedPosture(const RobotModel& model, const Eigen::Vector3d& base, double bend);

/// The biped's IK start: upright, knees slightly bent, pelvis above the stance (left) foot side.
Eigen::VectorXd bipedIkGuess(const RobotModel& model);

/// The transition OCP's reference step (bench/ocp, the OCP tests): SS-L, the left sole at
/// (0, 0.1), the right sole to (target_x, -0.1) over `horizon` [s]; x_f the IK posture there
/// (qd_f = 0), x_0 the IK stance for a step to (start_x, -0.1) with the right leg folded (swing
/// sole about 0.1 m up), at rest. For the biped of urdf/biped.urdf.
/// 	hrows ReachError when the start's IK fails.
TransitionRequest ocpStepCase(const std::shared_ptr<const RobotModel>& model, double target_x,
                              double start_x, double horizon);

/// bench/reach's SS-L -> DS case (the paper's Sec. IV-B transition): left stance sole at
/// (0, 0.1, 0), the right sole 3 cm short of its target (0.25, -0.12, 0) and 2 cm up, moving
/// to stop there at t_f = config.reach.horizon (x_f at rest). For the biped of urdf/biped.urdf.
/// \throws ReachError when the model lacks the biped's joints or the swing state has no IK.
FootstepPlanRequest benchSwingCase(const std::shared_ptr<const RobotModel>& model,
                                   const FootstepPlannerConfig& config,
                                   const ContactConfig& contact);

}  // namespace reach_trajopt
