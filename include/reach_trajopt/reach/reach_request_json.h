#pragma once
/// \file reach_request_json.h
/// The JSON request of the reach_check tool (its format is documented in
/// nodes/tools/reach_check.cpp), read strictly with JsonReader: known keys only, vectors of
/// exactly n_q (or 3) finite numbers, the "config" overrides through ReachConfig's strict YAML
/// reader. Reading builds nothing (no IK): the tool turns the request into a ReachProblem.

#include <Eigen/Core>
#include <string>

#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/contact/contact_mode.h"
#include "reach_trajopt/planner/kinematic_feasibility.h"
#include "reach_trajopt/reach/reach_config.h"

namespace reach_trajopt {

/// A validated reach_check request.
struct ReachCheckRequest {
  std::string mode = "SS-L";   ///< "SS-L" | "SS-R" | "none" (fixed base, no contacts)
  FlatContact stance, target;  ///< footholds (read when mode != none)
  bool has_x0 = false;         ///< x0 given, else the swing description below
  Eigen::VectorXd q0, qd0;     ///< x_0, size n_q each
  Eigen::Vector3d swing_position = Eigen::Vector3d::Zero();  ///< [m] (when !has_x0)
  Eigen::Vector3d swing_velocity = Eigen::Vector3d::Zero();  ///< [m/s]
  double swing_yaw = 0.0;                                    ///< [rad]
  Eigen::VectorXd q_init;   ///< IK start (size n_q), empty: the IK's own guess
  bool has_xf = false;      ///< xf given, else x_f comes from the kinematic check
  Eigen::VectorXd qf, qdf;  ///< x_f, size n_q each
  ReachConfig config;       ///< the base config with the request's "config" overrides
};

/// Reads a foothold {"position": [x, y, z], "yaw": rad} (yaw optional, 0).
FlatContact readFoothold(const JsonReader& r);

/// Reads a reach_check request for a model with `nq` coordinates on top of `base_config`.
/// \throws ReachError naming the source and key path of the first problem.
ReachCheckRequest readReachCheckRequest(const JsonReader& r, int nq,
                                        const ReachConfig& base_config);

}  // namespace reach_trajopt
