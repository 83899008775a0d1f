// Unit tests of the bundled QP (DualActiveSetQp, HessianFactor) on cases with analytic answers,
// against an independent KKT linear solve, and on bad input. The large random comparison with
// quadprog is test/oracle/test_qp_oracle.py.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <vector>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/qp/dual_active_set_qp.h"

// Counts heap allocations (malloc is what operator new and Eigen both end in) while enabled.
extern "C" void* __libc_malloc(size_t size);
namespace {
std::atomic<long> g_malloc_count{0};
std::atomic<bool> g_count_mallocs{false};
}  // namespace
extern "C" void* malloc(size_t size) noexcept {
  if (g_count_mallocs.load(std::memory_order_relaxed))
    g_malloc_count.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}

namespace reach_trajopt {
namespace qp {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

const double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Problem {
  MatrixXd G;
  VectorXd g;
  MatrixXd Aeq;
  VectorXd beq;
  MatrixXd Ain;
  VectorXd bin;
};

MatrixXd randomSpd(std::mt19937& rng, int n) {
  std::normal_distribution<double> normal;
  MatrixXd B(n, n);
  for (int i = 0; i < n * n; ++i) B.data()[i] = normal(rng);
  return B * B.transpose() / n + 0.5 * MatrixXd::Identity(n, n);
}

MatrixXd randomMatrix(std::mt19937& rng, int rows, int cols) {
  std::normal_distribution<double> normal;
  MatrixXd A(rows, cols);
  for (int i = 0; i < rows * cols; ++i) A.data()[i] = normal(rng);
  return A;
}

// Feasible by construction: equalities through a random point, inequalities with slack >= 0
// (a third of them zero, i.e. active there).
Problem randomProblem(std::mt19937& rng, int n, int m_eq, int m_in) {
  Problem p;
  p.G = randomSpd(rng, n);
  p.g = randomMatrix(rng, n, 1);
  const VectorXd x_f = randomMatrix(rng, n, 1);
  p.Aeq = randomMatrix(rng, m_eq, n);
  p.beq = p.Aeq * x_f;
  p.Ain = randomMatrix(rng, m_in, n);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  p.bin = p.Ain * x_f;
  for (int i = 0; i < m_in; ++i)
    if (uni(rng) > 0.33) p.bin(i) -= uni(rng);
  return p;
}

// Checks the KKT conditions of the sign convention of dual_active_set_qp.h.
void expectKkt(const Problem& p, const QpResult& r, double tol = 1e-9) {
  ASSERT_EQ(r.status, QpStatus::kOptimal) << r.message;
  const VectorXd stat = p.G * r.x + p.g - p.Aeq.transpose() * r.eq() - p.Ain.transpose() * r.in();
  EXPECT_LT(stat.lpNorm<Eigen::Infinity>(), tol) << "stationarity";
  if (p.Aeq.rows() > 0) {
    EXPECT_LT((p.Aeq * r.x - p.beq).lpNorm<Eigen::Infinity>(), tol);
  }
  if (p.Ain.rows() > 0) {
    const VectorXd s = p.Ain * r.x - p.bin;
    EXPECT_GT(s.minCoeff(), -tol) << "primal feasibility";
    EXPECT_GT(r.in().minCoeff(), -tol) << "dual sign";
    EXPECT_LT(r.in().cwiseProduct(s).lpNorm<Eigen::Infinity>(), tol) << "complementarity";
  }
  EXPECT_NEAR(r.objective, 0.5 * r.x.dot(p.G * r.x) + p.g.dot(r.x), 1e-9);
}

const QpResult& solve(DualActiveSetQp& qp, const Problem& p,
                      const std::vector<int>* warm = nullptr) {
  return qp.solve(p.G, p.g, p.Aeq, p.beq, p.Ain, p.bin, warm);
}

TEST(DualActiveSetQp, UnconstrainedMinimumIsMinusGInverseG) {
  std::mt19937 rng(1);
  Problem p = randomProblem(rng, 7, 0, 0);
  DualActiveSetQp qp(7, 0, 0);
  const QpResult& r = solve(qp, p);
  ASSERT_EQ(r.status, QpStatus::kOptimal);
  EXPECT_LT((r.x - p.G.ldlt().solve(-p.g)).norm(), 1e-12);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_TRUE(r.active_set.empty());
  // A 0 x 0 matrix and a 0 x n matrix are both "no rows".
  p.Aeq = MatrixXd(0, 0);
  p.Ain = MatrixXd(0, 7);
  EXPECT_EQ(solve(qp, p).status, QpStatus::kOptimal);
}

TEST(DualActiveSetQp, BoxConstrainedDiagonalQpIsAClamp) {
  // min sum 1/2 d_i x_i^2 + g_i x_i, lo <= x <= hi  ->  x_i = clamp(-g_i / d_i, lo_i, hi_i).
  const int n = 6;
  VectorXd d(n), g(n), lo(n), hi(n);
  d << 1, 2, 3, 0.5, 4, 1;
  g << -3, 1, 0.3, 0.2, -8, 0;
  lo << -1, -1, -1, -1, -1, 0;
  hi << 1, 1, 1, 1, 1, 1;
  Problem p{d.asDiagonal(), g, MatrixXd(0, n), VectorXd(0), MatrixXd(2 * n, n), VectorXd(2 * n)};
  p.Ain << MatrixXd::Identity(n, n), -MatrixXd::Identity(n, n);
  p.bin << lo, -hi;
  DualActiveSetQp qp(n, 0, 2 * n);
  const QpResult& r = solve(qp, p);
  expectKkt(p, r);
  for (int i = 0; i < n; ++i) {
    const double expected = std::clamp(-g(i) / d(i), lo(i), hi(i));
    EXPECT_NEAR(r.x(i), expected, 1e-14) << i;
    // The multiplier of the bound that is hit is |d_i x_i + g_i|.
    const double grad = d(i) * expected + g(i);
    EXPECT_NEAR(r.in()(i)-r.in()(n + i), grad, 1e-14) << i;
  }
  // x_5 = 0 sits on its bound with zero multiplier (weakly active): no multiplier may be < 0.
  EXPECT_GE(r.in().minCoeff(), 0.0);
}

// Euclidean projection of c onto the simplex {x >= 0, sum x = 1} by the sort algorithm.
VectorXd projectOntoSimplex(const VectorXd& c) {
  std::vector<double> v(c.data(), c.data() + c.size());
  std::sort(v.begin(), v.end(), std::greater<double>());
  double sum = 0.0, theta = 0.0;
  for (size_t k = 0; k < v.size(); ++k) {
    sum += v[k];
    const double t = (sum - 1.0) / static_cast<double>(k + 1);
    if (v[k] - t > 0.0) theta = t;
  }
  return (c.array() - theta).max(0.0);
}

TEST(DualActiveSetQp, ProjectionOntoSimplexMatchesSortAlgorithm) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 3 + trial;
    const VectorXd c = randomMatrix(rng, n, 1);
    Problem p{MatrixXd::Identity(n, n), -c,
              MatrixXd::Ones(1, n),     VectorXd::Ones(1),
              MatrixXd::Identity(n, n), VectorXd::Zero(n)};
    DualActiveSetQp qp(n, 1, n);
    const QpResult& r = solve(qp, p);
    expectKkt(p, r);
    EXPECT_LT((r.x - projectOntoSimplex(c)).lpNorm<Eigen::Infinity>(), 1e-13) << trial;
  }
}

