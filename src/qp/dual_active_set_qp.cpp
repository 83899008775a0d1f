#include "reach_trajopt/qp/dual_active_set_qp.h"

#include <Eigen/Householder>
#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>
#include <string>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {
namespace qp {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

int checkedVariables(int n) {
  if (n <= 0)
    throw QpInputError("DualActiveSetQp: number of variables must be > 0, got " +
                       std::to_string(n));
  return n;
}

// Rotates columns a and b of M by the Givens rotation (c, s): the same rotation that maps
// (v_a, v_b) to (c v_a + s v_b, -s v_a + c v_b) on J^T n, so J = L^{-T} Q stays consistent.
void rotateColumns(Eigen::MatrixXd& M, int a, int b, double c, double s) {
  double* ca = M.col(a).data();
  double* cb = M.col(b).data();
  const Eigen::Index rows = M.rows();
  for (Eigen::Index i = 0; i < rows; ++i) {
    const double t = ca[i];
    ca[i] = c * t + s * cb[i];
    cb[i] = c * cb[i] - s * t;
  }
}

}  // namespace

const char* toString(QpStatus status) {
  switch (status) {
    case QpStatus::kOptimal:
      return "optimal";
    case QpStatus::kInfeasible:
      return "infeasible";
    case QpStatus::kIterationLimit:
      return "iteration_limit";
    case QpStatus::kInvalidInput:
      return "invalid_input";
  }
  return "unknown";
}

void QpSolverConfig::validate() const {
  if (max_iterations < 0)
    throw ConfigError("QpSolverConfig.max_iterations must be >= 0, got " +
                      std::to_string(max_iterations));
  if (!std::isfinite(feasibility_tol) || feasibility_tol < 0.0)
    throw ConfigError("QpSolverConfig.feasibility_tol must be finite and >= 0, got " +
                      std::to_string(feasibility_tol));
  if (!std::isfinite(dependence_tol) || dependence_tol < 0.0 || dependence_tol >= 1.0)
    throw ConfigError("QpSolverConfig.dependence_tol must be in [0, 1), got " +
                      std::to_string(dependence_tol));
  if (!std::isfinite(regularization) || regularization < 0.0)
    throw ConfigError("QpSolverConfig.regularization must be finite and >= 0, got " +
                      std::to_string(regularization));
}

DualActiveSetQp::DualActiveSetQp(int n, int m_eq_max, int m_in_max, const QpSolverConfig& config)
    : config_(config),
      n_(checkedVariables(n)),
      m_eq_max_(m_eq_max),
      m_in_max_(m_in_max),
      own_factor_(n) {
  if (m_eq_max < 0 || m_in_max < 0)
    throw QpInputError("DualActiveSetQp: row maxima must be >= 0, got m_eq_max " +
                       std::to_string(m_eq_max) + ", m_in_max " + std::to_string(m_in_max));
  config_.validate();
  result_.x = Eigen::VectorXd::Zero(n);
  result_.multipliers = Eigen::VectorXd::Zero(m_eq_max + m_in_max);
  result_.active_set.reserve(n);
  result_.message.reserve(512);
  J_ = Eigen::MatrixXd::Zero(n, n);
  R_ = Eigen::MatrixXd::Zero(n, n);
  householder_ = Eigen::MatrixXd::Zero(n, n);
  tau_ = Eigen::VectorXd::Zero(n);
  active_.assign(n, -1);
  is_active_.assign(m_in_max, 0);
  eq_redundant_.assign(m_eq_max, 0);
  u_ = Eigen::VectorXd::Zero(n + 1);
  x_ = Eigen::VectorXd::Zero(n);
  x0_ = Eigen::VectorXd::Zero(n);
  d_ = Eigen::VectorXd::Zero(n);
  z_ = Eigen::VectorXd::Zero(n);
  r_ = Eigen::VectorXd::Zero(n);
  w_ = Eigen::VectorXd::Zero(n);
  work_ = Eigen::VectorXd::Zero(n);
  s_ = Eigen::VectorXd::Zero(m_in_max);
  row_norm_ = Eigen::VectorXd::Zero(m_in_max);
  cache_A_eq_ = Eigen::MatrixXd::Zero(m_eq_max, n);
  cache_J_ = Eigen::MatrixXd::Zero(n, n);
  cache_R_ = Eigen::MatrixXd::Zero(n, n);
  cache_active_.assign(n, -1);
  cache_eq_redundant_.assign(m_eq_max, 0);
}

