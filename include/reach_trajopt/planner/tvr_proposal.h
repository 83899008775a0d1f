#pragma once
/// \file tvr_proposal.h
/// The walking loop's TVR proposal of the next contact (eq. 11) as one stateless call: the
/// measured CoM state and everything the loop's planner is set up with (the LIPM height, the
/// heuristic bounds switch) beside the shared planner section (TvrConfig's gains and bounds).
/// The loop plans it in process or hands it to another planner (tvr_planner_node's
/// propose_footstep); both give the same bits for the same TvrConfig.

#include <Eigen/Core>

#include "reach_trajopt/contact/contact_mode.h"
#include "reach_trajopt/planner/lipm.h"
#include "reach_trajopt/planner/tvr_planner.h"

namespace reach_trajopt {

/// TvrPlanner::planFromMeasured's arguments and the planner's per-run inputs.
struct TvrProposalRequest {
  LipmState measured;                                ///< CoM position [m], velocity [m/s] at t
  Eigen::Vector2d stance = Eigen::Vector2d::Zero();  ///< stance sole centre (x, y) [m]
  Side swing = Side::kRight;                         ///< the sole that steps
  double time = 0.0;                                 ///< t of the run [s]
  double remaining = 0.0;                            ///< to the nominal touchdown [s], >= 0
  double x_start = 0.0;                              ///< CoM x at the start of the run [m]
  double forward_speed = 0.0;                        ///< desired CoM speed along x [m/s]
  double y_mid = 0.0;                                ///< y of p_des [m]
  double com_height = 1.0;       ///< h of the LIPM [m] (replaces TvrConfig::com_height)
  bool heuristic_bounds = true;  ///< replaces TvrConfig::heuristic_bounds
};

/// The proposed contact and the planner's input (the CoM predicted at touchdown, p_des).
struct TvrProposal {
  TvrStep step;
  TvrInput input;
};

/// @brief Eq. (11) from a measured CoM state with `config`'s gains and bounds, the request's
/// LIPM height and bounds switch (TvrPlanner::planFromMeasured).
/// \throws ReachError (ConfigError) on a config the request makes invalid (h <= 0), RequestError
///     on a non-finite input.
TvrProposal proposeFootstep(const TvrConfig& config, const TvrProposalRequest& request);

}  // namespace reach_trajopt
