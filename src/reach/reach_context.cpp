/// \file reach_context.cpp
/// The shared, read-only data of one reachability check.

#include "reach_trajopt/reach/reach_context.h"

#include <algorithm>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

ReachContext::ReachContext(std::shared_ptr<const RobotModel> model_in, const ContactConfig& contact,
                           const ReachConfig& config_in, const SamplingBudget& budget_in,
                           const ContactMode& mode_in,
                           const std::optional<Eigen::Isometry3d> footholds[2],
                           const std::optional<Eigen::Isometry3d>& target)
    : model(std::move(model_in)),
      config(config_in),
      budget(budget_in),
      mode(mode_in),
      cone(contact) {
  if (!model) throw ReachError("ReachContext: null model");
  config.validate();
  budget.validate("budget");
  const RobotModel& md = *model;
  n = md.nq();
  nu = md.nu();
  floating = md.floatingBase();
  nc = mode.contactCount();
  if (floating && nc == 0)
    throw ReachError(
        "reachability: the mode has no contact (flight is not handled) for the "
        "floating-base model " +
        md.source());
  for (int s = 0; s < 2; ++s) {
    const Side side = s == 0 ? Side::kLeft : Side::kRight;
    if (!mode.inContact(side)) continue;
    const std::string& frame = s == 0 ? contact.left_sole_frame : contact.right_sole_frame;
    if (!footholds[s])
      throw ReachError(std::string("reachability: mode ") + mode.name() + " holds the " +
                       sideName(side) + " sole but no foothold was given for it");
    contacts.emplace_back(md, frame, *footholds[s]);
  }
  if (!config.output_frame.empty()) {
    output_frame = md.frameId(config.output_frame);
  } else {
    if (!mode.isSingleSupport())
      throw ReachError("reachability: output_frame is empty and mode " + mode.name() +
                       " has no swing sole: name the output frame");
    output_frame = md.frameId(contact.soleFrame(mode.swing()));
  }
  for (char c : config.output_axes) output_axes.push_back(c - 'x');
  if (mode.isSingleSupport() && target && std::isfinite(config.swing_ground_margin)) {
    swing_frame = md.frameId(contact.soleFrame(mode.swing()));
    ground_height = target->translation().z() - config.swing_ground_margin;
  }
  if (mode.isSingleSupport() && contact.leg_clearance) {
    legs = LegClearance(md, contact.left_sole_frame, contact.right_sole_frame);
    if (!legs.empty()) leg_margin = contact.legMarginFrom(HUGE_VAL);
  }
  q_min = md.positionLowerLimits();
  q_max = md.positionUpperLimits();
  qd_max = md.velocityLimits();
  u_max = md.effortLimits();
  for (int i = 0; i < n; ++i) {
    if (std::isfinite(q_min[i]) || std::isfinite(q_max[i])) finite_position.push_back(i);
    if (std::isfinite(qd_max[i])) finite_velocity.push_back(i);
  }
  for (int i = 0; i < nu; ++i)
    if (!(u_max[i] > 0.0) || !std::isfinite(u_max[i]))
      throw ReachError("reachability: joint " + md.joints()[n - nu + i].name +
                       " needs a positive finite effort limit (the input set U of (15))");
}

void ReachContext::output(const Workspace& ws, Eigen::Ref<Eigen::VectorXd> y,
                          Eigen::Ref<Eigen::VectorXd> y_rate) const {
  const Eigen::Vector3d p = model->framePose(ws, output_frame).translation();
  const Vector6d v = model->frameVelocity(ws, output_frame);
  for (int k = 0; k < ny(); ++k) {
    y[k] = p[output_axes[k]];
    y_rate[k] = v[output_axes[k]];
  }
}

bool ReachContext::stateConstraintsHold(const Workspace& ws) const {
  if (swing_frame >= 0 && model->framePose(ws, swing_frame).translation().z() < ground_height)
    return false;
  return !(leg_margin > -HUGE_VAL) || legs.separatedBy(*model, ws, leg_margin);
}

void ReachContext::startAt(const Eigen::Ref<const Eigen::VectorXd>& q0) {
  if (!(leg_margin > -HUGE_VAL)) return;
  leg_margin = std::min(leg_margin, legs.distanceAt(*model, q0));
}

bool ReachContext::withinLimits(const Eigen::Ref<const Eigen::VectorXd>& q,
                                const Eigen::Ref<const Eigen::VectorXd>& qd) const {
  const double tol = config.limit_tolerance;
  for (int i : finite_position)
    if (q[i] < q_min[i] - tol || q[i] > q_max[i] + tol) return false;
  for (int i : finite_velocity)
    if (std::abs(qd[i]) > qd_max[i] + tol) return false;
  return true;
}

}  // namespace reach_trajopt