void DualActiveSetQp::setConfig(const QpSolverConfig& config) {
  config.validate();
  config_ = config;
}

void DualActiveSetQp::fail(QpStatus status, const char* format, ...) {
  char buf[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof(buf), format, args);
  va_end(args);
  result_.status = status;
  result_.message.assign(buf);
}

bool DualActiveSetQp::sameCheckedMatrices(const MatrixRef& A_eq, const MatrixRef& A_in) const {
  return matrices_checked_ && checked_.A_eq == A_eq.data() && checked_.A_in == A_in.data() &&
         checked_.eq_rows == A_eq.rows() && checked_.eq_cols == A_eq.cols() &&
         checked_.eq_stride == A_eq.outerStride() && checked_.in_rows == A_in.rows() &&
         checked_.in_cols == A_in.cols() && checked_.in_stride == A_in.outerStride();
}

bool DualActiveSetQp::checkInput(const VectorRef& g, const MatrixRef& A_eq, const VectorRef& b_eq,
                                 const MatrixRef& A_in, const VectorRef& b_in,
                                 bool matrices_checked) {
  if (!matrices_checked) {  // new matrices: whatever passed before no longer describes them
    matrices_checked_ = false;
    row_norms_valid_ = false;
  }
  result_.x.setZero();
  result_.objective = 0.0;
  result_.active_set.clear();
  result_.iterations = 0;
  result_.m_eq = 0;
  result_.m_in = 0;
  result_.message.clear();
  const int m_eq = static_cast<int>(A_eq.rows());
  const int m_in = static_cast<int>(A_in.rows());
  if (g.size() != n_) {
    fail(QpStatus::kInvalidInput, "g: expected size %d, got %d", n_, static_cast<int>(g.size()));
    return false;
  }
  if (m_eq > m_eq_max_ || m_in > m_in_max_) {
    fail(QpStatus::kInvalidInput,
         "too many rows: %d equalities (max %d), %d inequalities (max %d) for this solver", m_eq,
         m_eq_max_, m_in, m_in_max_);
    return false;
  }
  if ((m_eq > 0 && A_eq.cols() != n_) || b_eq.size() != m_eq) {
    fail(QpStatus::kInvalidInput, "A_eq is %d x %d and b_eq has %d entries; expected m x %d and m",
         m_eq, static_cast<int>(A_eq.cols()), static_cast<int>(b_eq.size()), n_);
    return false;
  }
  if ((m_in > 0 && A_in.cols() != n_) || b_in.size() != m_in) {
    fail(QpStatus::kInvalidInput, "A_in is %d x %d and b_in has %d entries; expected m x %d and m",
         m_in, static_cast<int>(A_in.cols()), static_cast<int>(b_in.size()), n_);
    return false;
  }
  const char* bad = nullptr;
  if (!g.allFinite())
    bad = "g";
  else if (!matrices_checked && m_eq > 0 && !A_eq.allFinite())
    bad = "A_eq";
  else if (!b_eq.allFinite())
    bad = "b_eq";
  else if (!matrices_checked && m_in > 0 && !A_in.allFinite())
    bad = "A_in";
  else if (!b_in.allFinite())
    bad = "b_in";
  if (bad != nullptr) {
    fail(QpStatus::kInvalidInput, "%s contains a non-finite value (NaN or inf)", bad);
    return false;
  }
  if (!matrices_checked) {
    checked_ = CheckedMatrices{A_eq.data(),        A_in.data(), A_eq.rows(), A_eq.cols(),
                               A_eq.outerStride(), A_in.rows(), A_in.cols(), A_in.outerStride()};
    matrices_checked_ = true;
  }
  result_.m_eq = m_eq;
  result_.m_in = m_in;
  result_.multipliers.head(m_eq + m_in).setZero();
  return true;
}

