#pragma once
/// \file stopwatch.h
/// Wall-clock durations of the stack's timed work (a check's passes, a step's plan, an OCP
/// solve, a walk): seconds elapsed on the monotonic clock since a start point.

#include <chrono>

namespace reach_trajopt {

using SteadyClock = std::chrono::steady_clock;

/// Seconds (wall clock, monotonic) from `start` to now.
inline double secondsSince(SteadyClock::time_point start) {
  return std::chrono::duration<double>(SteadyClock::now() - start).count();
}

}  // namespace reach_trajopt
