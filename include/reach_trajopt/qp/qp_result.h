#pragma once
/// \file qp_result.h
/// Status and result of the bundled dense QP (see dual_active_set_qp.h for the problem form and
/// the sign convention of the multipliers).

#include <Eigen/Core>
#include <string>
#include <vector>

namespace reach_trajopt {
namespace qp {

/// Outcome of one QP solve.
enum class QpStatus {
  kOptimal,         ///< x satisfies the KKT conditions within the configured tolerances
  kInfeasible,      ///< the constraints admit no point (Goldfarb-Idnani step 2(c), or
                    ///< inconsistent dependent equality rows)
  kIterationLimit,  ///< QpSolverConfig::max_iterations add/drop steps were not enough
  kInvalidInput     ///< wrong sizes, non-finite numbers, or G not positive definite
};

/// "optimal", "infeasible", "iteration_limit", "invalid_input" (the names used by qp_solve).
const char* toString(QpStatus status);

/// Everything a solve returns. The solver owns one, sized at construction, and overwrites it on
/// every solve without heap allocation (that is why the multiplier vector has capacity
/// m_eq_max + m_in_max and only its head is meaningful).
struct QpResult {
  QpStatus status = QpStatus::kInvalidInput;
  /// Primal solution (dim n). Finite whatever the status (zero for kInvalidInput; the last
  /// dual-feasible iterate for kInfeasible / kIterationLimit).
  Eigen::VectorXd x;
  /// 1/2 x^T G x + g^T x at x (for a regularized G, of the regularized problem).
  double objective = 0.0;
  /// Lagrange multipliers, storage of capacity m_eq_max + m_in_max: entries [0, m_eq) belong to
  /// the equality rows, [m_eq, m_eq + m_in) to the inequality rows; use eq() / in().
  Eigen::VectorXd multipliers;
  /// Indices of the active constraints in the same combined numbering: equality row i is i,
  /// inequality row j is m_eq + j. Equality rows found linearly dependent (redundant) are not in
  /// it. Pass it back as a warm start.
  std::vector<int> active_set;
  int iterations = 0;   ///< add and drop steps of the dual method (warm-start drops included)
  int m_eq = 0;         ///< number of equality rows of the problem solved
  int m_in = 0;         ///< number of inequality rows of the problem solved
  std::string message;  ///< human-readable reason, empty when optimal

  /// Multipliers of the equality rows (dim m_eq).
  Eigen::VectorBlock<const Eigen::VectorXd> eq() const { return multipliers.segment(0, m_eq); }
  /// Multipliers of the inequality rows (dim m_in), all >= 0 at an optimum.
  Eigen::VectorBlock<const Eigen::VectorXd> in() const { return multipliers.segment(m_eq, m_in); }
  /// All multipliers of the problem solved (dim m_eq + m_in): equalities then inequalities.
  Eigen::VectorBlock<const Eigen::VectorXd> all() const {
    return multipliers.segment(0, m_eq + m_in);
  }
};

}  // namespace qp
}  // namespace reach_trajopt
