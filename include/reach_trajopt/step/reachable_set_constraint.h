#pragma once
/// \file reachable_set_constraint.h
/// The reachable sets as the OCP's constraint (eq. 23): per forward slice of a check, the 2-D
/// convex hull of the swing sole's (x, y) outputs, A y <= b, grown by a margin, as a
/// ReachableSlice at the slice's time. Only the slices up to the witness's junction are used:
/// the certified witness passes through a sample of each of them, so it is a feasible point of
/// these rows, while after the junction the witness leaves the sampled sets (its bridge
/// closes the gap to x_f) and the sampled hulls under-approximate the true reachable set.

#include <vector>

#include "reach_trajopt/ocp/transition_request.h"
#include "reach_trajopt/reach/reachability_analyzer.h"

namespace reach_trajopt {

/// The time [s] after t_0 of the witness's junction (its bridge start: the last forward sample
/// it passes through); +inf without a valid, bridged witness.
double junctionTime(const WitnessPath& witness);

/// The slices of `result` at times 0 < t <= t_junction (the witness's bridge start; the whole
/// forward set without a witness), each hull grown by `margin` [m]. Empty when the output has
/// no x and y axes or a slice's hull is degenerate (that slice is skipped).
std::vector<ReachableSlice> reachableSetConstraint(const ReachResult& result,
                                                   const std::string& output_axes, double margin);

/// The slices of `slices` at times t <= t_junction of `witness` (all of them without a valid
/// witness): another check's hulls cut where this witness leaves the sampled sets (the step
/// planner's hull pass: its forward set, the quick pass's witness).
std::vector<ReachableSlice> slicesUpToJunction(std::vector<ReachableSlice> slices,
                                               const WitnessPath& witness);

/// `slices` with every half-space A_i y <= b_i moved outward by `extra` [m] (b_i += extra
/// |A_i|): hulls grown by that much more than their check's margin.
std::vector<ReachableSlice> grownSlices(std::vector<ReachableSlice> slices, double extra);

}  // namespace reach_trajopt