TEST(DualActiveSetQp, EqualityOnlyMatchesKktLinearSolve) {
  std::mt19937 rng(3);
  const int n = 12, m = 5;
  Problem p = randomProblem(rng, n, m, 0);
  MatrixXd K = MatrixXd::Zero(n + m, n + m);
  K << p.G, -p.Aeq.transpose(), p.Aeq, MatrixXd::Zero(m, m);
  VectorXd rhs(n + m);
  rhs << -p.g, p.beq;
  const VectorXd sol = K.fullPivLu().solve(rhs);
  DualActiveSetQp qp(n, m, 0);
  const QpResult& r = solve(qp, p);
  expectKkt(p, r);
  EXPECT_LT((r.x - sol.head(n)).norm(), 1e-12);
  EXPECT_LT((r.eq() - sol.tail(m)).norm(), 1e-11);
  EXPECT_EQ(static_cast<int>(r.active_set.size()), m);
}

TEST(DualActiveSetQp, InfeasibleProblemsAreReportedInfeasible) {
  DualActiveSetQp qp(2, 3, 3);
  MatrixXd G = MatrixXd::Identity(2, 2);
  VectorXd g = VectorXd::Zero(2);
  // x0 >= 1 and -x0 >= 0.
  MatrixXd Ain(2, 2);
  Ain << 1, 0, -1, 0;
  VectorXd bin(2);
  bin << 1, 0;
  const QpResult& r = qp.solve(G, g, MatrixXd(0, 2), VectorXd(0), Ain, bin);
  EXPECT_EQ(r.status, QpStatus::kInfeasible);
  EXPECT_FALSE(r.message.empty());
  EXPECT_TRUE(r.x.allFinite());
  // Dependent equality rows with inconsistent right-hand sides.
  MatrixXd Aeq(3, 2);
  Aeq << 1, 1, 1, -1, 2, 0;
  VectorXd beq(3);
  beq << 1, 0, 1.5;  // row 3 = row 1 + row 2 needs 1
  EXPECT_EQ(qp.solve(G, g, Aeq, beq, MatrixXd(0, 2), VectorXd(0)).status, QpStatus::kInfeasible);
  // An equality and an inequality that exclude each other.
  MatrixXd Aeq1(1, 2), Ain1(1, 2);
  Aeq1 << 1, 2;
  Ain1 << -1, -2;
  VectorXd b1(1), c1(1);
  b1 << 1;
  c1 << -0.5;  // x0 + 2 x1 <= 0.5
  EXPECT_EQ(qp.solve(G, g, Aeq1, b1, Ain1, c1).status, QpStatus::kInfeasible);
  // A zero row 0 >= 1.
  MatrixXd Ain2 = MatrixXd::Zero(1, 2);
  VectorXd bin2 = VectorXd::Ones(1);
  EXPECT_EQ(qp.solve(G, g, MatrixXd(0, 2), VectorXd(0), Ain2, bin2).status, QpStatus::kInfeasible);
}

