#pragma once
/// \file footstep_plan_request_json.h
/// A FootstepPlanRequest as JSON, for replaying the footsteps of a walk offline
/// (`walk_experiment --plan-requests FILE` writes one per line; `verdict_grid` reads them):
///   {"stance": "left" | "right",
///    "stance_pose": {"position": [x, y, z], "rotation": [9 numbers, row-major]},
///    "target": [x, y, z], "target_yaw": yaw [rad] (optional: none, the stance pose's heading),
///    "q": [n_q], "qd": [n_q],
///    "touchdown_com": {"p": [x, y], "pd": [vx, vy]} (optional),
///    "reach_horizon": t_f - t_0 of the check [s] (optional; none: the config's)}
/// Read strictly (json_reader.h): known keys only, exact sizes, finite numbers, a rotation
/// matrix within 1e-6 of orthonormal, a horizon in (0, kMaxTransitionHorizon]. The request
/// keeps the stance pose's position and heading (its stance_contact); written back, the pose
/// is flat and target_yaw always given. "q", "qd" are x_0 (the request's q0, qd0).

#include <nlohmann/json.hpp>

#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/step/footstep_transition_planner.h"

namespace reach_trajopt {

/// The request's JSON (reach_horizon from request.reach when set).
nlohmann::json footstepPlanRequestJson(const FootstepPlanRequest& request);

/// Reads a request for a model with `nq` coordinates on top of `base` (its policies and flags
/// are kept); "reach_horizon" sets request.reach = base_reach with that horizon.
/// \throws RequestError naming the source and key path of the first problem.
FootstepPlanRequest readFootstepPlanRequest(const JsonReader& r, int nq,
                                            const ReachConfig& base_reach,
                                            const FootstepPlanRequest& base = {});

}  // namespace reach_trajopt
