#include "reach_trajopt/qp/hessian_factor.h"

#include <Eigen/Cholesky>
#include <atomic>
#include <cmath>
#include <cstdio>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {
namespace qp {

namespace {
std::atomic<unsigned long long> g_next_factor_id{1};

int checkedSize(int n) {
  if (n <= 0)
    throw QpInputError("HessianFactor: number of variables must be > 0, got " + std::to_string(n));
  return n;
}
}  // namespace

HessianFactor::HessianFactor(int n)
    : n_(checkedSize(n)),
      L_(Eigen::MatrixXd::Zero(n, n)),
      J0_(Eigen::MatrixXd::Zero(n, n)),
      J0t_(Eigen::MatrixXd::Zero(n, n)),
      Lt_(Eigen::MatrixXd::Zero(n, n)) {
  message_.reserve(256);
}

bool HessianFactor::compute(const Eigen::Ref<const Eigen::MatrixXd>& G, double regularization) {
  valid_ = false;
  message_.clear();
  char buf[256];
  if (G.rows() != n_ || G.cols() != n_) {
    std::snprintf(buf, sizeof(buf), "G must be %d x %d, got %d x %d", n_, n_,
                  static_cast<int>(G.rows()), static_cast<int>(G.cols()));
    message_.assign(buf);
    return false;
  }
  if (!std::isfinite(regularization) || regularization < 0.0) {
    message_.assign("regularization must be finite and >= 0");
    return false;
  }
  // Only the lower triangle is read (and checked), as documented.
  for (int j = 0; j < n_; ++j)
    for (int i = j; i < n_; ++i)
      if (!std::isfinite(G(i, j))) {
        std::snprintf(buf, sizeof(buf), "G: non-finite value at (%d, %d)", i, j);
        message_.assign(buf);
        return false;
      }
  // A diagonal G (the weights of the contact QP (15) and of (19)) needs no elimination.
  bool diagonal = true;
  for (int j = 0; j < n_ && diagonal; ++j)
    for (int i = j + 1; i < n_; ++i)
      if (G(i, j) != 0.0) {
        diagonal = false;
        break;
      }
  bool positive_definite = true;
  if (diagonal) {
    const auto d = G.diagonal().array() + regularization;
    const double max_diag = d.abs().maxCoeff();
    positive_definite = max_diag > 0.0 && d.minCoeff() > kMinPivotRatio * max_diag;
    if (positive_definite) {
      L_.setZero();
      L_.diagonal() = d.sqrt().matrix();
      J0_.setZero();
      J0_.diagonal() = d.sqrt().inverse().matrix();
    }
  } else {
    L_.triangularView<Eigen::Lower>() = G;
    L_.triangularView<Eigen::StrictlyUpper>().setZero();
    L_.diagonal().array() += regularization;
    const double max_diag = L_.diagonal().cwiseAbs().maxCoeff();
    Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>, Eigen::Lower> llt(L_);  // in place, no allocation
    const double min_pivot_sq = L_.diagonal().array().square().minCoeff();
    positive_definite = llt.info() == Eigen::Success && max_diag > 0.0 &&
                        min_pivot_sq > kMinPivotRatio * max_diag && L_.diagonal().allFinite();
    if (positive_definite) {
      // L^T J0 = I, so J0 = L^{-T} is upper triangular.
      J0_.setIdentity();
      L_.triangularView<Eigen::Lower>().transpose().solveInPlace(J0_);
    }
  }
  if (!positive_definite) {
    std::snprintf(buf, sizeof(buf),
                  "G%s is not positive definite (Cholesky pivot ratio below %.0e); it may be only "
                  "semi-definite: set QpSolverConfig::regularization > 0 to solve G + rho I",
                  regularization > 0.0 ? " + rho I" : "", kMinPivotRatio);
    message_.assign(buf);
    return false;
  }
  J0t_ = J0_.transpose();
  Lt_ = L_.transpose();
  regularization_ = regularization;
  id_ = g_next_factor_id.fetch_add(1, std::memory_order_relaxed);
  valid_ = true;
  return true;
}

}  // namespace qp
}  // namespace reach_trajopt