TEST(DualActiveSetQp, DegenerateRowsDoNotChangeTheSolution) {
  std::mt19937 rng(4);
  for (int trial = 0; trial < 30; ++trial) {
    const int n = 10, m_eq = 3, m_in = 15;
    const Problem p = randomProblem(rng, n, m_eq, m_in);
    DualActiveSetQp qp(n, 2 * m_eq + 1, 3 * m_in + 1);
    const VectorXd x_ref = solve(qp, p).x;
    expectKkt(p, qp.result());
    Problem d = p;
    // Dependent equality rows (a sum, a scaled copy), duplicated and scaled inequality rows, an
    // implied one and a zero row that holds.
    d.Aeq.conservativeResize(2 * m_eq, n);
    d.beq.conservativeResize(2 * m_eq);
    d.Aeq.row(m_eq) = p.Aeq.row(0) + p.Aeq.row(1);
    d.beq(m_eq) = p.beq(0) + p.beq(1);
    d.Aeq.bottomRows(m_eq - 1) = 3.0 * p.Aeq.bottomRows(m_eq - 1);
    d.beq.tail(m_eq - 1) = 3.0 * p.beq.tail(m_eq - 1);
    d.Ain.resize(2 * m_in + 2, n);
    d.bin.resize(2 * m_in + 2);
    d.Ain << p.Ain, 2.0 * p.Ain, p.Ain.row(0), MatrixXd::Zero(1, n);
    d.bin << p.bin, 2.0 * p.bin, p.bin(0) - 1.0, -1.0;
    const QpResult& r = solve(qp, d);
    expectKkt(d, r);
    EXPECT_LT((r.x - x_ref).lpNorm<Eigen::Infinity>(), 1e-10) << trial;
    EXPECT_LE(static_cast<int>(r.active_set.size()), n);
  }
}

TEST(DualActiveSetQp, ManyRowsThroughOneVertex) {
  // 3 variables, 12 inequality rows all tight at x* = (1, 1, 1), minimum pulled towards it.
  std::mt19937 rng(5);
  const int n = 3, m = 12;
  Problem p{MatrixXd::Identity(n, n),           VectorXd::Zero(n), MatrixXd(0, n), VectorXd(0),
            randomMatrix(rng, m, n).cwiseAbs(), VectorXd()};
  p.bin = p.Ain * VectorXd::Ones(n);  // all rows >= at (1,1,1); origin violates all of them
  DualActiveSetQp qp(n, 0, m);
  expectKkt(p, solve(qp, p));
}

