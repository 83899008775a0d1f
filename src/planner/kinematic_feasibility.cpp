#include "reach_trajopt/planner/kinematic_feasibility.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "reach_trajopt/common/config_fields.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/common/format_number.h"
#include "reach_trajopt/contact/contact_constraint.h"

namespace reach_trajopt {

namespace {

constexpr int kTaskRows = 18;  // left sole 6, right sole 6, pelvis position 3 (x, y zeroed when
                               // free), pelvis rotation 3

/// True when two rectangles (centre, heading, half extents hx, hy) intersect: separating axis
/// test over the four edge normals.
bool rectanglesOverlap(const Eigen::Vector2d& c1, double yaw1, const Eigen::Vector2d& c2,
                       double yaw2, double hx, double hy) {
  const Eigen::Matrix2d R1 = Eigen::Rotation2Dd(yaw1).toRotationMatrix();
  const Eigen::Matrix2d R2 = Eigen::Rotation2Dd(yaw2).toRotationMatrix();
  const Eigen::Vector2d d = c2 - c1;
  const Eigen::Vector2d h(hx, hy);
  for (const Eigen::Matrix2d* R : {&R1, &R2}) {
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d axis = R->col(k);
      const double r1 = (R1.transpose() * axis).cwiseAbs().dot(h);
      const double r2 = (R2.transpose() * axis).cwiseAbs().dot(h);
      if (std::abs(d.dot(axis)) > r1 + r2) return false;
    }
  }
  return true;
}

}  // namespace

void KinematicFeasibilityConfig::validate() const {
  if (pelvis_frame.empty()) throw ConfigError("KinematicFeasibilityConfig: empty pelvis_frame");
  fields().checkRanges(*this);
}

const ConfigFields<KinematicFeasibilityConfig>& KinematicFeasibilityConfig::fields() {
  using C = KinematicFeasibilityConfig;
  static const ConfigFields<C> f =
      ConfigFields<C>("KinematicFeasibilityConfig", "kinematic_feasibility",
                      "include/reach_trajopt/planner/kinematic_feasibility.h",
                      "Kinematic feasibility of the next contact (Sec. III-B): joint-limited IK, "
                      "both soles flat; the sole frames and sizes are those of `contact:`.")
          .add("pelvis_frame", &C::pelvis_frame, "", "frame held upright at the nominal height")
          .add("pelvis_height", &C::pelvis_height, "m", Range::positive(),
               "pelvis origin above the mean sole height; also the relaxed OCP's landing "
               "height (ocp.terminal_pelvis_height)")
          .add("position_tolerance", &C::position_tolerance, "m", Range::positive(),
               "max sole / pelvis height error accepted")
          .add("orientation_tolerance", &C::orientation_tolerance, "rad", Range::positive(),
               "max orientation error accepted")
          .add("max_iterations", &C::max_iterations, "", Range::atLeast(1),
               "Newton iterations (a few more per decade of tolerance)")
          .add("damping", &C::damping, "m^2", Range::positive(), "DLS damping lambda^2 floor")
          .add("max_joint_step", &C::max_joint_step, "rad or m", Range::positive(),
               "largest update per iteration")
          .add("sole_clearance", &C::sole_clearance, "m", Range::nonNegative(),
               "minimal gap between the two sole rectangles")
          .add("min_lateral_offset", &C::min_lateral_offset, "m", Range(),
               "swing sole centre towards its own side of the stance sole centre, at least this")
          .add("workspace_radius", &C::workspace_radius, "m", Range::positive(),
               "soles farther apart horizontally: an error, not a step")
          .add("workspace_height", &C::workspace_height, "m", Range::positive(),
               "same for the sole height difference");
  return f;
}

KinematicFeasibilityConfig KinematicFeasibilityConfig::fromYaml(const YamlSection& s) {
  return fields().read(s);
}

