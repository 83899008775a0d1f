/// \file footstep_reachability.cpp
/// Kinematic feasibility, then the reachability check, of one footstep.

#include "reach_trajopt/reach/footstep_reachability.h"

#include <cmath>
#include <string>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/planner/double_support_velocity.h"

namespace reach_trajopt {

FootstepReachability::FootstepReachability(std::shared_ptr<const ReachabilityAnalyzer> analyzer,
                                           std::shared_ptr<const KinematicFeasibility> kinematics)
    : analyzer_(std::move(analyzer)), kinematics_(std::move(kinematics)) {
  if (!analyzer_ || !kinematics_) throw ReachError("FootstepReachability: null component");
}

FootstepCheckResult FootstepReachability::check(const ContactTransition& request) const {
  return check(request, analyzer_->config());
}

FootstepCheckResult FootstepReachability::kinematicStage(const ContactTransition& r) const {
  FootstepCheckResult out;
  out.kinematics =
      kinematics_->check(r.stance, r.stance_contact, r.target, r.q0, r.touchdown.pelvis_position);
  out.kinematically_feasible = out.kinematics.feasible;
  if (!out.kinematics.feasible) {
    out.reason =
        "unreachable: the foothold is kinematically infeasible (" + out.kinematics.reason + ")";
    return out;
  }
  out.qdf = touchdownVelocity(r, out.kinematics.q_f);
  out.reason = "kinematically feasible (reachability not checked)";
  return out;
}

Eigen::VectorXd FootstepReachability::touchdownVelocity(const ContactTransition& r,
                                                        const Eigen::VectorXd& qf) const {
  if (r.qdf.size()) return r.qdf;
  const RobotModel& m = analyzer_->model();
  const ContactConfig& c = analyzer_->contactConfig();
  return doubleSupportVelocity(
      m, qf, m.frameId(c.left_sole_frame), m.frameId(c.right_sole_frame),
      Eigen::Vector3d(r.touchdown.com_velocity.x(), r.touchdown.com_velocity.y(), 0.0));
}

bool FootstepReachability::derivedTouchdownWithinVelocityLimits(const ContactTransition& r,
                                                                const ReachConfig& config,
                                                                FootstepCheckResult& out) const {
  if (r.qdf.size()) return true;  // given: the analyzer refuses it when out of its limits
  const RobotModel& m = analyzer_->model();
  const Eigen::VectorXd qd_max = m.velocityLimits();
  for (int i = 0; i < m.nq(); ++i) {
    if (!(std::abs(out.qdf[i]) > qd_max[i] + config.limit_tolerance)) continue;
    out.reason =
        "unreachable: x_f, the posture moving with the predicted touchdown CoM velocity, "
        "exceeds the velocity limit of " +
        m.joints()[i].name + " (|qd| = " + std::to_string(std::abs(out.qdf[i])) + " > " +
        std::to_string(qd_max[i]) + ")";
    return false;
  }
  return true;
}

ReachProblem footstepProblem(const ContactTransition& r, const Eigen::VectorXd& q_f,
                             const Eigen::VectorXd& qd_f) {
  ReachProblem p;
  p.mode = ContactMode::singleSupport(r.stance);
  p.q0 = r.q0;
  p.qd0 = r.qd0;
  p.qf = q_f;
  p.qdf = qd_f;
  p.footholds[r.stance == Side::kLeft ? 0 : 1] = r.stance_contact.pose();
  p.target = r.target.pose();
  return p;
}

FootstepCheckResult FootstepReachability::check(const ContactTransition& r,
                                                const ReachConfig& config,
                                                const ReachProgressCallback& progress) const {
  FootstepCheckResult out = kinematicStage(r);
  if (!out.kinematically_feasible || !derivedTouchdownWithinVelocityLimits(r, config, out))
    return out;
  out.reach = analyzer_->check(footstepProblem(r, out.kinematics.q_f, out.qdf), config, progress);
  out.reachable = out.reach.reachable;
  out.reason = out.reach.reason;
  return out;
}

FootstepCheckResult FootstepReachability::checkPass(const ContactTransition& r,
                                                    const ReachConfig& config,
                                                    const CheckPass& pass,
                                                    const ReachProgressCallback& progress) const {
  FootstepCheckResult out = kinematicStage(r);
  if (!out.kinematically_feasible || !derivedTouchdownWithinVelocityLimits(r, config, out))
    return out;
  out.reach =
      analyzer_->checkPass(footstepProblem(r, out.kinematics.q_f, out.qdf), config, pass, progress);
  out.reachable = out.reach.reachable;
  out.reason = out.reach.reason;
  return out;
}

}  // namespace reach_trajopt
