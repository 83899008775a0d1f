/// \file state_json.cpp
/// Strict reading of state files (state_json.h).

#include "reach_trajopt/common/state_json.h"

namespace reach_trajopt {
namespace {

JointSpaceState readState(const JsonReader& r, int nq) {
  r.requireObject("{\"q\": [n_q numbers], \"qd\": [n_q numbers]}");
  r.requireOnlyKeys({"q", "qd", "qdd"});
  JointSpaceState s{r.vector("q", nq), r.vector("qd", nq), Eigen::VectorXd()};
  if (r.has("qdd")) s.qdd = r.vector("qdd", nq);
  return s;
}

}  // namespace

std::vector<JointSpaceState> readStates(const JsonReader& r, int nq) {
  r.requireObject("{\"q\": [...], \"qd\": [...]} or {\"states\": [...]}");
  std::vector<JointSpaceState> out;
  if (!r.has("states")) {
    out.push_back(readState(r, nq));
    return out;
  }
  r.requireOnlyKeys({"states"});
  const JsonReader list = r.at("states");
  const std::size_t n = list.requireArray(1, kMaxStates);
  for (std::size_t i = 0; i < n; ++i) out.push_back(readState(list.at(i), nq));
  return out;
}

}  // namespace reach_trajopt
