#pragma once
/// \file spline_fit.h
/// Warm start of the transition OCP: the least-squares fit of a sampled path (the reachability
/// witness, one sample per 1 ms) onto the cubic B-spline basis, with some control points held
/// at given values (the ones that encode x_0 and, in the strict problem, x_f):
///   min_c  sum_i |B(t_i) c - y_i|^2 + rho |D2 c|^2,
/// B the sparse basis matrix (four non-zeros per row), D2 the second differences of the control
/// points (keeps the problem full rank when the path does not cover every segment). The sparse
/// least-squares problem is solved by SuiteSparseQR (SPQR) on the stacked matrix: one
/// factorization, one solve per coordinate.

#include <Eigen/Core>
#include <vector>

#include "reach_trajopt/ocp/cubic_bspline.h"

namespace reach_trajopt {

/// Fits control points (K x d, one column per coordinate) to samples (N x d at times t, N).
/// \param fixed         K flags: true rows of `fixed_values` are kept, not fitted
/// \param fixed_values  K x d values of the fixed control points (other rows ignored)
/// \param regularization rho >= 0 (see file comment)
/// Throws ReachError on size mismatches, non-finite samples, times outside [0, T] or when
/// SPQR fails.
Eigen::MatrixXd fitSplineControlPoints(const CubicBSplineBasis& basis, const Eigen::VectorXd& times,
                                       const Eigen::MatrixXd& samples,
                                       const std::vector<bool>& fixed,
                                       const Eigen::MatrixXd& fixed_values, double regularization);

}  // namespace reach_trajopt
