#pragma once
/// \file cancelled.h
/// The error of a long computation cancelled by its caller through a progress callback (the
/// reachability check, reach/reach_progress.h; the transition OCP, ocp/ocp_progress.h).

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

/// Thrown by a check or a solve whose progress callback returned false.
class ReachCancelled : public ReachError {
 public:
  using ReachError::ReachError;
};

}  // namespace reach_trajopt
