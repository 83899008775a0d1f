/// \file footstep_plan_msgs.cpp
/// The plan_footstep service's conversions (see the header).

#include "reach_trajopt/ros/footstep_plan_msgs.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include "reach_trajopt/common/config_fields.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/common/stopwatch.h"
#include "reach_trajopt/ocp/transition_request.h"
#include "reach_trajopt/ros/conversions.h"
#include "reach_trajopt/ros/service_requests.h"

namespace reach_trajopt {
namespace ros_bridge {

namespace {
constexpr double kMinTimeBudget = 1e-3;  // [s] a deadline already past, as a budget
constexpr double kMaxTimeBudget = 1e6;   // [s]

const std::pair<OcpPolicy, const char*> kOcpPolicies[] = {{OcpPolicy::kByVerdict, "by_verdict"},
                                                          {OcpPolicy::kStrict, "strict"},
                                                          {OcpPolicy::kAuto, "auto"}};
const std::pair<InfeasibleFootholdPolicy, const char*> kInfeasiblePolicies[] = {
    {InfeasibleFootholdPolicy::kNearestFeasible, "nearest_feasible"},
    {InfeasibleFootholdPolicy::kRelaxTowardTarget, "relax_toward_target"},
    {InfeasibleFootholdPolicy::kReject, "reject"},
    {InfeasibleFootholdPolicy::kNoFallback, "no_fallback"},
    {InfeasibleFootholdPolicy::kNearestReachable, "nearest_reachable"}};

template <typename Enum, size_t N>
Enum parseName(const std::pair<Enum, const char*> (&table)[N], const std::string& field,
               const std::string& name) {
  std::string known;
  for (const auto& [value, n] : table) {
    if (name == n) return value;
    known += (known.empty() ? "" : " | ") + std::string(n);
  }
  throw RequestError(field + ": unknown name '" + name + "' (expected " + known + ")");
}

}  // namespace

Eigen::VectorXd finiteVector(const std::vector<double>& v, size_t size, const std::string& field) {
  if (v.size() != size)
    throw RequestError(field + ": expected " + std::to_string(size) + " numbers, got " +
                       std::to_string(v.size()));
  for (double x : v)
    if (!std::isfinite(x)) throw RequestError(field + ": a number is not finite");
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

namespace {

/// The fields of a sample budget, one list for both directions: `copy(msg field, budget field)`
/// for each (const on the side read).
template <class Msg, class Budget, class Copy>
void forEachSampleBudgetField(Msg& m, Budget& b, Copy&& copy) {
  copy(m.initial_samples, b.initial_samples);
  copy(m.children_per_parent, b.children_per_parent);
  copy(m.backward_children_per_parent, b.backward_children_per_parent);
  copy(m.max_boundary, b.max_boundary);
  copy(m.interior_samples, b.interior_samples);
  copy(m.certificate_candidates, b.certificate_candidates);
  copy(m.constraint_margin, b.constraint_margin);
}

}  // namespace

reach_trajopt::SampleBudget toSampleBudgetMsg(const SamplingBudget& b) {
  reach_trajopt::SampleBudget m;
  forEachSampleBudgetField(m, b, [](auto& to, const auto& from) { to = from; });
  return m;
}

SamplingBudget fromSampleBudgetMsg(const reach_trajopt::SampleBudget& m) {
  SamplingBudget b;
  forEachSampleBudgetField(m, b, [](const auto& from, auto& to) { to = from; });
  return b;
}

std::vector<double> asVector(const Eigen::Ref<const Eigen::VectorXd>& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

std::vector<double> pathViolationVector(const PathViolation& v) {
  return {v.dynamics,       v.cone,         v.torque,           v.position_limit,
          v.velocity_limit, v.contact,      v.contact_velocity, v.integration,
          v.ground,         v.leg_clearance};
}

PathViolation pathViolationFromVector(const std::vector<double>& v, const std::string& service) {
  requireResponseEntries(service, v, 10, "witness_violation");
  return PathViolation{v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9]};
}

const char* ocpPolicyName(OcpPolicy p) {
  for (const auto& [value, name] : kOcpPolicies)
    if (value == p) return name;
  return "by_verdict";
}

const char* infeasibleFootholdPolicyName(InfeasibleFootholdPolicy p) {
  for (const auto& [value, name] : kInfeasiblePolicies)
    if (value == p) return name;
  return "nearest_feasible";
}

reach_trajopt::PlanFootstep::Request toPlanFootstepRequestMsg(const FootstepPlanRequest& r,
                                                              const ReachConfig& reach,
                                                              const ros::Time& t0) {
  reach_trajopt::PlanFootstep::Request m;
  m.header.stamp = t0;
  m.header.frame_id = kWorldFrame;
  m.stance = r.stance == Side::kLeft ? "left" : "right";
  // The stance sole as a flat pose (the planner reads its position and heading only).
  const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> R = r.stance_contact.pose().linear();
  m.stance_pose.assign(R.data(), R.data() + 9);
  const Eigen::Vector3d& p = r.stance_contact.position;
  m.stance_pose.insert(m.stance_pose.end(), p.data(), p.data() + 3);
  m.target = toPointMsg(r.target.position);
  m.target_yaw.push_back(r.target.yaw);
  m.q = asVector(r.q0);
  m.qd = asVector(r.qd0);
  if (r.touchdown_com)
    m.touchdown_com = {r.touchdown_com->p.x(), r.touchdown_com->p.y(), r.touchdown_com->pd.x(),
                       r.touchdown_com->pd.y()};
  m.make_contact_consistent = r.make_contact_consistent;
  m.check_reachability = r.check_reachability;
  m.solve_ocp = r.solve_ocp;
  m.horizon = r.horizon;
  const ReachConfig& used = r.reach ? *r.reach : reach;
  m.reach_horizon = used.horizon;
  m.seed = static_cast<int64_t>(used.seed);
  m.budgets = {toSampleBudgetMsg(used.budgets.full), toSampleBudgetMsg(used.budgets.quick),
               toSampleBudgetMsg(used.budgets.hullBudget())};
  m.ocp_policy = ocpPolicyName(r.ocp_policy);
  m.on_infeasible = infeasibleFootholdPolicyName(r.on_infeasible);
  if (r.deadline) {  // what is left of it now; one already past asks for the quickest answer
    const double left = secondsUntil(*r.deadline);
    m.time_budget = std::max(left, kMinTimeBudget);
  }
  return m;
}

FootstepPlanRequest fromPlanFootstepRequestMsg(const reach_trajopt::PlanFootstep::Request& m,
                                               int nq, const ReachConfig& base) {
  requireWorldFrame(m.header.frame_id, "header.frame_id: ");
  FootstepPlanRequest r;
  if (m.stance != "left" && m.stance != "right")
    throw RequestError("stance: expected 'left' or 'right', got '" + m.stance + "'");
  r.stance = m.stance == "left" ? Side::kLeft : Side::kRight;
  const Eigen::VectorXd pose = finiteVector(m.stance_pose, 12, "stance_pose");
  const Eigen::Matrix3d R =
      Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(pose.data());
  if (!(R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-6) || R.determinant() < 0.0)
    throw RequestError("stance_pose: the first 9 numbers are not a rotation matrix (row-major)");
  Eigen::Isometry3d stance_pose = Eigen::Isometry3d::Identity();
  stance_pose.linear() = R;
  stance_pose.translation() = pose.tail<3>();
  r.stance_contact = FlatContact::fromPose(stance_pose);
  r.target.position = finiteVector({m.target.x, m.target.y, m.target.z}, 3, "target");
  if (m.target_yaw.size() > 1)
    throw RequestError("target_yaw: expected no value or one, got " +
                       std::to_string(m.target_yaw.size()));
  // None: the stance sole's heading.
  r.target.yaw =
      m.target_yaw.empty() ? r.stance_contact.yaw : finiteVector(m.target_yaw, 1, "target_yaw")[0];
  r.q0 = finiteVector(m.q, static_cast<size_t>(nq), "q");
  r.qd0 = finiteVector(m.qd, static_cast<size_t>(nq), "qd");
  if (!m.touchdown_com.empty()) {
    const Eigen::VectorXd c = finiteVector(m.touchdown_com, 4, "touchdown_com");
    r.touchdown_com = LipmState{c.head<2>(), c.tail<2>()};
  }
  r.make_contact_consistent = m.make_contact_consistent;
  r.check_reachability = m.check_reachability;
  r.solve_ocp = m.solve_ocp;
  auto horizon = [](const std::string& field, double h) {
    if (!std::isfinite(h) || h < 0.0 || h > kMaxTransitionHorizon) {
      std::ostringstream os;
      os << field << ": expected 0 (the default) or a horizon in (0, " << kMaxTransitionHorizon
         << "] s, got " << h;
      throw RequestError(os.str());
    }
    return h;
  };
  r.horizon = horizon("horizon", m.horizon);
  ReachConfig reach = base;
  if (!m.budgets.empty()) {
    if (m.budgets.size() != 3)
      throw RequestError("budgets: expected none or 3 (full, quick, hull), got " +
                         std::to_string(m.budgets.size()));
    reach.budgets.full = fromSampleBudgetMsg(m.budgets[0]);
    reach.budgets.quick = fromSampleBudgetMsg(m.budgets[1]);
    const SamplingBudget hull = fromSampleBudgetMsg(m.budgets[2]);
    reach.budgets.hull = {
        hull.initial_samples,  hull.children_per_parent, hull.backward_children_per_parent,
        hull.max_boundary,     hull.interior_samples,    hull.certificate_candidates,
        hull.constraint_margin};
  }
  if (horizon("reach_horizon", m.reach_horizon) > 0.0) reach.horizon = m.reach_horizon;
  if (m.seed < -1) throw RequestError("seed: expected -1 (the node's) or >= 0");
  if (m.seed >= 0) reach.seed = static_cast<std::uint64_t>(m.seed);
  try {
    reach.validate();
    reach.requireResourcesWithinLimits(nq);
  } catch (const ReachError& e) {
    throw RequestError(std::string("budgets/reach_horizon/seed: ") + e.what());
  }
  r.reach = reach;
  r.ocp_policy = parseName(kOcpPolicies, "ocp_policy", m.ocp_policy);
  r.on_infeasible = parseName(kInfeasiblePolicies, "on_infeasible", m.on_infeasible);
  if (!std::isfinite(m.time_budget) || m.time_budget < 0.0 || m.time_budget > kMaxTimeBudget) {
    std::ostringstream os;
    os << "time_budget: expected 0 (none) or a wall time in (0, " << kMaxTimeBudget << "] s, got "
       << m.time_budget;
    throw RequestError(os.str());
  }
  if (m.time_budget > 0.0) r.deadline = secondsAfter(SteadyClock::now(), m.time_budget);
  return r;
}

reach_trajopt::PlanFootstep::Response toPlanFootstepResponseMsg(const FootstepTransition& step,
                                                                const RobotModel& model,
                                                                const ContactConfig& contact,
                                                                const ros::Time& t0) {
  reach_trajopt::PlanFootstep::Response m;
  m.success = true;
  m.message = std::string(stepVerdictName(step.verdict)) + ": " + step.reason;
  m.kinematically_feasible = step.kinematically_feasible;
  m.kinematics_reason = step.check.kinematics.reason;
  m.reachable = step.reachable;
  m.certificate = certificateName(step.certificate);
  m.foothold_source = footholdSourceName(step.foothold_source);
  m.candidates_checked = static_cast<std::uint32_t>(step.candidates_checked);
  m.target_verdict = step.target_verdict ? stepVerdictName(*step.target_verdict) : "";
  m.verdict = stepVerdictName(step.verdict);
  m.reason = step.reason;
  m.hausdorff_distance = step.hausdorff_distance;
  m.check_time = step.check_time_s;
  m.ocp_time = step.ocp_time_s;
  m.check_passes = static_cast<std::uint32_t>(step.check_passes);
  m.foothold = toPointMsg(step.foothold);
  m.step_horizon = step.transition.horizon;
  const WitnessPath& w = step.check.reach.witness;
  m.witness_valid = w.valid;
  if (w.valid) m.witness_violation = pathViolationVector(w.violation);
  m.witness_position_gap = w.position_gap;
  m.witness_velocity_gap = w.velocity_gap;
  m.witness_terminal_position_gap = w.terminal_position_gap;
  m.witness_terminal_velocity_gap = w.terminal_velocity_gap;
  m.trajectory = toTransitionTrajectoryMsg(step.trajectory, model,
                                           {contact.left_sole_frame, contact.right_sole_frame}, t0);
  return m;
}

FootstepTransition fromPlanFootstepResponseMsg(const reach_trajopt::PlanFootstep::Response& m,
                                               const FootstepPlanRequest& request,
                                               const RobotModel& model) {
  FootstepTransition s;
  s.request = request;
  s.transition.stance = request.stance;
  s.kinematically_feasible = m.kinematically_feasible;
  s.check.kinematically_feasible = m.kinematically_feasible;
  s.check.kinematics.feasible = m.kinematically_feasible;
  s.check.kinematics.reason = m.kinematics_reason;
  s.reachable = m.reachable;
  s.check.reachable = m.reachable;
  s.certificate = valueOf(certificateNames(), m.certificate, "plan_footstep response: certificate");
  s.foothold_source =
      valueOf(footholdSourceNames(), m.foothold_source, "plan_footstep response: foothold_source");
  s.candidates_checked = static_cast<int>(m.candidates_checked);
  if (!m.target_verdict.empty())
    s.target_verdict =
        valueOf(stepVerdictNames(), m.target_verdict, "plan_footstep response: target_verdict");
  s.verdict = valueOf(stepVerdictNames(), m.verdict, "plan_footstep response: verdict");
  s.reason = m.reason;
  s.check.reason = m.reason;
  s.hausdorff_distance = m.hausdorff_distance;
  s.check_time_s = m.check_time;
  s.ocp_time_s = m.ocp_time;
  s.check_passes = static_cast<int>(m.check_passes);
  s.foothold = fromPointMsg(m.foothold);
  s.transition.horizon = m.step_horizon;
  WitnessPath& w = s.check.reach.witness;
  w.valid = m.witness_valid;
  if (w.valid) {
    w.violation = pathViolationFromVector(m.witness_violation, "plan_footstep");
  }
  w.position_gap = m.witness_position_gap;
  w.velocity_gap = m.witness_velocity_gap;
  w.terminal_position_gap = m.witness_terminal_position_gap;
  w.terminal_velocity_gap = m.witness_terminal_velocity_gap;
  s.trajectory = fromTransitionTrajectoryMsg(m.trajectory, model);
  return s;
}

}  // namespace ros_bridge
}  // namespace reach_trajopt
