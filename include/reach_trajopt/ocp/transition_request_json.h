#pragma once
/// \file transition_request_json.h
/// The JSON request of the plan_transition tool (format in nodes/tools/plan_transition.cpp),
/// read strictly with JsonReader: known keys only, q vectors of exactly n_q finite numbers,
/// hull rows of 2, a horizon within (0, kMaxTransitionHorizon], at most kMaxRequestSlices
/// slices and kMaxSeedSamples seed samples. Reading runs no IK: without "qf" the caller fills
/// x_f from the kinematic feasibility check (and must refuse an infeasible one).

#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/contact/contact_mode.h"
#include "reach_trajopt/ocp/transition_request.h"
#include "reach_trajopt/planner/kinematic_feasibility.h"

namespace reach_trajopt {

/// Upper bounds of a request (docs/limits.md): a swing lasts well under a second; the OCP's
/// cost and output grow with the horizon (output_dt samples) and the slices.
constexpr std::size_t kMaxRequestSlices = 10000;  ///< reachable-set slices per request
constexpr std::size_t kMaxSliceRows = 1000;       ///< half-spaces per slice
constexpr std::size_t kMaxSeedSamples = 100000;   ///< seed path samples

/// A read plan_transition request.
struct TransitionRequestJson {
  TransitionRequest request;  ///< qf/qdf empty when has_qf is false
  bool has_qf = false;
};

/// Reads a plan_transition request for a model with `nq` coordinates.
/// \throws ReachError naming the source and key path of the first problem.
TransitionRequestJson readTransitionRequest(const JsonReader& r, int nq);

/// Writes `r` in the format readTransitionRequest reads (for replays, e.g. walk_experiment
/// --ocp-requests). The stance pose and the swing target are written as flat footholds (position
/// and yaw): their roll and pitch are dropped. The seed path is not written.
nlohmann::json transitionRequestToJson(const TransitionRequest& r);

}  // namespace reach_trajopt
