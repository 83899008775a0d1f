/// \file capture_limits.cpp
/// Koolen et al.'s N-step capture regions of the LIPM with a finite foot (see the header).

#include "reach_trajopt/planner/capture_limits.h"

#include <cmath>
#include <string>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/planner/tvr_planner.h"

namespace reach_trajopt {
namespace {

void requireInRange(const char* name, double value, double lo, bool strict) {
  if (!std::isfinite(value) || (strict ? !(value > lo) : !(value >= lo)))
    throw RequestError(std::string("capture model: ") + name + " must be finite and " +
                       (strict ? "> " : ">= ") + std::to_string(lo) + " (got " +
                       std::to_string(value) + ")");
}

/// Support function of the sole's rectangle in direction (cos theta, sin theta) [m].
double soleExtent(const CaptureModel& m, double theta) {
  return m.sole_half_length * std::abs(std::cos(theta)) +
         m.sole_half_width * std::abs(std::sin(theta));
}

/// Support function of the step bounds, the leg on the side of the push stepping [m].
double stepReach(const CaptureModel& m, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  return (c >= 0.0 ? m.step_forward_max : m.step_backward_max) * std::abs(c) +
         m.step_lateral_max * std::abs(s);
}

}  // namespace

void CaptureModel::validate() const {
  requireInRange("com_height", com_height, 0.0, true);
  requireInRange("gravity", gravity, 0.0, true);
  requireInRange("min_swing_time", min_swing_time, 0.0, false);
  requireInRange("sole_half_length", sole_half_length, 0.0, false);
  requireInRange("sole_half_width", sole_half_width, 0.0, false);
  requireInRange("stance_half_separation", stance_half_separation, 0.0, false);
  requireInRange("step_forward_max", step_forward_max, 0.0, false);
  requireInRange("step_backward_max", step_backward_max, 0.0, false);
  requireInRange("step_lateral_max", step_lateral_max, 0.0, false);
}

CaptureModel CaptureModel::fromConfigs(const TvrConfig& tvr, const ContactConfig& contact,
                                       double swing_time) {
  CaptureModel m;
  m.com_height = tvr.com_height;
  m.gravity = tvr.gravity;
  m.min_swing_time = swing_time;
  m.sole_half_length = contact.half_length;
  m.sole_half_width = contact.half_width;
  m.step_forward_max = std::max(0.0, tvr.foot_offset_x_max);
  m.step_backward_max = std::max(0.0, -tvr.foot_offset_x_min);
  m.step_lateral_max = tvr.foot_offset_y_max;
  return m;
}

double CaptureModel::omega() const { return std::sqrt(gravity / com_height); }

double captureRegionRadius(const CaptureModel& model, double theta, int steps) {
  if (steps < 0) throw RequestError("captureRegionRadius: steps must be >= 0");
  const double d0 = soleExtent(model, theta);
  const double l = stepReach(model, theta);
  const double decay = std::exp(-model.omega() * model.min_swing_time);
  double d = d0;
  for (int n = 1; n <= steps; ++n) d = (d + l - d0) * decay + d0;
  return d;
}

CaptureLimits captureLimits(const CaptureModel& model, double theta) {
  model.validate();
  if (!std::isfinite(theta)) throw RequestError("captureLimits: direction must be finite");
  const double w = model.omega();
  const double d0 = soleExtent(model, theta);
  const double l = stepReach(model, theta);
  const double decay = std::exp(-w * model.min_swing_time);
  CaptureLimits c;
  c.direction = theta;
  c.zero_step = w * (d0 + model.stance_half_separation * std::abs(std::sin(theta)));
  c.one_step = w * captureRegionRadius(model, theta, 1);
  // The fixed point of d_N's recursion; no swing time (decay 1): unbounded.
  c.n_step = decay < 1.0 ? w * (d0 + (l - d0) * decay) / (1.0 - decay) : HUGE_VAL;
  return c;
}

}  // namespace reach_trajopt