const QpResult& DualActiveSetQp::solve(const MatrixRef& G, const VectorRef& g,
                                       const MatrixRef& A_eq, const VectorRef& b_eq,
                                       const MatrixRef& A_in, const VectorRef& b_in,
                                       const std::vector<int>* warm_start) {
  if (!checkInput(g, A_eq, b_eq, A_in, b_in, false)) return result_;
  if (!own_factor_.compute(G, config_.regularization)) {
    fail(QpStatus::kInvalidInput, "%s", own_factor_.message().c_str());
    return result_;
  }
  run(own_factor_, g, A_eq, b_eq, A_in, b_in, warm_start);
  return result_;
}

const QpResult& DualActiveSetQp::solve(const HessianFactor& factor, const VectorRef& g,
                                       const MatrixRef& A_eq, const VectorRef& b_eq,
                                       const MatrixRef& A_in, const VectorRef& b_in,
                                       const std::vector<int>* warm_start, Matrices matrices) {
  const bool unchanged = matrices == Matrices::kUnchanged && sameCheckedMatrices(A_eq, A_in);
  if (!checkInput(g, A_eq, b_eq, A_in, b_in, unchanged)) return result_;
  if (!factor.valid() || factor.size() != n_) {
    fail(QpStatus::kInvalidInput, "Hessian factor is %s (size %d, solver has %d variables)",
         factor.valid() ? "of the wrong size" : "not computed or failed", factor.size(), n_);
    return result_;
  }
  run(factor, g, A_eq, b_eq, A_in, b_in, warm_start);
  return result_;
}

bool DualActiveSetQp::householderAppend(const RowRef& a) {
  const int k = q_;
  d_.noalias() = factor_->J0t().triangularView<Eigen::Lower>() * a.transpose();
  const double dnorm = d_.norm();
  for (int i = 0; i < k; ++i)
    d_.tail(n_ - i).applyHouseholderOnTheLeft(householder_.col(i).tail(n_ - i - 1), tau_[i],
                                              work_.data());
  if (k >= n_) return false;
  const double rest = d_.tail(n_ - k).norm();
  if (!(rest > config_.dependence_tol * dnorm) || !(rest > 0.0)) return false;
  double beta = 0.0;
  d_.tail(n_ - k).makeHouseholderInPlace(tau_[k], beta);
  householder_.col(k).tail(n_ - k) = d_.tail(n_ - k);
  R_.col(k).head(k) = d_.head(k);
  R_(k, k) = beta;
  return true;
}

bool DualActiveSetQp::appendWithJ(const RowRef& a, int index) {
  if (q_ >= n_) return false;
  d_.noalias() = J_.transpose() * a.transpose();
  const double rest_sq = d_.tail(n_ - q_).squaredNorm();
  const double tol = config_.dependence_tol;
  if (!(rest_sq > tol * tol * d_.squaredNorm()) || !(rest_sq > 0.0)) return false;
  addConstraint(index);
  return true;
}

void DualActiveSetQp::formJ(const Eigen::MatrixXd& J0) {
  J_ = J0;
  for (int k = 0; k < q_; ++k)
    J_.rightCols(n_ - k).applyHouseholderOnTheRight(householder_.col(k).tail(n_ - k - 1), tau_[k],
                                                    work_.data());
}

void DualActiveSetQp::solveOnActiveSet(const MatrixRef& A_eq, const VectorRef& b_eq,
                                       const MatrixRef& A_in, const VectorRef& b_in) {
  x_ = x0_;
  if (q_ == 0) return;
  for (int k = 0; k < q_; ++k) {
    const int idx = active_[k];
    w_(k) = idx < m_eq_ ? b_eq(idx) - A_eq.row(idx).dot(x0_)
                        : b_in(idx - m_eq_) - A_in.row(idx - m_eq_).dot(x0_);
  }
  auto R = R_.topLeftCorner(q_, q_).triangularView<Eigen::Upper>();
  R.transpose().solveInPlace(w_.head(q_));  // y = R^{-T} w
  u_.head(q_) = w_.head(q_);
  R.solveInPlace(u_.head(q_));  // u = R^{-1} y
  x_.noalias() += J_.leftCols(q_) * w_.head(q_);
}

