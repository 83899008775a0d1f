#pragma once
/// \file reach_progress.h
/// Progress of a reachability check (reachability_analyzer.h) while it runs, for a caller that
/// reports it (e.g. an action server's feedback) or cancels a check that is no longer wanted
/// (e.g. a newer plan arrived). Reported after each propagated time slice of each direction;
/// the two directions run side by side, so their reports interleave and may come from any of
/// the check's OpenMP threads, never two at once. The sets do not depend on whether anyone
/// listens.

#include <functional>

#include "reach_trajopt/common/cancelled.h"

namespace reach_trajopt {

/// Where a check is: one direction's slices propagated so far and what they cost.
struct ReachProgress {
  bool forward = true;   ///< the direction of this slice (the two run side by side)
  int slices_done = 0;   ///< slices of this direction propagated (root excluded)
  int slices_total = 0;  ///< slices this direction propagates
  long samples = 0;      ///< samples kept so far in this direction (roots excluded)
  long qps = 0;          ///< QPs solved so far in this direction
};

/// Called with each ReachProgress; returns false to cancel the check (it then throws
/// ReachCancelled, common/cancelled.h, before the next slice).
using ReachProgressCallback = std::function<bool(const ReachProgress&)>;

}  // namespace reach_trajopt
