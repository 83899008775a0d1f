/// \file step_timing.cpp
/// Step-timing adaptation of the TVR step (see the header).

#include "reach_trajopt/planner/step_timing.h"

#include <cmath>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/planner/tvr_planner.h"

namespace reach_trajopt {

StepTiming adaptStepTiming(const TvrPlanner& planner, const LipmState& com,
                           const Eigen::Vector2d& stance, Side swing, double t, double x_start,
                           double forward_speed, double y_mid, const StepTimingRange& range) {
  if (!(range.nominal > 0.0) || !(range.min > 0.0) || !(range.min <= range.nominal) ||
      !(range.nominal <= range.max) || !std::isfinite(range.max) || !(range.resolution > 0.0))
    throw RequestError(
        "adaptStepTiming: the swing durations need 0 < min <= nominal <= max (finite) and a "
        "resolution > 0");
  // a(T) and its distance to the bounds' rectangle.
  const auto evaluate = [&](double T) {
    StepTiming s;
    s.swing_duration = T;
    s.foothold =
        planner.planFromMeasured(com, stance, swing, t, T, x_start, forward_speed, y_mid).alpha_tvr;
    s.bound_violation =
        (planner.boundedContact(s.foothold, stance, 0.0, swing) - s.foothold).norm();
    return s;
  };
  StepTiming best = evaluate(range.nominal);
  const double nominal_violation = best.bound_violation;
  // Outward from the nominal duration, so that the first of equal distances is the nearest.
  const int n = static_cast<int>(
      std::ceil(std::max(range.nominal - range.min, range.max - range.nominal) / range.resolution));
  for (int k = 1; k <= n && best.bound_violation > 0.0; ++k) {
    for (const double T :
         {range.nominal - k * range.resolution, range.nominal + k * range.resolution}) {
      if (T < range.min - 1e-12 || T > range.max + 1e-12) continue;
      const StepTiming s = evaluate(T);
      if (s.bound_violation < best.bound_violation - 1e-9) best = s;
    }
  }
  best.nominal_violation = nominal_violation;
  return best;
}

}  // namespace reach_trajopt
