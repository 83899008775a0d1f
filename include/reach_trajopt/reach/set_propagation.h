#pragma once
/// \file set_propagation.h
/// One direction of the reachability check (paper eq. 15-16 forward, 17-20 backward): from a
/// root state, `steps` slices dt apart, each made of the children of the previous slice's kept
/// samples (its boundary (21) plus interior picks), every child the solution of one contact QP
/// (ForwardStep / BackwardStep). The same routine serves both directions; only the step type,
/// the direction of time and the number of children per parent differ. A step whose children
/// are too few (most draws rejected, ReachConfig::redraw_rounds / redraw_below) draws another
/// round of children from the same parents, with new keys, before its slice is gathered.
///
/// Determinism: the draws of a child depend only on (seed, direction, step, parent, child) and
/// results are stored at fixed indices (round by round), so the slices are bit-identical for
/// any thread count.
///
/// Threads: the children of a slice are work items (a few children of one parent) that OpenMP
/// worker tasks claim. propagateSets() runs the forward and the backward direction side by side
/// in one team: while one direction does the serial part of a step (gathering the children, the
/// boundary selection (21)), the other one's children keep every thread busy, and neither waits
/// for the other between steps. A worker keeps to one direction while it has items.

#include <Eigen/Core>
#include <vector>

#include "reach_trajopt/reach/reach_context.h"
#include "reach_trajopt/reach/reach_progress.h"
#include "reach_trajopt/reach/sample_slice.h"

namespace reach_trajopt {

enum class PropagationDirection { kForward, kBackward };

/// What one direction of the check produced besides its slices.
struct PropagationStats {
  long samples = 0;               ///< kept samples over all slices (root excluded)
  long rejected = 0;              ///< draws that gave no sample
  long qps = 0;                   ///< QPs solved
  long prefiltered = 0;           ///< backward draws the prefilter rejected (before any QP)
  double boundary_time = 0.0;     ///< wall time of the boundary selection (21) [s]
  double propagation_time = 0.0;  ///< wall time of the rest [s]
};

/// Where one direction starts and how far it goes.
struct PropagationRoot {
  PropagationDirection direction = PropagationDirection::kForward;
  /// Time index of the root: slice j is at time (root_index + sign j) dt, sign +1 forward
  /// (root x_0 at index 0), -1 backward (root x_f at index i_t).
  int root_index = 0;
  Eigen::VectorXd q, qd;  ///< the root state (size n_q each)
  int steps = 0;          ///< slices to add after the root
};

/// One direction of the check: its root, then what propagateSets() made of it.
struct DirectionSet {
  PropagationRoot root;
  std::vector<SampleSlice> slices;  ///< out: the root slice followed by root.steps slices
  PropagationStats stats;           ///< out (wall times overlap the other directions')
};

/// Propagates every set from its root, all directions side by side in one OpenMP team (the
/// check: the forward set from x_0 and the backward set from x_f; the hull pass: the forward
/// set alone). A direction's slices are the same whatever runs beside it and for any thread
/// count.
/// \param threads   OpenMP threads (>= 1)
/// \param progress  called after each slice of any direction, never concurrently; false
///     cancels every direction (ReachCancelled); may be empty
void propagateSets(const ReachContext& ctx, const std::vector<DirectionSet*>& sets, int threads,
                   const ReachProgressCallback& progress = {});

/// The configuration q of sample `index` of slice `slice` (exact, from its parent's stored
/// configuration). \param semi_implicit  the forward integrator used (forward slices only)
Eigen::VectorXd sampleConfigurationOf(const std::vector<SampleSlice>& slices,
                                      PropagationDirection direction, double dt, bool semi_implicit,
                                      int slice, int index);

}  // namespace reach_trajopt
