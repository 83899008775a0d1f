#pragma once
/// \file stopwatch.h
/// Wall-clock durations of the stack's timed work (a check's passes, a step's plan, an OCP
/// solve, a walk) and its deadlines: seconds on the monotonic clock since a start point, until a
/// deadline, and the deadline a budget in seconds sets.

#include <chrono>

namespace reach_trajopt {

using SteadyClock = std::chrono::steady_clock;

/// Seconds (wall clock, monotonic) from `start` to now.
inline double secondsSince(SteadyClock::time_point start) {
  return std::chrono::duration<double>(SteadyClock::now() - start).count();
}

/// Seconds (wall clock, monotonic) from now until `deadline`; negative once it has passed.
inline double secondsUntil(SteadyClock::time_point deadline) {
  return std::chrono::duration<double>(deadline - SteadyClock::now()).count();
}

/// The time point `seconds` (finite) after `start`: a deadline set from a budget in seconds.
inline SteadyClock::time_point secondsAfter(SteadyClock::time_point start, double seconds) {
  return start +
         std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(seconds));
}

}  // namespace reach_trajopt
