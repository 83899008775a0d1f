#pragma once
/// \file boundary_selection.h
/// Boundary samples of one time slice, eq. (21): the samples whose outputs lie on the boundary
/// of the slice's output set are the only ones propagated to the next step.
///
/// Rule (configurable through ReachConfig): for each look-ahead tau the points
/// y + tau * ydot are formed; in every coordinate plane of the output (one plane for a 2-D
/// output, the planes xy, xz, yz for 3-D) the 2-D convex hull vertices (Andrew's monotone
/// chain) are kept together with the farthest point from the centroid in each of
/// `angular_bins` sectors (so concave parts survive). A 1-D output keeps the extremes and
/// evenly spaced ranks. The candidate lists are merged round-robin up to max_boundary, so a
/// cap never drops a whole plane or look-ahead.

#include <Eigen/Core>
#include <vector>

namespace reach_trajopt {

/// Options of selectBoundary (a view of the ReachConfig fields it uses).
struct BoundaryRule {
  std::vector<double> lookahead = {0.0};  ///< tau values [s]
  int angular_bins = 16;                  ///< sectors per plane (0: hull only)
  int max_boundary = 96;                  ///< cap on the result
  /// OpenMP threads over the (tau, plane) hulls; the result is the same for any count.
  int threads = 1;
};

/// Indices (ascending) of the boundary samples of one slice.
/// \param y       outputs, n_y x N (n_y in 1..3)
/// \param y_rate  output rates, n_y x N
std::vector<int> selectBoundary(const Eigen::Ref<const Eigen::MatrixXd>& y,
                                const Eigen::Ref<const Eigen::MatrixXd>& y_rate,
                                const BoundaryRule& rule);

/// Indices of the 2-D convex hull vertices of the points (2 x N), counter-clockwise, collinear
/// points dropped; one index for coincident points. Andrew's monotone chain, O(N log N).
std::vector<int> convexHull2d(const Eigen::Ref<const Eigen::Matrix2Xd>& points);

}  // namespace reach_trajopt
