/// \file window_comparison.cpp
/// The test (14) on the overlap window (see the header).

#include "reach_trajopt/reach/window_comparison.h"

#include <omp.h>

#include <algorithm>

#include "reach_trajopt/reach/output_hull.h"

namespace reach_trajopt {

std::vector<SliceComparison> compareWindow(const ReachConfig& config,
                                           const std::vector<SampleSlice>& forward,
                                           const std::vector<SampleSlice>& backward, int i_2,
                                           int i_1, int i_t) {
  const double dt = config.dt;
  std::vector<SliceComparison> window(std::max(0, i_1 - i_2 + 1));
  const int threads = config.threads > 0 ? config.threads : omp_get_max_threads();
  // Slices are independent and written at fixed indices: the same result for any thread count.
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (int i = i_2; i <= i_1; ++i) {
    SliceComparison& c = window[i - i_2];
    c.time = i * dt;
    c.forward_slice = i;
    c.backward_slice = i_t - i;
    const SampleSlice& F = forward[i];
    const SampleSlice& B = backward[i_t - i];
    c.distance = hausdorffDistance(F.output, B.output);
    const double K = c.distance.resolution();
    c.overlap_tolerance = std::min(K, config.overlap_gap_max);
    if (F.size() > 0 && B.size() > 0) {
      // Inside a hull up to the sampling resolution (a set touching a face, e.g. x_f's sole
      // on the ground plane that bounds the forward set, counts as inside).
      c.backward_inside_forward = OutputHull(F.output).countInside(B.output, c.overlap_tolerance);
      c.forward_inside_backward = OutputHull(B.output).countInside(F.output, c.overlap_tolerance);
    }
    c.overlap = c.distance.closest <= c.overlap_tolerance || c.backward_inside_forward > 0 ||
                c.forward_inside_backward > 0;
    c.within_delta = c.distance.hausdorff <= std::min(config.delta, K);
  }
  return window;
}

int decidingSlice(const std::vector<SliceComparison>& window, bool& passed) {
  int best = -1;
  passed = false;
  for (int k = 0; k < static_cast<int>(window.size()); ++k) {
    const SliceComparison& c = window[k];
    const bool ok = c.overlap || c.within_delta;
    if (c.distance.closest_a < 0) continue;
    if (best < 0 || (ok && !passed) ||
        (ok == passed && c.distance.closest < window[best].distance.closest)) {
      best = k;
      passed = ok;
    }
  }
  return best;
}

}  // namespace reach_trajopt
