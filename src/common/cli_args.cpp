/// \file cli_args.cpp
/// Strict option-value parsing (cli_args.h).

#include "reach_trajopt/common/cli_args.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <thread>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

double parseDoubleOption(const std::string& option, const std::string& text, double lo, double hi,
                         bool allow_nonfinite) {
  const char* s = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s, &end);
  std::ostringstream os;
  const bool finite = std::isfinite(v) && errno != ERANGE;
  if (allow_nonfinite && !finite && end != s && *end == '\0') return v;
  if (text.empty() || end == s || *end != '\0' || !finite) {
    os << option << ": expected a finite number, got '" << text << "'";
    throw RequestError(os.str());
  }
  if (v < lo || v > hi) {
    os << option << ": expected a number in [" << lo << ", " << hi << "], got " << text;
    throw RequestError(os.str());
  }
  return v;
}

long long parseIntOption(const std::string& option, const std::string& text, long long lo,
                         long long hi) {
  const char* s = text.c_str();
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(s, &end, 10);
  if (text.empty() || end == s || *end != '\0' || errno == ERANGE || v < lo || v > hi) {
    std::ostringstream os;
    os << option << ": expected an integer in [" << lo << ", " << hi << "], got '" << text << "'";
    throw RequestError(os.str());
  }
  return v;
}

int hardwareThreads() {
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : static_cast<int>(n);
}

std::string threadsBeyondHardware(int threads) {
  if (threads <= hardwareThreads()) return {};
  return "must be <= the " + std::to_string(hardwareThreads()) +
         " hardware threads of this machine (0: OpenMP's default), got " + std::to_string(threads);
}

int parseThreadsOption(const std::string& option, const std::string& text) {
  return static_cast<int>(parseIntOption(option, text, 0, hardwareThreads()));
}

}  // namespace reach_trajopt
