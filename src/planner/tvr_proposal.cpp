/// \file tvr_proposal.cpp
/// One stateless TVR proposal (see the header).

#include "reach_trajopt/planner/tvr_proposal.h"

#include <cmath>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

TvrProposal proposeFootstep(const TvrConfig& config, const TvrProposalRequest& r) {
  if (!std::isfinite(r.remaining) || r.remaining < 0.0)
    throw RequestError("TVR proposal: remaining must be finite and >= 0");
  TvrConfig c = config;
  c.com_height = r.com_height;
  c.heuristic_bounds = r.heuristic_bounds;
  const TvrPlanner planner(c);  // validates
  TvrProposal out;
  out.step = planner.planFromMeasured(r.measured, r.stance, r.swing, r.time, r.remaining, r.x_start,
                                      r.forward_speed, r.y_mid, &out.input);
  return out;
}

}  // namespace reach_trajopt
