#pragma once
/// \file error.h
/// The exception types of reach_trajopt. Every bad input (missing file, malformed URDF,
/// unknown frame, non-finite numbers, wrong sizes, invalid configuration) throws a ReachError
/// with a message naming the problem and where it was found; callers that need to tell the
/// cause apart catch one of its subclasses (ModelError, ConfigError, QpInputError,
/// RequestError). Nodes catch ReachError at their boundary, answer the request with the
/// message and keep serving.

#include <Eigen/Core>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace reach_trajopt {

/// Base of every error the library throws on bad input.
class ReachError : public std::runtime_error {
 public:
  explicit ReachError(const std::string& what) : std::runtime_error(what) {}
};

/// The robot description: a missing or malformed URDF, an unsupported joint, an unknown frame
/// or joint name.
class ModelError : public ReachError {
 public:
  using ReachError::ReachError;
};

/// A configuration file or struct: unknown keys, wrong types, values out of range.
class ConfigError : public ReachError {
 public:
  using ReachError::ReachError;
};

/// A QP given to the solver: wrong sizes or non-finite data.
class QpInputError : public ReachError {
 public:
  using ReachError::ReachError;
};

/// A request to a tool, a service or a planner: states, footholds, horizons, options.
class RequestError : public ReachError {
 public:
  using ReachError::ReachError;
};

/// Throws ReachError("<what>: expected size <expected>, got <actual>") when sizes differ.
inline void requireSize(const char* what, Eigen::Index actual, Eigen::Index expected) {
  if (actual != expected) {
    std::ostringstream os;
    os << what << ": expected size " << expected << ", got " << actual;
    throw ReachError(os.str());
  }
}

/// Throws ReachError naming the first non-finite entry of `v` (NaN or +-inf).
template <typename Derived>
void requireFinite(const char* what, const Eigen::DenseBase<Derived>& v) {
  if (!v.allFinite()) {
    for (Eigen::Index r = 0; r < v.rows(); ++r)
      for (Eigen::Index c = 0; c < v.cols(); ++c)
        if (!std::isfinite(v(r, c))) {
          std::ostringstream os;
          os << what << ": non-finite value " << v(r, c) << " at (" << r << ", " << c << ")";
          throw ReachError(os.str());
        }
  }
}

/// Throws ConfigError("<owner>: <name> must be positive and finite, got <v>") unless
/// 0 < v < inf (the check of a config struct's field).
inline void requirePositiveFinite(const char* owner, const char* name, double v) {
  if (!std::isfinite(v) || v <= 0.0) {
    std::ostringstream os;
    os << owner << ": " << name << " must be positive and finite, got " << v;
    throw ConfigError(os.str());
  }
}

}  // namespace reach_trajopt