namespace {

/// Why a foothold is rejected before the IK (one foot through the other), or "" when not.
std::string geometricRejection(const KinematicFeasibilityConfig& config,
                               const ContactConfig& contact, Side stance,
                               const FlatContact& current, const FlatContact& planned,
                               const std::string& stance_name, const std::string& swing_name) {
  // Overlapping soles, or the swing sole across the stance sole.
  const double margin = 0.5 * config.sole_clearance;
  if (rectanglesOverlap(current.position.head<2>(), current.yaw, planned.position.head<2>(),
                        planned.yaw, contact.half_length + margin, contact.half_width + margin))
    return "planned " + swing_name + " overlaps the stance sole " + stance_name + " (clearance " +
           formatNumber(config.sole_clearance) + " m): one foot would pass through the other";
  const Eigen::Vector3d delta = planned.position - current.position;
  const Eigen::Vector2d offset =
      Eigen::Rotation2Dd(-current.yaw) * delta.head<2>();  // stance heading frame
  const double toward_swing = (opposite(stance) == Side::kLeft ? 1.0 : -1.0) * offset.y();
  if (toward_swing < config.min_lateral_offset)
    return "planned " + swing_name + " crosses to the far side of the stance sole " + stance_name +
           " (lateral offset " + formatNumber(toward_swing) + " m < " +
           formatNumber(config.min_lateral_offset) +
           " m): the swing leg would pass through the stance leg";
  return "";
}

/// One damped least-squares step toward e = 0 whose joints stay within [q_lo, q_hi]: a joint
/// that would cross its limit is clamped to it and the step is re-solved for the others.
void clampedStep(const Eigen::MatrixXd& J, const Eigen::Matrix<double, kTaskRows, 1>& e,
                 const Eigen::VectorXd& q, const Eigen::VectorXd& q_lo, const Eigen::VectorXd& q_hi,
                 double lambda, double max_step, std::vector<bool>& locked, Eigen::MatrixXd& Jf,
                 Eigen::VectorXd& dq) {
  const int n = static_cast<int>(q.size());
  Eigen::Matrix<double, kTaskRows, kTaskRows> JJt;
  std::fill(locked.begin(), locked.end(), false);
  dq.setZero();
  for (int pass = 0; pass <= n; ++pass) {
    Jf = J;
    Eigen::Matrix<double, kTaskRows, 1> rhs = -e;
    for (int i = 0; i < n; ++i) {
      if (locked[i]) {
        rhs -= J.col(i) * dq[i];
        Jf.col(i).setZero();
      }
    }
    JJt.noalias() = Jf * Jf.transpose();
    JJt.diagonal().array() += lambda;
    Eigen::VectorXd step = Jf.transpose() * JJt.ldlt().solve(rhs);
    const double biggest = step.cwiseAbs().maxCoeff();
    if (biggest > max_step) step *= max_step / biggest;
    bool clamped = false;
    for (int i = 0; i < n; ++i) {
      if (locked[i]) continue;
      dq[i] = step[i];
      const double qi = q[i] + dq[i];
      if (qi < q_lo[i] || qi > q_hi[i]) {
        dq[i] = std::clamp(qi, q_lo[i], q_hi[i]) - q[i];
        locked[i] = true;
        clamped = true;
      }
    }
    if (!clamped) break;
  }
}

/// Outcome of the IK iterations: position / orientation residual per task (left sole, right
/// sole, pelvis) [m, rad].
struct IkOutcome {
  bool converged = false;
  int iterations = 0;
  double task_pos[3] = {0, 0, 0}, task_rot[3] = {0, 0, 0};
};

/// Joint-limited IK of the three tasks from q (updated in place).
IkOutcome solveIk(const RobotModel& model, const ContactConstraint (&tasks)[3], bool pelvis_free,
                  const KinematicFeasibilityConfig& config, Eigen::VectorXd& q,
                  KinematicFeasibilityResult& result) {
  const int n = model.nq();
  const Eigen::VectorXd q_lo = model.positionLowerLimits();
  const Eigen::VectorXd q_hi = model.positionUpperLimits();
  Workspace ws(model);
  ContactConstraintTerms terms(n);
  Eigen::Matrix<double, kTaskRows, 1> e;
  Eigen::MatrixXd J(kTaskRows, n), Jf(kTaskRows, n);
  Eigen::VectorXd dq(n);
  std::vector<bool> locked(n);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  IkOutcome out;
  int it = 0;
  for (;; ++it) {
    model.update(ws, q, zero);
    for (int t = 0; t < 3; ++t) {
      tasks[t].evaluate(model, ws, terms);
      e.segment<6>(6 * t) = terms.phi;
      J.middleRows<6>(6 * t) = terms.J_phi;
      if (t == 2 && pelvis_free) {  // x, y free: zero rows (the damping keeps JJ^T regular)
        e.segment<2>(12).setZero();
        J.middleRows<2>(12).setZero();
      }
      out.task_pos[t] = e.segment<3>(6 * t).norm();
      out.task_rot[t] = terms.phi.tail<3>().norm();
    }
    result.position_residual = *std::max_element(out.task_pos, out.task_pos + 3);
    result.orientation_residual = *std::max_element(out.task_rot, out.task_rot + 3);
    if (result.position_residual <= config.position_tolerance &&
        result.orientation_residual <= config.orientation_tolerance) {
      out.converged = true;
      break;
    }
    if (it >= config.max_iterations) break;
    // Levenberg-style damping lambda^2 = damping + |e|^2: large far away (robust near the
    // reach boundary), vanishing at the solution (quadratic convergence).
    const double lambda = config.damping + e.squaredNorm();
    clampedStep(J, e, q, q_lo, q_hi, lambda, config.max_joint_step, locked, Jf, dq);
    q += dq;
    q = q.cwiseMax(q_lo).cwiseMin(q_hi);  // rounding
  }
  out.iterations = it;
  return out;
}

/// Why the IK failed: the task that missed most, by how much, and the joints at their limits.
std::string infeasibleReason(const RobotModel& model, const KinematicFeasibilityConfig& config,
                             const ContactConfig& contact, const IkOutcome& ik,
                             const Eigen::VectorXd& q) {
  const char* names[3] = {contact.left_sole_frame.c_str(), contact.right_sole_frame.c_str(),
                          config.pelvis_frame.c_str()};
  int worst = 0;
  for (int t = 1; t < 3; ++t) {
    if (ik.task_pos[t] + ik.task_rot[t] > ik.task_pos[worst] + ik.task_rot[worst]) worst = t;
  }
  std::ostringstream os;
  os << "kinematically infeasible: after " << ik.iterations << " IK iterations " << names[worst]
     << " misses its target by " << formatNumber(ik.task_pos[worst]) << " m and "
     << formatNumber(ik.task_rot[worst]) << " rad (tolerances " << config.position_tolerance
     << " m, " << config.orientation_tolerance << " rad)";
  const Eigen::VectorXd q_lo = model.positionLowerLimits();
  const Eigen::VectorXd q_hi = model.positionUpperLimits();
  std::string at_limits;
  for (int i = 0; i < model.nq(); ++i) {
    const auto& j = model.joints()[i];
    if (j.is_virtual) continue;
    const double tol = 1e-9;
    if (q[i] <= q_lo[i] + tol) at_limits += " " + j.name + " (lower)";
    if (q[i] >= q_hi[i] - tol) at_limits += " " + j.name + " (upper)";
  }
  if (!at_limits.empty()) os << "; joints at limits:" << at_limits;
  return os.str();
}

}  // namespace