void DualActiveSetQp::addConstraint(int index) {
  // d_ = J^T n_p. One Householder reflector maps d(q..n-1) to beta e_q; applying it to the
  // columns q..n-1 of J keeps J^T N = R (the paper uses Givens rotations; same result).
  const int nf = n_ - q_;
  double tau = 0.0, beta = 0.0;
  d_.tail(nf).makeHouseholderInPlace(tau, beta);
  J_.rightCols(nf).applyHouseholderOnTheRight(d_.tail(nf - 1), tau, work_.data());
  R_.col(q_).head(q_) = d_.head(q_);
  R_(q_, q_) = beta;
  active_[q_] = index;
  ++q_;
}

void DualActiveSetQp::dropConstraint(int k) {
  const int idx = active_[k];
  if (idx >= m_eq_) is_active_[idx - m_eq_] = 0;
  for (int j = k; j < q_ - 1; ++j) {
    R_.col(j).head(j + 2) = R_.col(j + 1).head(j + 2);
    active_[j] = active_[j + 1];
    u_(j) = u_(j + 1);
  }
  --q_;
  // R is now upper Hessenberg from column k on: restore it with Givens rotations on rows j, j+1
  // and the same rotations on the columns j, j+1 of J.
  for (int j = k; j < q_; ++j) {
    const double a = R_(j, j), b = R_(j + 1, j);
    if (b == 0.0) continue;
    const double h = std::hypot(a, b);
    const double c = a / h, s = b / h;
    R_(j, j) = h;
    R_(j + 1, j) = 0.0;
    for (int col = j + 1; col < q_; ++col) {
      const double t = R_(j, col);
      R_(j, col) = c * t + s * R_(j + 1, col);
      R_(j + 1, col) = c * R_(j + 1, col) - s * t;
    }
    rotateColumns(J_, j, j + 1, c, s);
  }
}

void DualActiveSetQp::run(const HessianFactor& factor, const VectorRef& g, const MatrixRef& A_eq,
                          const VectorRef& b_eq, const MatrixRef& A_in, const VectorRef& b_in,
                          const std::vector<int>* warm_start) {
  const Eigen::MatrixXd& J0 = factor.J0();
  factor_ = &factor;
  const int m_eq = static_cast<int>(A_eq.rows());
  const int m_in = static_cast<int>(A_in.rows());
  m_eq_ = m_eq;
  q_ = 0;
  std::fill(is_active_.begin(), is_active_.begin() + m_in, 0);
  std::fill(eq_redundant_.begin(), eq_redundant_.begin() + m_eq, 0);

  // Unconstrained minimum x0 = -G^{-1} g = -J0 J0^T g.
  w_.noalias() = factor.J0t().triangularView<Eigen::Lower>() * g;
  x0_.noalias() = J0.triangularView<Eigen::Upper>() * w_;
  x0_ = -x0_;

  activateEqualities(factor, A_eq);
  if (warm_start != nullptr) {
    for (int idx : *warm_start) {
      const int j = idx - m_eq;
      if (j < 0 || j >= m_in || is_active_[j]) continue;
      if (appendWithJ(A_in.row(j), idx)) is_active_[j] = 1;
    }
  }
  solveOnActiveSet(A_eq, b_eq, A_in, b_in);
  if (!redundantEqualitiesHold(A_eq, b_eq)) {
    finish(factor, g, m_eq, m_in);
    return;
  }
  dropNegativeMultipliers(A_eq, b_eq, A_in, b_in);

  if (m_in > 0 && !row_norms_valid_) row_norm_.head(m_in) = A_in.rowwise().norm();
  row_norms_valid_ = true;  // A_in is the checked matrix (checkInput) until new ones come
  for (;;) {
    // Step 1: the most violated inequality (violation per unit row norm).
    const int p = mostViolatedRow(A_in, b_in);
    if (p < 0) {
      result_.status = QpStatus::kOptimal;
      break;
    }
    // Step 2: move towards satisfying row p, dropping blocking rows, until it can be added.
    if (!addViolatedRow(A_in, p)) {
      finish(factor, g, m_eq, m_in);
      return;
    }
  }
  finish(factor, g, m_eq, m_in);
}

