#pragma once
/// \file cli_args.h
/// Strict parsing of command-line option values for the tools: the whole text must be a number
/// in range, or a ReachError names the option ("--steps: expected an integer in [1, 1000], got
/// '5x'"). std::stoi / atoi accept "5x" as 5 and crash or wrap on "1e10"; these do not.

#include <string>

namespace reach_trajopt {

/// The value of `option` as a finite number in [lo, hi]. With `allow_nonfinite`, "nan" and
/// "inf" are returned as such (for a caller whose own validation names them).
double parseDoubleOption(const std::string& option, const std::string& text, double lo = -1e300,
                         double hi = 1e300, bool allow_nonfinite = false);
/// The value of `option` as an integer in [lo, hi] (decimal digits, optional sign).
long long parseIntOption(const std::string& option, const std::string& text, long long lo,
                         long long hi);
/// The number of threads asked by `option`: 0 (OpenMP's default) to the hardware threads of
/// this machine (more cannot run faster and each thread owns a workspace).
int parseThreadsOption(const std::string& option, const std::string& text);
/// Hardware threads of this machine (>= 1).
int hardwareThreads();
/// Empty when a config's `threads` (0: OpenMP's default) is at most hardwareThreads(), else
/// why not ("must be <= the 2 hardware threads of this machine (0: OpenMP's default), got 8"):
/// each thread owns a workspace, and more threads than the machine has cannot run faster.
std::string threadsBeyondHardware(int threads);

}  // namespace reach_trajopt
