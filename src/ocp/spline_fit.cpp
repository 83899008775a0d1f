#include "reach_trajopt/ocp/spline_fit.h"

#include <Eigen/SPQRSupport>
#include <Eigen/SparseCore>
#include <cmath>
#include <sstream>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

namespace {

/// Throws RequestError on size mismatches, non-finite data or times outside [0, T].
void checkFitInput(const CubicBSplineBasis& basis, const Eigen::VectorXd& times,
                   const Eigen::MatrixXd& samples, const std::vector<bool>& fixed,
                   const Eigen::MatrixXd& fixed_values, double regularization) {
  const int K = basis.controlPoints();
  const int n = static_cast<int>(times.size());
  const int d = static_cast<int>(samples.cols());
  requireSize("fitSplineControlPoints: samples rows", samples.rows(), n);
  requireSize("fitSplineControlPoints: fixed flags", static_cast<Eigen::Index>(fixed.size()), K);
  requireSize("fitSplineControlPoints: fixed_values rows", fixed_values.rows(), K);
  requireSize("fitSplineControlPoints: fixed_values columns", fixed_values.cols(), d);
  requireFinite("fitSplineControlPoints: times", times);
  requireFinite("fitSplineControlPoints: samples", samples);
  if (!std::isfinite(regularization) || regularization < 0.0) {
    throw RequestError("fitSplineControlPoints: regularization must be >= 0");
  }
  const double tol = 1e-9 * basis.duration();
  for (int i = 0; i < n; ++i) {
    if (times[i] < -tol || times[i] > basis.duration() + tol) {
      std::ostringstream os;
      os << "fitSplineControlPoints: sample time " << times[i] << " s outside [0, "
         << basis.duration() << "] s";
      throw RequestError(os.str());
    }
  }
}

/// The stacked least-squares system [B; sqrt(rho) D2] c_free = rhs over the free control
/// points (`col`: column of each free one, -1 when fixed), fixed ones moved to the right.
void stackFitSystem(const CubicBSplineBasis& basis, const Eigen::VectorXd& times,
                    const Eigen::MatrixXd& samples, const std::vector<bool>& fixed,
                    const Eigen::MatrixXd& fixed_values, double regularization,
                    const std::vector<int>& col, int n_free, Eigen::SparseMatrix<double>& A,
                    Eigen::MatrixXd& rhs) {
  const int K = basis.controlPoints();
  const int n = static_cast<int>(times.size());
  const int d = static_cast<int>(samples.cols());
  const int n_reg = K - 2;  // second differences c_{k} - 2 c_{k+1} + c_{k+2}
  const double sr = std::sqrt(regularization);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(4 * n + 3 * n_reg);
  rhs = Eigen::MatrixXd::Zero(n + n_reg, d);
  for (int i = 0; i < n; ++i) {
    const CubicBSplineBasis::Row row = basis.evaluate(times[i]);
    rhs.row(i) = samples.row(i);
    for (int j = 0; j < 4; ++j) {
      const int k = row.first + j;
      if (row.value[j] == 0.0) continue;
      if (fixed[k]) {
        rhs.row(i) -= row.value[j] * fixed_values.row(k);
      } else {
        triplets.emplace_back(i, col[k], row.value[j]);
      }
    }
  }
  if (sr > 0.0) {
    const double w[3] = {sr, -2.0 * sr, sr};
    for (int r = 0; r < n_reg; ++r) {
      for (int j = 0; j < 3; ++j) {
        const int k = r + j;
        if (fixed[k]) {
          rhs.row(n + r) -= w[j] * fixed_values.row(k);
        } else {
          triplets.emplace_back(n + r, col[k], w[j]);
        }
      }
    }
  }
  A.resize(n + n_reg, n_free);
  A.setFromTriplets(triplets.begin(), triplets.end());
  A.makeCompressed();
}

}  // namespace

Eigen::MatrixXd fitSplineControlPoints(const CubicBSplineBasis& basis, const Eigen::VectorXd& times,
                                       const Eigen::MatrixXd& samples,
                                       const std::vector<bool>& fixed,
                                       const Eigen::MatrixXd& fixed_values, double regularization) {
  checkFitInput(basis, times, samples, fixed, fixed_values, regularization);
  const int K = basis.controlPoints();
  const int d = static_cast<int>(samples.cols());
  // Column index of each free control point.
  std::vector<int> col(K, -1);
  int n_free = 0;
  for (int k = 0; k < K; ++k) {
    if (!fixed[k]) col[k] = n_free++;
  }
  Eigen::MatrixXd c = fixed_values;
  if (n_free == 0) return c;

  Eigen::SparseMatrix<double> A;
  Eigen::MatrixXd rhs;
  stackFitSystem(basis, times, samples, fixed, fixed_values, regularization, col, n_free, A, rhs);
  Eigen::SPQR<Eigen::SparseMatrix<double>> qr;
  qr.compute(A);
  if (qr.info() != Eigen::Success) {
    throw ReachError("fitSplineControlPoints: SPQR factorization failed");
  }
  if (qr.rank() < n_free) {
    std::ostringstream os;
    os << "fitSplineControlPoints: the samples determine only " << qr.rank() << " of " << n_free
       << " free control points (use regularization > 0)";
    throw RequestError(os.str());
  }
  // One factorization, one solve per coordinate (Eigen's SPQR wrapper solves vectors).
  Eigen::MatrixXd free(n_free, d);
  for (int j = 0; j < d; ++j) {
    free.col(j) = qr.solve(rhs.col(j));
    if (qr.info() != Eigen::Success || !free.col(j).allFinite()) {
      throw ReachError("fitSplineControlPoints: SPQR solve failed");
    }
  }
  for (int k = 0; k < K; ++k) {
    if (!fixed[k]) c.row(k) = free.row(col[k]);
  }
  return c;
}

}  // namespace reach_trajopt