void DualActiveSetQp::activateEqualities(const HessianFactor& factor, const MatrixRef& A_eq) {
  // Initial active set: equality rows first (dependent ones are redundant), with one Householder
  // QR of L^{-1} A_eq^T, or from the cache when the factor and A_eq are those of the last solve.
  const int m_eq = static_cast<int>(A_eq.rows());
  const bool reuse = cache_valid_ && factor.id() == cache_factor_id_ && m_eq == cache_m_eq_ &&
                     (m_eq == 0 || cache_A_eq_.topRows(m_eq) == A_eq);
  if (reuse) {
    q_ = cache_q_;
    J_ = cache_J_;
    R_.topLeftCorner(q_, q_) = cache_R_.topLeftCorner(q_, q_);
    std::copy(cache_active_.begin(), cache_active_.begin() + q_, active_.begin());
    std::copy(cache_eq_redundant_.begin(), cache_eq_redundant_.begin() + m_eq,
              eq_redundant_.begin());
    return;
  }
  for (int i = 0; i < m_eq; ++i) {
    if (householderAppend(A_eq.row(i)))
      active_[q_++] = i;
    else
      eq_redundant_[i] = 1;
  }
  formJ(factor.J0());
  // Only a factor that outlives this call is worth caching for (not the solve(G) one).
  cache_valid_ = &factor != &own_factor_;
  if (cache_valid_) {
    cache_factor_id_ = factor.id();
    cache_m_eq_ = m_eq;
    cache_q_ = q_;
    if (m_eq > 0) cache_A_eq_.topRows(m_eq) = A_eq;
    cache_J_ = J_;
    cache_R_.topLeftCorner(q_, q_) = R_.topLeftCorner(q_, q_);
    std::copy(active_.begin(), active_.begin() + q_, cache_active_.begin());
    std::copy(eq_redundant_.begin(), eq_redundant_.begin() + m_eq, cache_eq_redundant_.begin());
  }
}

bool DualActiveSetQp::redundantEqualitiesHold(const MatrixRef& A_eq, const VectorRef& b_eq) {
  // Redundant equality rows must hold on the affine set of the independent ones.
  const int m_eq = static_cast<int>(A_eq.rows());
  const double xnorm0 = x_.norm();
  const double consistency_tol = std::max(config_.feasibility_tol, config_.dependence_tol);
  for (int i = 0; i < m_eq; ++i) {
    if (!eq_redundant_[i]) continue;
    const double s = A_eq.row(i).dot(x_) - b_eq(i);
    const double tol = consistency_tol * (1.0 + std::abs(b_eq(i)) + A_eq.row(i).norm() * xnorm0);
    if (!(std::abs(s) <= tol)) {
      fail(QpStatus::kInfeasible,
           "equality row %d is linearly dependent on the others but inconsistent (residual %.3g)",
           i, s);
      return false;
    }
  }
  return true;
}

void DualActiveSetQp::dropNegativeMultipliers(const MatrixRef& A_eq, const VectorRef& b_eq,
                                              const MatrixRef& A_in, const VectorRef& b_in) {
  // A warm start is only usable while dual feasible: drop rows with negative multipliers.
  const int m_eq = m_eq_;
  for (;;) {
    int worst = -1;
    double most_negative = 0.0;
    for (int k = 0; k < q_; ++k)
      if (active_[k] >= m_eq && u_(k) < most_negative) {
        most_negative = u_(k);
        worst = k;
      }
    if (worst < 0) break;
    dropConstraint(worst);
    ++result_.iterations;
    solveOnActiveSet(A_eq, b_eq, A_in, b_in);
  }
}

