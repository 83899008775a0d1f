#pragma once
/// \file window_comparison.h
/// The test (14) of the reachability check on the overlap window [t_2, t_1]: per slice, the
/// Hausdorff distance between the forward and backward output sets (k-d trees), the resolution
/// K of Prop. 2, the closest pair and the convex-hull overlap of the two sets; then the slice
/// that decides the verdict (an overlapping slice, else the closest approach).

#include <vector>

#include "reach_trajopt/reach/hausdorff.h"
#include "reach_trajopt/reach/reach_config.h"
#include "reach_trajopt/reach/sample_slice.h"

namespace reach_trajopt {

/// The test (14) on one slice of the overlap window.
struct SliceComparison {
  double time = 0.0;               ///< t - t_0 [s]
  int forward_slice = 0;           ///< index into ReachResult::forward
  int backward_slice = 0;          ///< index into ReachResult::backward
  SetDistance distance;            ///< d_H, directed distances, K's, closest pair
  double overlap_tolerance = 0.0;  ///< min(K, overlap_gap_max) [m]
  /// Backward outputs inside the forward set's convex hull (up to overlap_tolerance).
  int backward_inside_forward = 0;
  int forward_inside_backward = 0;  ///< forward outputs inside the backward set's hull
  /// A sample of one set inside the other's hull, or closest <= overlap_tolerance.
  bool overlap = false;
  bool within_delta = false;  ///< d_H <= min(delta, K) (Prop. 2)
};

/// Compares slices i_2 .. i_1 of the forward set with the backward slices of the same times
/// (backward slice i_t - i at time i dt).
/// \param forward, backward  the two sets (slice 0 = x_0, resp. x_f)
std::vector<SliceComparison> compareWindow(const ReachConfig& config,
                                           const std::vector<SampleSlice>& forward,
                                           const std::vector<SampleSlice>& backward, int i_2,
                                           int i_1, int i_t);

/// Index into `window` of the deciding slice: the first slice that passes the test
/// (overlap or Prop. 2) with the closest pair, else the closest approach; -1 when every slice
/// has an empty set. `passed` tells whether that slice passes the test.
int decidingSlice(const std::vector<SliceComparison>& window, bool& passed);

}  // namespace reach_trajopt
