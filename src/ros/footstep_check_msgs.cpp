/// \file footstep_check_msgs.cpp
/// The check_footstep service's conversions (see the header).

#include "reach_trajopt/ros/footstep_check_msgs.h"

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/ocp/transition_request.h"
#include "reach_trajopt/ros/conversions.h"
#include "reach_trajopt/ros/footstep_plan_msgs.h"

namespace reach_trajopt {
namespace ros_bridge {

namespace {

/// The witness path's fields that the check_footstep response carries as they are, one list
/// for both directions: `copy(response field, witness field)` for each (const on the side
/// read). The path q and the violation are converted on their own.
template <class Response, class Witness, class Copy>
void forEachWitnessField(Response& m, Witness& w, Copy&& copy) {
  copy(m.witness_valid, w.valid);
  copy(m.witness_certified, w.certified);
  copy(m.witness_junction, w.junction);
  copy(m.witness_bridge_start, w.bridge_start);
  copy(m.witness_time, w.time);
  copy(m.witness_output_gap, w.output_gap);
  copy(m.witness_position_gap, w.position_gap);
  copy(m.witness_velocity_gap, w.velocity_gap);
  copy(m.witness_terminal_position_gap, w.terminal_position_gap);
  copy(m.witness_terminal_velocity_gap, w.terminal_velocity_gap);
  copy(m.witness_terminal_output_gap, w.terminal_output_gap);
}

std::vector<double> flatContact(const FlatContact& c) {
  return {c.position.x(), c.position.y(), c.position.z(), c.yaw};
}

FlatContact flatContact(const std::vector<double>& v, const std::string& field) {
  const Eigen::VectorXd x = finiteVector(v, 4, field);
  FlatContact c;
  c.position = x.head<3>();
  c.yaw = x[3];
  return c;
}

}  // namespace

reach_trajopt::CheckFootstep::Request toCheckFootstepRequestMsg(
    const ContactTransition& r, const ReachConfig& reach, const std::optional<CheckPass>& pass,
    bool reachability, bool samples, const ros::Time& t0) {
  reach_trajopt::CheckFootstep::Request m;
  m.header.stamp = t0;
  m.header.frame_id = kWorldFrame;
  m.stance = r.stance == Side::kLeft ? "left" : "right";
  m.stance_contact = flatContact(r.stance_contact);
  m.target = flatContact(r.target);
  m.q0 = asVector(r.q0);
  m.qd0 = asVector(r.qd0);
  m.qdf = asVector(r.qdf);
  m.touchdown_com_velocity = {r.touchdown.com_velocity.x(), r.touchdown.com_velocity.y()};
  if (r.touchdown.pelvis_position)
    m.touchdown_pelvis_position = asVector(*r.touchdown.pelvis_position);
  m.check_reachability = reachability;
  m.reach_horizon = reach.horizon;
  m.seed = static_cast<int64_t>(reach.seed);
  if (pass) {
    m.budget = {toSampleBudgetMsg(pass->budget)};
    m.forward_set_only = pass->forwardOnly();
    if (pass->forwardOnly() && std::isfinite(pass->forward_until_s))
      m.forward_until = {pass->forward_until_s};
  }
  m.return_samples = samples;
  return m;
}

FootstepCheckCall fromCheckFootstepRequestMsg(const reach_trajopt::CheckFootstep::Request& m,
                                              int nq, const ReachConfig& base) {
  requireWorldFrame(m.header.frame_id, "header.frame_id: ");
  FootstepCheckCall c;
  ContactTransition& r = c.request;
  if (m.stance != "left" && m.stance != "right")
    throw RequestError("stance: expected 'left' or 'right', got '" + m.stance + "'");
  r.stance = m.stance == "left" ? Side::kLeft : Side::kRight;
  r.stance_contact = flatContact(m.stance_contact, "stance_contact");
  r.target = flatContact(m.target, "target");
  r.q0 = finiteVector(m.q0, static_cast<size_t>(nq), "q0");
  r.qd0 = finiteVector(m.qd0, static_cast<size_t>(nq), "qd0");
  if (!m.qdf.empty()) r.qdf = finiteVector(m.qdf, static_cast<size_t>(nq), "qdf");
  r.touchdown.com_velocity = finiteVector(m.touchdown_com_velocity, 2, "touchdown_com_velocity");
  if (!m.touchdown_pelvis_position.empty())
    r.touchdown.pelvis_position =
        finiteVector(m.touchdown_pelvis_position, 3, "touchdown_pelvis_position");
  c.reachability = m.check_reachability;
  c.samples = m.return_samples;
  c.reach = base;
  if (!std::isfinite(m.reach_horizon) || m.reach_horizon < 0.0 ||
      m.reach_horizon > kMaxTransitionHorizon) {
    std::ostringstream os;
    os << "reach_horizon: expected 0 (the default) or a horizon in (0, " << kMaxTransitionHorizon
       << "] s, got " << m.reach_horizon;
    throw RequestError(os.str());
  }
  if (m.reach_horizon > 0.0) c.reach.horizon = m.reach_horizon;
  if (m.seed < -1) throw RequestError("seed: expected -1 (the node's) or >= 0");
  if (m.seed >= 0) c.reach.seed = static_cast<std::uint64_t>(m.seed);
  if (m.budget.size() > 1)
    throw RequestError("budget: expected none or one, got " + std::to_string(m.budget.size()));
  if (m.budget.empty() && (m.forward_set_only || !m.forward_until.empty()))
    throw RequestError("forward_set_only/forward_until: need a budget (one pass)");
  if (!m.forward_set_only && !m.forward_until.empty())
    throw RequestError("forward_until: only with forward_set_only");
  if (!m.budget.empty()) {
    CheckPass pass;
    pass.budget = fromSampleBudgetMsg(m.budget[0]);
    pass.sets = m.forward_set_only ? PassSets::kForwardOnly : PassSets::kBoth;
    if (!m.forward_until.empty()) {
      pass.forward_until_s = finiteVector(m.forward_until, 1, "forward_until")[0];
      if (pass.forward_until_s < 0.0) throw RequestError("forward_until: must be >= 0");
    }
    c.pass = pass;
  }
  try {
    c.reach.validate();
    if (c.pass) {
      c.pass->budget.validate("budget");
      c.reach.requireResourcesWithinLimits(nq, c.pass->budget);
    } else {
      c.reach.requireResourcesWithinLimits(nq);
    }
  } catch (const ReachError& e) {
    throw RequestError(std::string("budget/reach_horizon/seed: ") + e.what());
  }
  return c;
}

reach_trajopt::CheckFootstep::Response toCheckFootstepResponseMsg(
    const FootstepCheckResult& check, const reach_trajopt::ReachabilityResult& published) {
  reach_trajopt::CheckFootstep::Response m;
  const FootstepCheckResult& f = check;
  m.success = true;
  m.kinematically_feasible = f.kinematically_feasible;
  m.reachable = f.reachable;
  m.reason = f.reason;
  const KinematicFeasibilityResult& k = f.kinematics;
  m.kinematics_reason = k.reason;
  m.position_residual = k.position_residual;
  m.orientation_residual = k.orientation_residual;
  m.iterations = k.iterations;
  m.q_f = asVector(k.q_f);
  m.qd_f = asVector(k.qd_f);
  m.qdf = asVector(f.qdf);
  const ReachResult& reach = f.reach;
  m.reach_reachable = reach.reachable;
  m.reach_reason = reach.reason;
  for (const SliceComparison& c : reach.window) {
    m.window_time.push_back(c.time);
    m.window_hausdorff.push_back(c.distance.hausdorff);
    m.window_overlap.push_back(c.overlap);
  }
  const WitnessPath& w = reach.witness;
  forEachWitnessField(m, w, [](auto& to, const auto& from) { to = from; });
  m.witness_q.assign(w.q.data(), w.q.data() + w.q.size());
  if (w.valid) m.witness_violation = pathViolationVector(w.violation);
  for (const ReachableSlice& s : check.set_constraint) {
    m.constraint_time.push_back(s.time);
    m.constraint_rows.push_back(static_cast<uint32_t>(s.A.rows()));
    for (Eigen::Index i = 0; i < s.A.rows(); ++i) {
      m.constraint_normals.push_back(s.A(i, 0));
      m.constraint_normals.push_back(s.A(i, 1));
      m.constraint_offsets.push_back(s.b[i]);
    }
  }
  m.reachability = published;
  return m;
}

FootstepCheckResult fromCheckFootstepResponseMsg(const reach_trajopt::CheckFootstep::Response& m,
                                                 int nq) {
  const size_t n = static_cast<size_t>(nq);
  FootstepCheckResult out;
  FootstepCheckResult& f = out;
  f.kinematically_feasible = m.kinematically_feasible;
  f.reachable = m.reachable;
  f.reason = m.reason;
  KinematicFeasibilityResult& k = f.kinematics;
  k.feasible = m.kinematically_feasible;
  k.reason = m.kinematics_reason;
  k.position_residual = m.position_residual;
  k.orientation_residual = m.orientation_residual;
  k.iterations = m.iterations;
  if (!m.q_f.empty()) k.q_f = responseVector("check_footstep", m.q_f, n, "q_f");
  if (!m.qd_f.empty()) k.qd_f = responseVector("check_footstep", m.qd_f, n, "qd_f");
  if (m.kinematically_feasible || !m.qdf.empty())
    f.qdf = responseVector("check_footstep", m.qdf, n, "qdf");
  ReachResult& reach = f.reach;
  reach.reachable = m.reach_reachable;
  reach.reason = m.reach_reason;
  requireResponseEntries("check_footstep", m.window_hausdorff, m.window_time.size(),
                         "window_hausdorff");
  requireResponseEntries("check_footstep", m.window_overlap, m.window_time.size(),
                         "window_overlap");
  for (size_t i = 0; i < m.window_time.size(); ++i) {
    SliceComparison c;
    c.time = m.window_time[i];
    c.distance.hausdorff = m.window_hausdorff[i];
    c.overlap = m.window_overlap[i] != 0;
    reach.window.push_back(c);
  }
  WitnessPath& w = reach.witness;
  forEachWitnessField(m, w, [](const auto& from, auto& to) { to = from; });
  if (!m.witness_q.empty()) {
    requireResponseEntries("check_footstep", m.witness_q, n * m.witness_time.size(), "witness_q");
    w.q = Eigen::Map<const Eigen::MatrixXd>(m.witness_q.data(), nq,
                                            static_cast<Eigen::Index>(m.witness_time.size()));
  }
  if (w.bridge_start >= static_cast<int>(w.time.size()))
    throw ReachError("check_footstep response: witness_bridge_start: beyond witness_time");
  if (w.valid) {
    w.violation = pathViolationFromVector(m.witness_violation, "check_footstep");
  }
  requireResponseEntries("check_footstep", m.constraint_rows, m.constraint_time.size(),
                         "constraint_rows");
  size_t rows = 0;
  for (uint32_t r : m.constraint_rows) rows += r;
  requireResponseEntries("check_footstep", m.constraint_normals, 2 * rows, "constraint_normals");
  requireResponseEntries("check_footstep", m.constraint_offsets, rows, "constraint_offsets");
  size_t row = 0;
  for (size_t i = 0; i < m.constraint_time.size(); ++i) {
    ReachableSlice s;
    s.time = m.constraint_time[i];
    const Eigen::Index k_rows = static_cast<Eigen::Index>(m.constraint_rows[i]);
    s.A.resize(k_rows, 2);
    s.b.resize(k_rows);
    for (Eigen::Index j = 0; j < k_rows; ++j, ++row) {
      s.A(j, 0) = m.constraint_normals[2 * row];
      s.A(j, 1) = m.constraint_normals[2 * row + 1];
      s.b[j] = m.constraint_offsets[row];
    }
    out.set_constraint.push_back(std::move(s));
  }
  return out;
}

}  // namespace ros_bridge
}  // namespace reach_trajopt
