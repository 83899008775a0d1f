// The cubic B-spline basis of the transition OCP and the SPQR least-squares fit of a seed path:
// partition of unity, derivatives against central differences, clamped boundary values, exact
// reproduction of a spline from its samples, and held control points.
#include <gtest/gtest.h>

#include <cmath>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/ocp/cubic_bspline.h"
#include "reach_trajopt/ocp/spline_fit.h"

using namespace reach_trajopt;

namespace {

double curve(const CubicBSplineBasis& B, const Eigen::VectorXd& c, double t, int d = 0) {
  const auto r = B.evaluate(t);
  const Eigen::Vector4d& w = d == 0 ? r.value : (d == 1 ? r.d1 : r.d2);
  return w.dot(c.segment<4>(r.first));
}

}  // namespace

TEST(CubicBSpline, PartitionOfUnityAndDerivatives) {
  const CubicBSplineBasis B(0.3, 5);
  ASSERT_EQ(B.controlPoints(), 8);
  const Eigen::VectorXd c = Eigen::VectorXd::LinSpaced(8, -1.0, 2.0).array().sin();
  for (double t = 0.0; t <= 0.3; t += 0.0137) {
    const auto r = B.evaluate(t);
    EXPECT_NEAR(r.value.sum(), 1.0, 1e-14);
    EXPECT_NEAR(r.d1.sum(), 0.0, 1e-10);
    EXPECT_NEAR(r.d2.sum(), 0.0, 1e-8);
    EXPECT_TRUE((r.value.array() >= -1e-15).all());
    const double h = 1e-6;
    if (t > h && t < 0.3 - h) {
      EXPECT_NEAR(curve(B, c, t, 1), (curve(B, c, t + h) - curve(B, c, t - h)) / (2 * h), 1e-6);
      EXPECT_NEAR(curve(B, c, t, 2), (curve(B, c, t + h, 1) - curve(B, c, t - h, 1)) / (2 * h),
                  1e-4);
    }
  }
  EXPECT_THROW(CubicBSplineBasis(0.0, 3), ReachError);
  EXPECT_THROW(CubicBSplineBasis(0.3, 0), ReachError);
}

TEST(CubicBSpline, BoundaryControlPointsGiveBoundaryStates) {
  const CubicBSplineBasis B(0.25, 4);
  Eigen::VectorXd q0(1), v0(1), qT(1), vT(1), c0, c1, c2, c3;
  q0 << 0.3;
  v0 << -1.2;
  qT << -0.4;
  vT << 0.7;
  CubicBSplineBasis::boundaryControlPoints(B.knotSpacing(), q0, v0, qT, vT, c0, c1, c2, c3);
  Eigen::VectorXd c(7);
  c << c0[0], c1[0], 0.5, -0.2, 0.1, c2[0], c3[0];
  EXPECT_NEAR(curve(B, c, 0.0), 0.3, 1e-14);
  EXPECT_NEAR(curve(B, c, 0.0, 1), -1.2, 1e-12);
  EXPECT_NEAR(curve(B, c, 0.25), -0.4, 1e-14);
  EXPECT_NEAR(curve(B, c, 0.25, 1), 0.7, 1e-12);
}

TEST(SplineFit, ReproducesASplineAndKeepsHeldPoints) {
  const CubicBSplineBasis B(0.3, 4);
  const int K = B.controlPoints();
  Eigen::MatrixXd c(K, 2);
  for (int k = 0; k < K; ++k) c.row(k) << std::sin(k), 0.1 * k * k;
  const int n = 301;
  Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(n, 0.0, 0.3);
  Eigen::MatrixXd y(n, 2);
  for (int i = 0; i < n; ++i) {
    y(i, 0) = curve(B, c.col(0), t[i]);
    y(i, 1) = curve(B, c.col(1), t[i]);
  }
  std::vector<bool> fixed(K, false);
  fixed[0] = fixed[1] = true;
  const Eigen::MatrixXd fit = fitSplineControlPoints(B, t, y, fixed, c, 0.0);
  EXPECT_LT((fit - c).cwiseAbs().maxCoeff(), 1e-10);
  // Held points stay at their given values even when they disagree with the data.
  Eigen::MatrixXd held = c;
  held(0, 0) += 0.5;
  const Eigen::MatrixXd fit2 = fitSplineControlPoints(B, t, y, fixed, held, 1e-6);
  EXPECT_EQ(fit2(0, 0), held(0, 0));
  // Too few samples without regularization: rank-deficient, reported.
  EXPECT_THROW(fitSplineControlPoints(B, t.head(2), y.topRows(2), fixed, c, 0.0), ReachError);
  EXPECT_NO_THROW(fitSplineControlPoints(B, t.head(2), y.topRows(2), fixed, c, 1e-3));
  Eigen::VectorXd bad = t;
  bad[3] = 0.5;
  EXPECT_THROW(fitSplineControlPoints(B, bad, y, fixed, c, 0.0), ReachError);
}