KinematicFeasibility::KinematicFeasibility(std::shared_ptr<const RobotModel> model,
                                           const KinematicFeasibilityConfig& config,
                                           const ContactConfig& contact)
    : model_(std::move(model)), config_(config), contact_(contact) {
  if (!model_) throw ModelError("KinematicFeasibility: null robot model");
  config_.validate();
  contact_.validate();
  if (!model_->floatingBase()) {
    throw ModelError("KinematicFeasibility: model " + model_->source() +
                     " has no floating base (the pelvis must be free)");
  }
  left_sole_ = model_->frameId(contact_.left_sole_frame);
  right_sole_ = model_->frameId(contact_.right_sole_frame);
  pelvis_ = model_->frameId(config_.pelvis_frame);
}

KinematicFeasibilityResult KinematicFeasibility::check(
    Side stance, const FlatContact& current, const FlatContact& planned,
    const Eigen::VectorXd& q_init, const std::optional<Eigen::Vector3d>& pelvis_position) const {
  const RobotModel& model = *model_;
  const int n = model.nq();
  requireFinite("KinematicFeasibility: current contact position", current.position);
  requireFinite("KinematicFeasibility: planned contact position", planned.position);
  if (!std::isfinite(current.yaw) || !std::isfinite(planned.yaw)) {
    throw RequestError("KinematicFeasibility: non-finite contact yaw");
  }
  if (pelvis_position) requireFinite("KinematicFeasibility: pelvis position", *pelvis_position);
  if (q_init.size() != 0) {
    requireSize("KinematicFeasibility: q_init", q_init.size(), n);
    requireFinite("KinematicFeasibility: q_init", q_init);
  }
  const Side swing = opposite(stance);
  const std::string& stance_name = contact_.soleFrame(stance);
  const std::string& swing_name = contact_.soleFrame(swing);

  const Eigen::Vector3d delta = planned.position - current.position;
  if (delta.head<2>().norm() > config_.workspace_radius ||
      std::abs(delta.z()) > config_.workspace_height) {
    throw RequestError("KinematicFeasibility: step outside the workspace: planned " + swing_name +
                       " is " + formatNumber(delta.head<2>().norm()) + " m from " + stance_name +
                       " horizontally and " + formatNumber(delta.z()) + " m vertically (limits " +
                       formatNumber(config_.workspace_radius) + " m, " +
                       formatNumber(config_.workspace_height) + " m)");
  }

  KinematicFeasibilityResult result;
  result.qd_f = Eigen::VectorXd::Zero(n);
  const FlatContact& left = stance == Side::kLeft ? current : planned;
  const FlatContact& right = stance == Side::kLeft ? planned : current;
  const double yaw_mean = std::atan2(std::sin(left.yaw) + std::sin(right.yaw),
                                     std::cos(left.yaw) + std::cos(right.yaw));

  if (q_init.size() != 0) {
    result.q_f = q_init;
  } else {
    // A standing guess: joints mid-range, base between the soles at the nominal height.
    result.q_f = model.neutralConfiguration();
    result.q_f.head<2>() = 0.5 * (left.position + right.position).head<2>();
    result.q_f[2] = 0.5 * (left.position.z() + right.position.z()) + config_.pelvis_height;
    result.q_f[3] = yaw_mean;
    result.q_f[4] = result.q_f[5] = 0.0;
  }

  // One foot through the other.
  result.reason =
      geometricRejection(config_, contact_, stance, current, planned, stance_name, swing_name);
  if (!result.reason.empty()) {
    result.position_residual = result.orientation_residual =
        std::numeric_limits<double>::infinity();
    return result;
  }

  // ---- joint-limited IK: damped least squares with clamping ---------------------------------
  Eigen::Isometry3d pelvis_target = Eigen::Isometry3d::Identity();
  pelvis_target.linear() = Eigen::AngleAxisd(yaw_mean, Eigen::Vector3d::UnitZ()).matrix();
  pelvis_target.translation().z() =
      0.5 * (left.position.z() + right.position.z()) + config_.pelvis_height;
  if (pelvis_position) pelvis_target.translation() = *pelvis_position;
  const ContactConstraint tasks[3] = {ContactConstraint(left_sole_, left.pose()),
                                      ContactConstraint(right_sole_, right.pose()),
                                      ContactConstraint(pelvis_, pelvis_target)};
  const Eigen::VectorXd q_lo = model.positionLowerLimits();
  const Eigen::VectorXd q_hi = model.positionUpperLimits();
  result.q_f = result.q_f.cwiseMax(q_lo).cwiseMin(q_hi);

  const IkOutcome ik = solveIk(model, tasks, !pelvis_position, config_, result.q_f, result);
  result.iterations = ik.iterations;
  if (ik.converged) {
    result.feasible = true;
    return result;
  }
  result.reason = infeasibleReason(model, config_, contact_, ik, result.q_f);
  return result;
}

}  // namespace reach_trajopt