TEST(DualActiveSetQp, NonFiniteAndBadSizesAreInvalidInput) {
  std::mt19937 rng(6);
  const Problem p = randomProblem(rng, 5, 2, 4);
  DualActiveSetQp qp(5, 2, 4);
  auto expect_invalid = [&](const Problem& q, const char* what) {
    const QpResult& r = solve(qp, q);
    EXPECT_EQ(r.status, QpStatus::kInvalidInput) << what;
    EXPECT_TRUE(r.x.allFinite()) << what;
    EXPECT_FALSE(r.message.empty()) << what;
  };
  for (int which = 0; which < 6; ++which) {
    Problem q = p;
    switch (which) {
      case 0:
        q.G(1, 1) = kNaN;
        break;
      case 1:
        q.g(2) = kNaN;
        break;
      case 2:
        q.Aeq(1, 3) = std::numeric_limits<double>::infinity();
        break;
      case 3:
        q.beq(0) = kNaN;
        break;
      case 4:
        q.Ain(3, 4) = -std::numeric_limits<double>::infinity();
        break;
      case 5:
        q.bin(1) = kNaN;
        break;
    }
    expect_invalid(q, "non-finite");
  }
  Problem q = p;
  q.g.resize(4);
  expect_invalid(q, "g size");
  q = p;
  q.Ain = MatrixXd::Zero(5, 5);  // more rows than m_in_max
  q.bin = VectorXd::Zero(5);
  expect_invalid(q, "too many rows");
  q = p;
  q.bin.resize(3);
  expect_invalid(q, "b_in size");
  q = p;
  q.Aeq = MatrixXd::Zero(2, 4);
  expect_invalid(q, "A_eq cols");
  q = p;
  q.G = MatrixXd::Identity(4, 4);
  expect_invalid(q, "G size");
  // The solver is still usable afterwards.
  expectKkt(p, solve(qp, p));
}

TEST(DualActiveSetQp, SemiDefiniteHessianIsRejectedOrRegularized) {
  const int n = 3;
  Problem p{MatrixXd::Zero(n, n), VectorXd::Zero(n),        MatrixXd(0, n),
            VectorXd(0),          MatrixXd::Identity(n, n), VectorXd::Ones(n)};
  p.G(0, 0) = 1.0;  // positive semi-definite, rank 1
  p.g << -2.0, 1.0, 1.0;
  DualActiveSetQp qp(n, 0, n);
  const QpResult& r = solve(qp, p);
  EXPECT_EQ(r.status, QpStatus::kInvalidInput);
  EXPECT_NE(r.message.find("regularization"), std::string::npos) << r.message;
  QpSolverConfig config;
  config.regularization = 1e-8;
  qp.setConfig(config);
  // min 1/2 x0^2 - 2 x0 + x1 + x2, x >= 1: x = (2, 1, 1) (the regularization moves it O(1e-8)).
  const QpResult& rr = solve(qp, p);
  ASSERT_EQ(rr.status, QpStatus::kOptimal) << rr.message;
  EXPECT_LT((rr.x - Eigen::Vector3d(2.0, 1.0, 1.0)).norm(), 1e-6);
  // A negative definite G is rejected even with the small regularization.
  p.G = -MatrixXd::Identity(n, n);
  EXPECT_EQ(solve(qp, p).status, QpStatus::kInvalidInput);
}

TEST(DualActiveSetQp, WarmStartGivesTheColdAnswer) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> coin(0, 1);
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 20, m_eq = 6, m_in = 40;
    Problem p = randomProblem(rng, n, m_eq, m_in);
    DualActiveSetQp cold(n, m_eq, m_in), warm(n, m_eq, m_in);
    const QpResult& rc = solve(cold, p);
    expectKkt(p, rc);
    // From the optimal active set: nothing left to do.
    std::vector<int> active = rc.active_set;
    const QpResult& rw = solve(warm, p, &active);
    expectKkt(p, rw);
    EXPECT_LT((rw.x - rc.x).lpNorm<Eigen::Infinity>(), 1e-11);
    EXPECT_LE(rw.iterations, 1) << trial;
    // From a random, mostly wrong guess with junk indices (out of range, repeated, equalities).
    std::vector<int> guess = {-3, 0, 1000, m_eq + 2, m_eq + 2};
    for (int j = 0; j < m_in; ++j)
      if (coin(rng)) guess.push_back(m_eq + j);
    expectKkt(p, solve(warm, p, &guess));
    EXPECT_LT((warm.result().x - rc.x).lpNorm<Eigen::Infinity>(), 1e-10);
    // From the previous problem's active set after a perturbation of the right-hand sides.
    p.bin += 0.05 * randomMatrix(rng, m_in, 1);
    p.beq += 0.05 * randomMatrix(rng, m_eq, 1);
    const VectorXd x_cold = solve(cold, p).x;
    expectKkt(p, solve(warm, p, &active));
    EXPECT_LT((warm.result().x - x_cold).lpNorm<Eigen::Infinity>(), 1e-10);
  }
}

