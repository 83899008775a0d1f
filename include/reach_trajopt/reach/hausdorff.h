#pragma once
/// \file hausdorff.h
/// The Hausdorff distance of eq. (14) between two finite output sets, with the resolution
/// bound K of Prop. 2 and the closest pair, using k-d trees (nanoflann): O((N + M) log(N + M))
/// instead of O(N M).

#include <Eigen/Core>
#include <cmath>

namespace reach_trajopt {

/// Comparison of a forward set A and a backward set B (points are columns, same dimension).
struct SetDistance {
  double hausdorff = HUGE_VAL;     ///< d_H(A, B) of eq. (14) [m]; inf when a set is empty
  double a_to_b = HUGE_VAL;        ///< sup_a inf_b |a - b|
  double b_to_a = HUGE_VAL;        ///< sup_b inf_a |a - b|
  double resolution_a = HUGE_VAL;  ///< K(A) = max_a d_H({a}, A \ {a}); inf for < 2 points
  double resolution_b = HUGE_VAL;  ///< K(B)
  double resolution() const { return resolution_a < resolution_b ? resolution_a : resolution_b; }
  double closest = HUGE_VAL;           ///< min_{a, b} |a - b|
  int closest_a = -1, closest_b = -1;  ///< column indices of the closest pair
};

/// d_H, the directed distances, K(A), K(B) and the closest pair of two point sets
/// (n_y x N and n_y x M). Ties go to the lowest index, so the result is deterministic.
/// \throws ReachError when the dimensions differ or a point is not finite.
SetDistance hausdorffDistance(const Eigen::Ref<const Eigen::MatrixXd>& A,
                              const Eigen::Ref<const Eigen::MatrixXd>& B);

}  // namespace reach_trajopt
