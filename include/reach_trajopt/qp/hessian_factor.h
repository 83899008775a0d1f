#pragma once
/// \file hessian_factor.h
/// The factorization of the QP Hessian that the dual active-set method starts from
/// (Goldfarb and Idnani 1983, section 3: G = L L^T and J = L^{-T}).

#include <Eigen/Core>
#include <string>

namespace reach_trajopt {
namespace qp {

/// @brief Cholesky factor G + rho I = L L^T and the inverse factor J0 = L^{-T} of a QP Hessian.
///
/// Compute it once and hand it to DualActiveSetQp::solve for every problem sharing G (e.g. the
/// children of one reachable-set parent, whose weights in eq. (15) are constant). Read-only
/// after compute(), so one factor may be shared by several threads' solvers.
class HessianFactor {
 public:
  /// Smallest accepted L_ii^2 / max_j G_jj: G with a smaller pivot is treated as singular.
  static constexpr double kMinPivotRatio = 1e-12;

  /// \param[in] n  number of variables (> 0); storage is allocated here, never in compute().
  /// \throws ReachError if n <= 0.
  explicit HessianFactor(int n);

  /// Factorizes G + regularization * I.
  /// \param[in] G  symmetric Hessian (n x n); only its lower triangle is read.
  /// \param[in] regularization  rho >= 0 added to the diagonal. With rho = 0 a G that is only
  ///     positive semi-definite is rejected; with rho > 0 the regularized problem is solved
  ///     (its solution differs from a minimizer of the singular problem by O(rho)).
  /// \return true on success; false (valid() false, message() saying why) if G has a wrong
  ///     size, a non-finite entry, or is not positive definite. Never throws, never allocates.
  bool compute(const Eigen::Ref<const Eigen::MatrixXd>& G, double regularization = 0.0);

  bool valid() const { return valid_; }
  /// Changes on every successful compute() (unique across all factors of the process), so a
  /// solver can tell that the factor it cached equality work for is still the same.
  unsigned long long id() const { return id_; }
  int size() const { return n_; }
  double regularization() const { return regularization_; }
  /// Lower-triangular Cholesky factor L (n x n; strict upper part is zero).
  const Eigen::MatrixXd& L() const { return L_; }
  /// Upper-triangular inverse factor J0 = L^{-T} (n x n), so G^{-1} = J0 J0^T.
  const Eigen::MatrixXd& J0() const { return J0_; }
  /// J0^T = L^{-1}, stored lower triangular so products with it need no transposed view.
  const Eigen::MatrixXd& J0t() const { return J0t_; }
  /// L^T, stored upper triangular (for 1/2 x^T G x = 1/2 |L^T x|^2).
  const Eigen::MatrixXd& Lt() const { return Lt_; }
  /// Why the last compute() failed (empty after a success).
  const std::string& message() const { return message_; }

 private:
  int n_;
  bool valid_ = false;
  unsigned long long id_ = 0;
  double regularization_ = 0.0;
  Eigen::MatrixXd L_;
  Eigen::MatrixXd J0_;
  Eigen::MatrixXd J0t_;
  Eigen::MatrixXd Lt_;
  std::string message_;
};

}  // namespace qp
}  // namespace reach_trajopt
