#include "reach_trajopt/planner/tvr_planner.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "reach_trajopt/common/config_fields.h"
#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

namespace {

void requireFiniteValue(const char* name, double v) {
  if (!std::isfinite(v)) {
    std::ostringstream os;
    os << "TvrConfig: " << name << " must be finite, got " << v;
    throw ConfigError(os.str());
  }
}

void requireInterval(const char* name, double lo, double hi) {
  requireFiniteValue(name, lo);
  requireFiniteValue(name, hi);
  if (lo > hi) {
    std::ostringstream os;
    os << "TvrConfig: " << name << " interval is empty: [" << lo << ", " << hi << "]";
    throw ConfigError(os.str());
  }
}

}  // namespace

void TvrConfig::validate() const {
  fields().checkRanges(*this);
  requireInterval("foot_offset_x", foot_offset_x_min, foot_offset_x_max);
  requireInterval("foot_offset_y", foot_offset_y_min, foot_offset_y_max);
  requireInterval("com_speed", com_speed_min, com_speed_max);
}

const ConfigFields<TvrConfig>& TvrConfig::fields() {
  using C = TvrConfig;
  static const ConfigFields<C> f =
      ConfigFields<C>("TvrConfig", "planner", "include/reach_trajopt/planner/tvr_planner.h",
                      "TVR footstep planner (eq. 9-12), values of Sec. IV-A; sign convention of "
                      "docs/method.md Sec. 3.")
          .add("com_height", &C::com_height, "m", Range::positive(),
               "h of the LIPM (the walk uses the standing CoM height)")
          .add("gravity", &C::gravity, "m/s^2", Range::positive(), "g")
          .add("t_s", &C::t_s, "s", Range::positive(), "time to velocity reversal")
          .add("kappa_x", &C::kappa_x, "", Range(),
               "sagittal bias (< 0 stabilizes); the authors' code value: with the paper's -0.66 "
               "our robot walks in place but not forward")
          .add("kappa_y", &C::kappa_y, "", Range(), "lateral bias (the paper's)")
          .add("foot_offset_x_min", &C::foot_offset_x_min, "m",
               "heuristic bound: next sole x offset from the stance sole, in its heading")
          .add("foot_offset_x_max", &C::foot_offset_x_max, "m", ">= foot_offset_x_min")
          .add("foot_offset_y_min", &C::foot_offset_y_min, "m", Range::nonNegative(),
               "heuristic bound: |y| offset towards the swing side (a distance)")
          .add("foot_offset_y_max", &C::foot_offset_y_max, "m", ">= foot_offset_y_min")
          .add("com_speed_min", &C::com_speed_min, "m/s", Range::nonNegative(),
               "heuristic bound on the horizontal CoM speed the planner uses")
          .add("com_speed_max", &C::com_speed_max, "m/s", ">= com_speed_min")
          .removed("step_duration",
                   "removed: it had no effect on the gait; the step period is "
                   "walk.single_support_duration + walk.double_support_duration")
          .removed("heuristic_bounds",
                   "removed: the walk mode sets the heuristic bounds (baseline: on, "
                   "proposed: off)");
  return f;
}

TvrConfig TvrConfig::fromYaml(const YamlSection& s) { return fields().read(s); }

TvrPlanner::TvrPlanner(const TvrConfig& config)
    : config_((config.validate(), config)), lipm_(config.com_height, config.gravity) {}

Eigen::Matrix<double, 2, 4> TvrPlanner::gain() const {
  const double w = lipm_.omega();
  const double coth = 1.0 / std::tanh(w * config_.t_s);
  Eigen::Matrix<double, 2, 4> K = Eigen::Matrix<double, 2, 4>::Zero();
  K(0, 0) = 1.0 - config_.kappa_x;
  K(1, 1) = 1.0 - config_.kappa_y;
  K(0, 2) = K(1, 3) = coth / w;
  return K;
}

