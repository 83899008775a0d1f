#pragma once
/// \file minimum_jerk.h
/// The minimum-jerk blend of the swing references: b(s) = 10 s^3 - 15 s^4 + 6 s^5 of
/// s = (t - t0) / T, clamped to [0, 1], and its first two time derivatives (zero at both ends).

#include <algorithm>

namespace reach_trajopt {

struct MinimumJerkBlend {
  double b;    ///< in [0, 1]
  double bd;   ///< db/dt [1/s]
  double bdd;  ///< d2b/dt2 [1/s^2]
};

/// The blend at time t [s] of a transition that starts at t0 [s] and lasts T > 0 [s].
inline MinimumJerkBlend minimumJerk(double t, double t0, double T) {
  const double s = std::clamp((t - t0) / T, 0.0, 1.0);
  return {s * s * s * (10 - 15 * s + 6 * s * s), 30 * s * s * (1 - s) * (1 - s) / T,
          60 * s * (1 - s) * (1 - 2 * s) / (T * T)};
}

}  // namespace reach_trajopt
