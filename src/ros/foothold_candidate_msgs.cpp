/// \file foothold_candidate_msgs.cpp
#include "reach_trajopt/ros/foothold_candidate_msgs.h"

#include <string>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/ros/conversions.h"
#include "reach_trajopt/ros/footstep_plan_msgs.h"

namespace reach_trajopt {
namespace ros_bridge {

reach_trajopt::CheckFootholds::Request toCheckFootholdsRequestMsg(const FootholdCandidates& batch,
                                                                  uint64_t request_id) {
  reach_trajopt::CheckFootholds::Request m;
  m.request_id = request_id;
  m.stance = batch.stance == Side::kLeft ? "left" : "right";
  m.stance_position = toPointMsg(batch.stance_contact.position);
  m.stance_yaw = batch.stance_contact.yaw;
  for (const FlatContact& c : batch.candidates) {
    m.candidates.push_back(toPointMsg(c.position));
    m.candidate_yaw.push_back(c.yaw);
  }
  m.q_init = asVector(batch.q_init);
  if (batch.pelvis_position) m.pelvis_position = asVector(*batch.pelvis_position);
  return m;
}

FootholdCandidates fromCheckFootholdsRequestMsg(const reach_trajopt::CheckFootholds::Request& m,
                                                int nq) {
  FootholdCandidates b;
  if (m.stance != "left" && m.stance != "right")
    throw RequestError("stance: expected 'left' or 'right', got '" + m.stance + "'");
  b.stance = m.stance == "left" ? Side::kLeft : Side::kRight;
  const geometry_msgs::Point& s = m.stance_position;
  b.stance_contact.position = finiteVector({s.x, s.y, s.z}, 3, "stance_position");
  b.stance_contact.yaw = finiteVector({m.stance_yaw}, 1, "stance_yaw")[0];
  if (m.candidates.size() > kMaxFootholdCandidates)
    throw RequestError("candidates: " + std::to_string(m.candidates.size()) +
                       " candidates exceed the limit of " + std::to_string(kMaxFootholdCandidates) +
                       " per request (one ring of the search: nearest_foothold.directions)");
  if (m.candidate_yaw.size() != m.candidates.size())
    throw RequestError("candidate_yaw: expected one per candidate (" +
                       std::to_string(m.candidates.size()) + "), got " +
                       std::to_string(m.candidate_yaw.size()));
  for (size_t i = 0; i < m.candidates.size(); ++i) {
    const geometry_msgs::Point& p = m.candidates[i];
    FlatContact c;
    c.position = finiteVector({p.x, p.y, p.z}, 3, "candidates[" + std::to_string(i) + "]");
    c.yaw = finiteVector({m.candidate_yaw[i]}, 1, "candidate_yaw[" + std::to_string(i) + "]")[0];
    b.candidates.push_back(c);
  }
  if (!m.q_init.empty()) b.q_init = finiteVector(m.q_init, static_cast<size_t>(nq), "q_init");
  if (!m.pelvis_position.empty())
    b.pelvis_position = Eigen::Vector3d(finiteVector(m.pelvis_position, 3, "pelvis_position"));
  return b;
}

reach_trajopt::CheckFootholds::Response toCheckFootholdsResponseMsg(
    const std::vector<CandidateOutcome>& outcomes, uint64_t request_id) {
  reach_trajopt::CheckFootholds::Response m;
  m.request_id = request_id;
  m.success = true;
  for (const CandidateOutcome& o : outcomes) {
    const KinematicFeasibilityResult& k = o.kinematics;
    m.feasible.push_back(k.feasible);
    m.reason.push_back(k.reason);
    m.error.push_back(o.error);
    m.position_residual.push_back(k.position_residual);
    m.orientation_residual.push_back(k.orientation_residual);
    m.iterations.push_back(k.iterations);
    // A failed check has no IK result: its rows stay empty (sizes say which is which).
    const std::vector<double> q = asVector(k.q_f), qd = asVector(k.qd_f);
    m.q_f.insert(m.q_f.end(), q.begin(), q.end());
    m.qd_f.insert(m.qd_f.end(), qd.begin(), qd.end());
  }
  return m;
}

std::vector<CandidateOutcome> fromCheckFootholdsResponseMsg(
    const reach_trajopt::CheckFootholds::Response& m, size_t candidates, int nq) {
  requireResponseEntries("check_footholds", m.feasible, candidates, "feasible");
  requireResponseEntries("check_footholds", m.reason, candidates, "reason");
  requireResponseEntries("check_footholds", m.error, candidates, "error");
  requireResponseEntries("check_footholds", m.position_residual, candidates, "position_residual");
  requireResponseEntries("check_footholds", m.orientation_residual, candidates,
                         "orientation_residual");
  requireResponseEntries("check_footholds", m.iterations, candidates, "iterations");
  size_t with_ik = 0;
  for (const std::string& e : m.error) with_ik += e.empty();
  const size_t n = static_cast<size_t>(nq);
  requireResponseEntries("check_footholds", m.q_f, with_ik * n, "q_f");
  requireResponseEntries("check_footholds", m.qd_f, with_ik * n, "qd_f");
  std::vector<CandidateOutcome> outcomes(candidates);
  size_t row = 0;
  for (size_t i = 0; i < candidates; ++i) {
    CandidateOutcome& o = outcomes[i];
    o.error = m.error[i];
    if (!o.error.empty()) continue;
    KinematicFeasibilityResult& k = o.kinematics;
    k.feasible = m.feasible[i];
    k.reason = m.reason[i];
    k.position_residual = m.position_residual[i];
    k.orientation_residual = m.orientation_residual[i];
    k.iterations = m.iterations[i];
    k.q_f = Eigen::Map<const Eigen::VectorXd>(m.q_f.data() + row * n, nq);
    k.qd_f = Eigen::Map<const Eigen::VectorXd>(m.qd_f.data() + row * n, nq);
    ++row;
  }
  return outcomes;
}

}  // namespace ros_bridge
}  // namespace reach_trajopt
