#pragma once
/// \file dual_active_set_qp.h
/// The bundled dense QP solver: the dual active-set method of Goldfarb and Idnani,
/// "A numerically stable dual method for solving strictly convex quadratic programs",
/// Math. Programming 27 (1983) 1-33, used by the contact QP (15), the backward feasibility
/// QP (19) and the whole-body controller.
///
/// Problem and sign convention (used everywhere in the qp area and by qp_solve):
///
///     minimize    1/2 x^T G x + g^T x
///     subject to  A_eq x  = b_eq      (m_eq rows)
///                 A_in x >= b_in      (m_in rows)
///
/// with Lagrangian 1/2 x^T G x + g^T x - lambda_eq^T (A_eq x - b_eq) - lambda_in^T (A_in x - b_in),
/// so at the optimum   G x + g = A_eq^T lambda_eq + A_in^T lambda_in,  lambda_in >= 0,
/// lambda_in_j (A_in x - b_in)_j = 0.
///
/// Method: start from the unconstrained minimum x0 = -G^{-1} g; put the equality rows in the
/// active set with one Householder QR of L^{-1} A_eq^T (the paper's J = L^{-T} Q and R; cached
/// for the next solve with the same factor and A_eq), then the inequality rows of a warm start,
/// dropping warm-start rows whose multiplier comes out negative;
/// then repeat the paper's steps 1-2: pick the most violated inequality (violation divided by
/// the row norm), take dual/primal steps along z = J_2 J_2^T n_p, r = R^{-1} J_1^T n_p, dropping
/// blocking rows (Givens rotations restore R), and add it with one Householder reflector. Every
/// iterate is dual feasible, so "no violated constraint" is the optimum and "violated constraint
/// with z = 0 and no constraint to drop" proves infeasibility.

#include <Eigen/Core>
#include <vector>

#include "reach_trajopt/qp/hessian_factor.h"
#include "reach_trajopt/qp/qp_result.h"

namespace reach_trajopt {
namespace qp {

/// Settings of DualActiveSetQp. The defaults suit problems scaled to O(1)..O(1e3) entries.
struct QpSolverConfig {
  /// Limit on add/drop steps of one solve (each step costs O(n^2)); kIterationLimit beyond it.
  int max_iterations = 1000;
  /// An inequality is violated when A_in_j x - b_in_j < -tol_j with
  /// tol_j = feasibility_tol * (1 + |b_in_j| + |A_in_j| |x|). Smaller is more exact but lets
  /// rounding noise trigger extra (harmless) iterations; it bounds the primal residual.
  double feasibility_tol = 1e-10;
  /// A row is linearly dependent on the active rows when the part of L^{-1} a_j orthogonal to
  /// them is below dependence_tol * |L^{-1} a_j|. Dependent equality rows are skipped (their
  /// consistency is checked); a dependent violated inequality with nothing to drop means
  /// infeasible.
  double dependence_tol = 1e-10;
  /// rho >= 0 added to G's diagonal by the solve(G, ...) overload. 0 (default): a G that is
  /// only positive semi-definite gives kInvalidInput. > 0: the problem with G + rho I is solved.
  double regularization = 0.0;

  /// \throws ReachError naming the bad field.
  void validate() const;
};

/// @brief Dense dual active-set QP solver (Goldfarb-Idnani 1983) with warm start.
///
/// Sized once for n variables and at most m_eq_max / m_in_max rows; solve() then never
/// allocates (problems may have fewer rows than the maxima). Holds scratch state, so use one
/// object per thread. Inputs are never thrown on: bad input gives QpStatus::kInvalidInput with a
/// message.
class DualActiveSetQp {
 public:
  using MatrixRef = Eigen::Ref<const Eigen::MatrixXd>;
  using VectorRef = Eigen::Ref<const Eigen::VectorXd>;

  /// \throws ReachError if n <= 0, m_eq_max < 0, m_in_max < 0 or config is invalid.
  DualActiveSetQp(int n, int m_eq_max, int m_in_max, const QpSolverConfig& config = {});