TEST(DualActiveSetQp, FactorizationIsReusedAcrossProblemsSharingG) {
  std::mt19937 rng(8);
  const int n = 15, m_eq = 4, m_in = 25;
  Problem p = randomProblem(rng, n, m_eq, m_in);
  HessianFactor factor(n);
  ASSERT_TRUE(factor.compute(p.G)) << factor.message();
  EXPECT_LT((factor.L() * factor.L().transpose() - p.G).norm(), 1e-12);
  EXPECT_LT((factor.J0() * factor.J0().transpose() - p.G.inverse()).norm(), 1e-10);
  DualActiveSetQp a(n, m_eq, m_in), b(n, m_eq, m_in);
  for (int child = 0; child < 10; ++child) {
    p.g = randomMatrix(rng, n, 1);
    p.bin -= 0.1 * randomMatrix(rng, m_in, 1).cwiseAbs();  // looser: stays feasible
    const QpResult& ra = a.solve(factor, p.g, p.Aeq, p.beq, p.Ain, p.bin);
    const QpResult& rb = solve(b, p);
    expectKkt(p, ra);
    EXPECT_EQ(ra.x, rb.x) << "same factorization, same arithmetic";
    EXPECT_EQ(ra.active_set, rb.active_set);
  }
  // The equality rows' QR cached from the last solve must not survive a change of A_eq in place
  // (same size, same factor) or a recomputed factor.
  for (int change = 0; change < 3; ++change) {
    if (change == 0) p.Aeq(1, 2) += 0.5;
    if (change == 1) {  // now dependent (and consistent)
      p.Aeq.row(3) = p.Aeq.row(0) + p.Aeq.row(1);
      p.beq(3) = p.beq(0) + p.beq(1);
    }
    if (change == 2) {
      p.G += 0.3 * MatrixXd::Identity(n, n);
      ASSERT_TRUE(factor.compute(p.G));
    }
    const VectorXd x_fresh = solve(b, p).x;
    const QpResult& ra = a.solve(factor, p.g, p.Aeq, p.beq, p.Ain, p.bin);
    EXPECT_EQ(ra.status, b.result().status) << change;
    if (b.result().status == QpStatus::kOptimal) {
      expectKkt(p, ra);
      EXPECT_LT((ra.x - x_fresh).norm(), 1e-10) << change;
    }
  }
  HessianFactor wrong(n + 1);
  EXPECT_FALSE(wrong.valid());
  EXPECT_EQ(a.solve(wrong, p.g, p.Aeq, p.beq, p.Ain, p.bin).status, QpStatus::kInvalidInput);
}

TEST(DualActiveSetQp, UnchangedMatricesGiveTheSameAnswerAndNewOnesAreStillChecked) {
  // The children of one parent: the same G, A_eq, A_in; new g and right-hand sides. Stating
  // Matrices::kUnchanged skips the matrices' check and row norms, not the answer.
  std::mt19937 rng(11);
  const int n = 12, m_eq = 3, m_in = 40;
  Problem p = randomProblem(rng, n, m_eq, m_in);
  HessianFactor factor(n);
  ASSERT_TRUE(factor.compute(p.G));
  DualActiveSetQp fresh(n, m_eq, m_in), reused(n, m_eq, m_in);
  using M = DualActiveSetQp::Matrices;
  for (int child = 0; child < 8; ++child) {
    p.g = randomMatrix(rng, n, 1);
    p.bin -= 0.1 * randomMatrix(rng, m_in, 1).cwiseAbs();
    const QpResult& a = fresh.solve(factor, p.g, p.Aeq, p.beq, p.Ain, p.bin);
    const QpResult& b = reused.solve(factor, p.g, p.Aeq, p.beq, p.Ain, p.bin, nullptr,
                                     child == 0 ? M::kNew : M::kUnchanged);
    expectKkt(p, b);
    EXPECT_EQ(a.x, b.x) << child;
    EXPECT_EQ(a.active_set, b.active_set) << child;
  }
  // Other matrices (another address) stated unchanged are checked all the same.
  Problem q = p;
  q.Ain(5, 3) = kNaN;
  EXPECT_EQ(reused.solve(factor, q.g, q.Aeq, q.beq, q.Ain, q.bin, nullptr, M::kUnchanged).status,
            QpStatus::kInvalidInput);
  EXPECT_NE(reused.result().message.find("A_in"), std::string::npos) << reused.result().message;
  // After a failed check nothing counts as checked, even at the old address.
  p.Aeq(0, 0) = kNaN;
  EXPECT_EQ(reused.solve(factor, p.g, p.Aeq, p.beq, p.Ain, p.bin).status, QpStatus::kInvalidInput);
  p.Aeq(0, 0) = 1.0;
  p.Ain(2, 2) = kNaN;  // in place, stated unchanged: the last solve checked nothing
  EXPECT_EQ(reused.solve(factor, p.g, p.Aeq, p.beq, p.Ain, p.bin, nullptr, M::kUnchanged).status,
            QpStatus::kInvalidInput);
  // New row norms once the matrices are new: rows of A_in scaled unevenly in place (the same
  // address; the most violated row per unit norm changes) solved kNew give the fresh answer.
  p.Ain(2, 2) = 0.5;
  for (int i = 0; i < m_in; ++i) {
    p.Ain.row(i) *= 1.0 + 10.0 * (i % 3);
    p.bin(i) *= 1.0 + 10.0 * (i % 3);
  }
  const QpResult& a = fresh.solve(factor, p.g, p.Aeq, p.beq, p.Ain, p.bin);
  const QpResult& b = reused.solve(factor, p.g, p.Aeq, p.beq, p.Ain, p.bin, nullptr, M::kNew);
  ASSERT_EQ(a.status, b.status);
  EXPECT_EQ(a.x, b.x);
}