TvrStep TvrPlanner::plan(const TvrInput& in) const {
  requireFinite("TvrPlanner::plan CoM position", in.com.p);
  requireFinite("TvrPlanner::plan CoM velocity", in.com.pd);
  requireFinite("TvrPlanner::plan p_des", in.p_des);
  requireFinite("TvrPlanner::plan stance sole position", in.stance);
  if (!std::isfinite(in.stance_yaw)) throw RequestError("TvrPlanner::plan: non-finite stance yaw");

  const Eigen::Vector2d kappa(config_.kappa_x, config_.kappa_y);
  const double w = lipm_.omega();
  const double coth = 1.0 / std::tanh(w * config_.t_s);
  const auto contact = [&](const Eigen::Vector2d& pd) -> Eigen::Vector2d {
    return in.com.p + pd * (coth / w) + kappa.cwiseProduct(in.p_des - in.com.p);
  };

  TvrStep out;
  out.alpha_tvr = contact(in.com.pd);
  out.com_velocity_used = in.com.pd;
  if (config_.heuristic_bounds) {
    const double speed = in.com.pd.norm();
    const double bounded = std::clamp(speed, config_.com_speed_min, config_.com_speed_max);
    if (bounded != speed && speed > 0.0) {
      out.com_velocity_used = in.com.pd * (bounded / speed);
      out.speed_clipped = true;
    }
  }
  out.alpha = contact(out.com_velocity_used);

  if (config_.heuristic_bounds)
    out.alpha = boundedContact(out.alpha, in.stance, in.stance_yaw, in.swing, &out.offset_clipped);
  out.offset = Eigen::Rotation2Dd(in.stance_yaw).inverse() * (out.alpha - in.stance);
  return out;
}

Eigen::Vector2d TvrPlanner::boundedContact(const Eigen::Vector2d& alpha,
                                           const Eigen::Vector2d& stance, double stance_yaw,
                                           Side swing, bool* clipped) const {
  requireFinite("TvrPlanner::boundedContact contact", alpha);
  requireFinite("TvrPlanner::boundedContact stance sole position", stance);
  const Eigen::Rotation2Dd heading(stance_yaw);
  const Eigen::Vector2d offset = heading.inverse() * (alpha - stance);
  const double sign = swing == Side::kLeft ? 1.0 : -1.0;
  Eigen::Vector2d o = offset;
  o.x() = std::clamp(o.x(), config_.foot_offset_x_min, config_.foot_offset_x_max);
  o.y() = sign * std::clamp(sign * o.y(), config_.foot_offset_y_min, config_.foot_offset_y_max);
  if (clipped) *clipped = o != offset;
  return o == offset ? alpha : Eigen::Vector2d(stance + heading * o);
}

Eigen::Matrix4d TvrPlanner::closedLoopMatrix(double T) const {
  if (!std::isfinite(T) || T <= 0.0) {
    throw RequestError("TvrPlanner: step duration must be positive and finite, got " +
                       std::to_string(T));
  }
  return lipm_.A(T) + lipm_.B(T) * gain();
}

TvrStabilityReport TvrPlanner::stability(double T) const {
  TvrStabilityReport r;
  r.closed_loop = closedLoopMatrix(T);
  // The map is decoupled per axis: states (px, pdx) = indices (0, 2) and (py, pdy) = (1, 3).
  for (int axis = 0; axis < 2; ++axis) {
    const double a = r.closed_loop(axis, axis), b = r.closed_loop(axis, axis + 2);
    const double c = r.closed_loop(axis + 2, axis), d = r.closed_loop(axis + 2, axis + 2);
    const double half_trace = 0.5 * (a + d), det = a * d - b * c;
    const std::complex<double> root =
        std::sqrt(std::complex<double>(half_trace * half_trace - det));
    r.eigenvalues[2 * axis] = half_trace + root;
    r.eigenvalues[2 * axis + 1] = half_trace - root;
  }
  r.spectral_radius = r.eigenvalues.cwiseAbs().maxCoeff();
  // A marginal eigenvalue (|lambda| = 1 up to rounding, e.g. at T = 2 t_s) is not stable.
  r.stable = r.spectral_radius < 1.0 - 1e-9;
  return r;
}

std::string TvrStabilityReport::summary() const {
  std::ostringstream os;
  os << "TVR step map (12): eigenvalues";
  for (int i = 0; i < 4; ++i) {
    os << " " << eigenvalues[i].real();
    if (eigenvalues[i].imag() != 0.0)
      os << (eigenvalues[i].imag() > 0 ? "+" : "") << eigenvalues[i].imag() << "i";
  }
  os << ", spectral radius " << spectral_radius << " -> ";
  if (stable) {
    os << "stable";
  } else if (std::abs(spectral_radius - 1.0) <= 1e-9) {
    os << "NOT STABLE (marginal: |lambda| = 1)";
  } else {
    os << "UNSTABLE";
  }
  return os.str();
}

TvrStep TvrPlanner::planFromMeasured(const LipmState& measured, const Eigen::Vector2d& stance,
                                     Side swing, double t, double remaining, double x_start,
                                     double forward_speed, double y_mid, TvrInput* input) const {
  TvrInput in;
  in.com = lipm_.propagate(measured, stance, remaining);
  in.p_des = Eigen::Vector2d(x_start + forward_speed * (t + remaining), y_mid);
  in.stance = stance;
  in.stance_yaw = 0.0;
  in.swing = swing;
  if (input) *input = in;
  return plan(in);
}

}  // namespace reach_trajopt