  /// Solves the QP, factorizing G (n x n, symmetric, lower triangle read) first.
  /// \param[in] g  linear cost (dim n).
  /// \param[in] A_eq, b_eq  equality rows (m_eq x n, dim m_eq); m_eq = 0 allowed (any 0-row
  ///     matrix, or a 0 x 0 one).
  /// \param[in] A_in, b_in  inequality rows A_in x >= b_in (m_in x n, dim m_in); may be empty.
  /// \param[in] warm_start  optional active set of an earlier solve (combined numbering of
  ///     QpResult::active_set); only its inequality entries are used, invalid ones ignored.
  /// \return the solver's own result, valid until the next solve.
  const QpResult& solve(const MatrixRef& G, const VectorRef& g, const MatrixRef& A_eq,
                        const VectorRef& b_eq, const MatrixRef& A_in, const VectorRef& b_in,
                        const std::vector<int>* warm_start = nullptr);

  /// Same with a factorization of G computed beforehand (HessianFactor::compute), reused across
  /// problems that share G. The objective is evaluated with L (G + rho I = L L^T).
  /// When the factor (same HessianFactor::id()) and A_eq are those of the previous solve of this
  /// object, the QR of the equality rows (the paper's J and R after adding them) is reused, so
  /// children of one parent (same M, J, weights; new torque or right-hand sides) only pay for
  /// the inequality steps. A_eq is compared entry by entry (O(m_eq n)), so this is always safe.
  ///
  /// `matrices`: kUnchanged states that A_eq and A_in are the matrices of the previous solve
  /// (the caller's own storage, not a temporary; entries untouched since), as for the children of
  /// one parent whose step fills them once. Their finiteness check and A_in's row norms (O(m n) per
  /// solve) are then reused. It is honoured only when the previous solve checked matrices at the
  /// same addresses with the same sizes; otherwise the full check runs, as for kNew.
  enum class Matrices { kNew, kUnchanged };
  const QpResult& solve(const HessianFactor& factor, const VectorRef& g, const MatrixRef& A_eq,
                        const VectorRef& b_eq, const MatrixRef& A_in, const VectorRef& b_in,
                        const std::vector<int>* warm_start = nullptr,
                        Matrices matrices = Matrices::kNew);

  const QpResult& result() const { return result_; }
  const QpSolverConfig& config() const { return config_; }
  void setConfig(const QpSolverConfig& config);
  int numVariables() const { return n_; }
  int maxEqualities() const { return m_eq_max_; }
  int maxInequalities() const { return m_in_max_; }