TEST(DualActiveSetQp, IterationLimitIsReported) {
  std::mt19937 rng(9);
  const Problem p = randomProblem(rng, 10, 0, 30);
  QpSolverConfig config;
  config.max_iterations = 1;
  DualActiveSetQp qp(10, 0, 30, config);
  const QpResult& r = solve(qp, p);
  ASSERT_EQ(r.status, QpStatus::kIterationLimit) << "the problem needs more than one step";
  EXPECT_TRUE(r.x.allFinite());
  EXPECT_EQ(r.iterations, 1);
}

TEST(DualActiveSetQp, SolveDoesNotAllocate) {
  std::mt19937 rng(10);
  const int n = 30, m_eq = 12, m_in = 60;
  const Problem big = randomProblem(rng, n, m_eq, m_in);
  const Problem small = randomProblem(rng, n, m_eq / 2, m_in / 3);  // fewer rows than the maxima
  Problem bad = big;
  bad.g(0) = kNaN;
  DualActiveSetQp qp(n, m_eq, m_in);
  HessianFactor factor(n);
  std::vector<int> warm;
  warm.reserve(n);
  solve(qp, big);
  warm = qp.result().active_set;
  g_malloc_count = 0;
  g_count_mallocs = true;
  solve(qp, big);
  solve(qp, small);
  solve(qp, bad);
  qp.solve(big.G, big.g, big.Aeq, big.beq, big.Ain, big.bin, &warm);
  factor.compute(big.G);
  qp.solve(factor, big.g, big.Aeq, big.beq, big.Ain, big.bin, &warm);
  g_count_mallocs = false;
  EXPECT_EQ(g_malloc_count.load(), 0);
  // The counter itself works.
  g_count_mallocs = true;
  VectorXd* heap = new VectorXd(100);
  g_count_mallocs = false;
  delete heap;
  EXPECT_GE(g_malloc_count.load(), 2);
  EXPECT_EQ(qp.result().status, QpStatus::kOptimal);
}

TEST(DualActiveSetQp, ConfigAndSizesAreValidated) {
  EXPECT_THROW(DualActiveSetQp(0, 1, 1), ReachError);
  EXPECT_THROW(DualActiveSetQp(3, -1, 1), ReachError);
  QpSolverConfig config;
  config.feasibility_tol = kNaN;
  EXPECT_THROW(config.validate(), ReachError);
  config = QpSolverConfig();
  config.dependence_tol = 1.0;
  EXPECT_THROW(config.validate(), ReachError);
  config = QpSolverConfig();
  config.max_iterations = -1;
  EXPECT_THROW(DualActiveSetQp(3, 1, 1, config), ReachError);
  EXPECT_NO_THROW(QpSolverConfig().validate());
  EXPECT_STREQ(toString(QpStatus::kInfeasible), "infeasible");
}

}  // namespace
}  // namespace qp
}  // namespace reach_trajopt
