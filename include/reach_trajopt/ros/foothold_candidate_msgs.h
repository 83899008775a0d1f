#pragma once
/// \file foothold_candidate_msgs.h
/// Pure conversions (no node, no master) of a batch of candidate footholds of the
/// nearest-feasible-foothold search (planner/nearest_feasible_foothold.h) to the request of a
/// reachability worker's check_footholds service (reach_trajopt/CheckFootholds) and of its
/// outcomes to the response, each way back validated. Every number travels as float64, so the
/// search decides bit for bit what it decides in process. Frame "world", SI units.

#include <cstdint>
#include <vector>

#include "reach_trajopt/CheckFootholds.h"
#include "reach_trajopt/planner/nearest_feasible_foothold.h"

namespace reach_trajopt {
namespace ros_bridge {

/// The most candidates one check_footholds request may carry: one ring of the search, whose
/// `nearest_foothold.directions` is at most 360 (each candidate is an IK solve).
constexpr size_t kMaxFootholdCandidates = 360;

/// The request of `batch`, tagged `request_id`.
reach_trajopt::CheckFootholds::Request toCheckFootholdsRequestMsg(const FootholdCandidates& batch,
                                                                  uint64_t request_id);

/// The batch of a request for a model with `nq` coordinates.
/// \throws RequestError naming the field: an unknown stance, sizes, non-finite numbers, more
/// than kMaxFootholdCandidates candidates.
FootholdCandidates fromCheckFootholdsRequestMsg(const reach_trajopt::CheckFootholds::Request& m,
                                                int nq);

/// The response (success = true) of `outcomes`, one per candidate, tagged `request_id`.
reach_trajopt::CheckFootholds::Response toCheckFootholdsResponseMsg(
    const std::vector<CandidateOutcome>& outcomes, uint64_t request_id);

/// The outcomes of a successful response to a batch of `candidates` candidates, for a model
/// with `nq` coordinates.
/// \throws ReachError naming the field of a malformed response (sizes).
std::vector<CandidateOutcome> fromCheckFootholdsResponseMsg(
    const reach_trajopt::CheckFootholds::Response& m, size_t candidates, int nq);

}  // namespace ros_bridge
}  // namespace reach_trajopt