 private:
  /// Sizes and finite entries of the input; the matrices' entries are not read when
  /// `matrices_checked` (see Matrices::kUnchanged). Remembers which matrices passed.
  bool checkInput(const VectorRef& g, const MatrixRef& A_eq, const VectorRef& b_eq,
                  const MatrixRef& A_in, const VectorRef& b_in, bool matrices_checked);
  /// The previous solve checked these very matrices (same addresses and sizes).
  bool sameCheckedMatrices(const MatrixRef& A_eq, const MatrixRef& A_in) const;
  void fail(QpStatus status, const char* format, ...);
  void run(const HessianFactor& factor, const VectorRef& g, const MatrixRef& A_eq,
           const VectorRef& b_eq, const MatrixRef& A_in, const VectorRef& b_in,
           const std::vector<int>* warm_start);
  using RowRef = Eigen::Ref<const Eigen::RowVectorXd, 0, Eigen::InnerStride<>>;
  /// Appends a row to the initial Householder QR; false if it is dependent on the active rows.
  bool householderAppend(const RowRef& a);
  /// Adds a row to the active set with J formed; false if it is dependent on the active rows.
  bool appendWithJ(const RowRef& a, int index);
  void formJ(const Eigen::MatrixXd& J0);
  /// x = x0 + J_1 R^{-T} w and u = R^{-1} R^{-T} w with w = b_A - N^T x0 (J formed).
  void solveOnActiveSet(const MatrixRef& A_eq, const VectorRef& b_eq, const MatrixRef& A_in,
                        const VectorRef& b_in);
  void addConstraint(int index);
  void dropConstraint(int position);
  /// run()'s parts. The equality rows as the initial active set (J formed), from the cache
  /// when the factor and A_eq are those of the last solve.
  void activateEqualities(const HessianFactor& factor, const MatrixRef& A_eq);
  /// False (status set) when a dependent equality row is inconsistent with the others at x.
  bool redundantEqualitiesHold(const MatrixRef& A_eq, const VectorRef& b_eq);
  /// Drops warm-start rows with negative multipliers until dual feasible.
  void dropNegativeMultipliers(const MatrixRef& A_eq, const VectorRef& b_eq, const MatrixRef& A_in,
                               const VectorRef& b_in);
  /// Step 1: the most violated inactive inequality per unit row norm (sets s_), -1 if none.
  int mostViolatedRow(const MatrixRef& A_in, const VectorRef& b_in);
  /// Step 2: primal and dual steps, dropping blocking rows, until row p is added; false
  /// (status set) at the iteration limit or when p cannot be satisfied.
  bool addViolatedRow(const MatrixRef& A_in, int p);
  void finish(const HessianFactor& factor, const VectorRef& g, int m_eq, int m_in);

  QpSolverConfig config_;
  int n_, m_eq_max_, m_in_max_;
  HessianFactor own_factor_;
  QpResult result_;

  // Goldfarb-Idnani state: q active rows, their combined indices, multipliers u, the paper's
  // J (n x n) and R (upper triangular, q x q used).
  int q_ = 0;
  int m_eq_ = 0;
  Eigen::MatrixXd J_, R_;
  Eigen::MatrixXd householder_;  // initial QR: column k holds reflector k below its diagonal
  Eigen::VectorXd tau_;
  const HessianFactor* factor_ = nullptr;  // factor of the current solve
  std::vector<int> active_;
  std::vector<char> is_active_;     // per inequality row
  std::vector<char> eq_redundant_;  // per equality row
  Eigen::VectorXd u_, x_, x0_, d_, z_, r_, w_, work_, s_, row_norm_;

  // The matrices the last checkInput passed (Matrices::kUnchanged): addresses, sizes and outer
  // strides; whether row_norm_ holds that A_in's row norms.
  struct CheckedMatrices {
    const double* A_eq = nullptr;
    const double* A_in = nullptr;
    long eq_rows = -1, eq_cols = -1, eq_stride = -1, in_rows = -1, in_cols = -1, in_stride = -1;
  };
  bool matrices_checked_ = false;
  CheckedMatrices checked_;
  bool row_norms_valid_ = false;

  // The active set after the equality rows, kept for the next solve with the same factor/A_eq.
  bool cache_valid_ = false;
  unsigned long long cache_factor_id_ = 0;
  int cache_m_eq_ = 0, cache_q_ = 0;
  Eigen::MatrixXd cache_A_eq_, cache_J_, cache_R_;
  std::vector<int> cache_active_;
  std::vector<char> cache_eq_redundant_;
};

/// The `matrices` argument of DualActiveSetQp::solve for a caller that refills its A_eq / A_in
/// now and then (a reach step's setParent) and solves several problems between refills (the
/// parent's children): kNew on the first solve after a refill, kUnchanged after it.
class MatricesSinceRefill {
 public:
  /// The caller has just rewritten its matrices.
  void refilled() { solved_ = false; }
  /// The argument for the solve about to run.
  DualActiveSetQp::Matrices nextSolve() {
    const bool solved = solved_;
    solved_ = true;
    return solved ? DualActiveSetQp::Matrices::kUnchanged : DualActiveSetQp::Matrices::kNew;
  }

 private:
  bool solved_ = false;
};

}  // namespace qp
}  // namespace reach_trajopt
