#pragma once
/// \file matrix_error.h
/// How far an analytic Jacobian is from its finite-difference reference, row by row relative
/// to the reference's magnitude (rows of different units are compared each on its own scale).

#include <Eigen/Core>
#include <algorithm>

namespace reach_trajopt::testing {

/// max over rows r of max_c |A(r, c) - B(r, c)| / max(1, max_c |B(r, c)|).
inline double rowRelativeError(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  double e = 0.0;
  for (Eigen::Index r = 0; r < A.rows(); ++r) {
    const double scale = std::max(1.0, B.row(r).cwiseAbs().maxCoeff());
    e = std::max(e, (A.row(r) - B.row(r)).cwiseAbs().maxCoeff() / scale);
  }
  return e;
}

}  // namespace reach_trajopt::testing