int DualActiveSetQp::mostViolatedRow(const MatrixRef& A_in, const VectorRef& b_in) {
  const int m_in = static_cast<int>(A_in.rows());
  int p = -1;
  if (m_in > 0) {
    s_.head(m_in).noalias() = A_in * x_;
    s_.head(m_in) -= b_in;
    const double xnorm = x_.norm();
    double best = 0.0;
    for (int j = 0; j < m_in; ++j) {
      if (is_active_[j]) continue;
      const double tol = config_.feasibility_tol * (1.0 + std::abs(b_in(j)) + row_norm_(j) * xnorm);
      if (s_(j) < -tol) {
        const double v = s_(j) / std::max(row_norm_(j), std::numeric_limits<double>::min());
        if (v < best) {
          best = v;
          p = j;
        }
      }
    }
  }
  return p;
}

bool DualActiveSetQp::addViolatedRow(const MatrixRef& A_in, int p) {
  const int m_eq = m_eq_;
  const double tol_dep_sq = config_.dependence_tol * config_.dependence_tol;
  double sp = s_(p);
  double u_plus = 0.0;
  const auto a_p = A_in.row(p);
  for (;;) {
    if (result_.iterations >= config_.max_iterations) {
      fail(QpStatus::kIterationLimit, "iteration limit %d reached (%d rows active)",
           config_.max_iterations, q_);
      return false;
    }
    ++result_.iterations;
    d_.noalias() = J_.transpose() * a_p.transpose();
    const int nf = n_ - q_;
    const double d2sq = d_.tail(nf).squaredNorm();
    const bool has_z = nf > 0 && d2sq > 0.0 && d2sq > tol_dep_sq * d_.squaredNorm();
    if (has_z) z_.noalias() = J_.rightCols(nf) * d_.tail(nf);
    if (q_ > 0) {
      r_.head(q_) = d_.head(q_);
      R_.topLeftCorner(q_, q_).triangularView<Eigen::Upper>().solveInPlace(r_.head(q_));
    }
    // Partial (dual) step length t1: the first active inequality whose multiplier hits zero.
    double t1 = kInf;
    int k_drop = -1;
    for (int k = 0; k < q_; ++k) {
      if (active_[k] >= m_eq && r_(k) > 0.0) {
        const double ratio = u_(k) / r_(k);
        if (ratio < t1) {
          t1 = ratio;
          k_drop = k;
        }
      }
    }
    // Full (primal) step length t2: row p becomes satisfied.
    const double t2 = has_z ? -sp / d2sq : kInf;
    if (t1 == kInf && t2 == kInf) {
      fail(QpStatus::kInfeasible,
           "infeasible: inequality row %d (violation %.3g) cannot be satisfied together with the "
           "%d active rows",
           p, sp, q_);
      return false;
    }
    const double t = std::min(t1, t2);
    if (q_ > 0) u_.head(q_) -= t * r_.head(q_);
    u_plus += t;
    if (t2 == kInf) {  // dual step only
      dropConstraint(k_drop);
      continue;
    }
    x_.noalias() += t * z_;
    sp += t * d2sq;
    if (t2 <= t1) {
      u_(q_) = u_plus;
      addConstraint(m_eq + p);
      is_active_[p] = 1;
      return true;
    }
    dropConstraint(k_drop);
  }
}

void DualActiveSetQp::finish(const HessianFactor& factor, const VectorRef& g, int m_eq, int m_in) {
  if (!x_.allFinite() || !u_.head(q_).allFinite()) {
    fail(QpStatus::kInvalidInput, "numerical breakdown (problem too ill-conditioned)");
    result_.x.setZero();
    result_.multipliers.head(m_eq + m_in).setZero();
    result_.objective = 0.0;
    return;
  }
  result_.x = x_;
  w_.noalias() = factor.Lt().triangularView<Eigen::Upper>() * x_;
  result_.objective = 0.5 * w_.squaredNorm() + g.dot(x_);
  result_.multipliers.head(m_eq + m_in).setZero();
  result_.active_set.clear();
  for (int k = 0; k < q_; ++k) {
    result_.multipliers(active_[k]) = u_(k);
    result_.active_set.push_back(active_[k]);
  }
  std::sort(result_.active_set.begin(), result_.active_set.end());
}

}  // namespace qp
}  // namespace reach_trajopt
