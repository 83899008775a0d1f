#pragma once
/// \file state_json.h
/// The state file of `model_info --state`, read strictly: {"q": [n_q], "qd": [n_q]} (and
/// optionally "qdd": [n_q], for --rnea-derivatives) or
/// {"states": [{"q": ..., "qd": ...}, ...]} (at most kMaxStates), known keys only, finite
/// numbers, exact sizes; errors name the file and key path ("s.json: states[2].qd: expected 18
/// numbers, got 17").

#include <Eigen/Core>
#include <vector>

#include "reach_trajopt/common/json_reader.h"

namespace reach_trajopt {

constexpr std::size_t kMaxStates = 100000;  ///< states per file (docs/limits.md)

struct JointSpaceState {
  Eigen::VectorXd q, qd;  ///< size n_q each [m, rad; m/s, rad/s]
  Eigen::VectorXd qdd;    ///< size n_q [m/s^2, rad/s^2], or empty when the file has none
};

/// \throws ReachError naming the source and key path of the first problem.
std::vector<JointSpaceState> readStates(const JsonReader& r, int nq);

}  // namespace reach_trajopt
