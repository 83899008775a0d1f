#include "reach_trajopt/ocp/cubic_bspline.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

CubicBSplineBasis::CubicBSplineBasis(double duration, int segments)
    : duration_(duration), segments_(segments) {
  if (!std::isfinite(duration) || duration <= 0.0) {
    std::ostringstream os;
    os << "CubicBSplineBasis: duration must be positive and finite, got " << duration;
    throw RequestError(os.str());
  }
  if (segments < 1) {
    throw RequestError("CubicBSplineBasis: need at least one segment, got " +
                       std::to_string(segments));
  }
}

double CubicBSplineBasis::knot(int i) const {
  if (i <= kDegree) return 0.0;
  if (i >= segments_ + kDegree) return duration_;
  return (i - kDegree) * knotSpacing();
}

CubicBSplineBasis::Row CubicBSplineBasis::evaluate(double t) const {
  constexpr int p = kDegree;
  t = std::min(std::max(t, 0.0), duration_);
  const int seg = std::min(static_cast<int>(std::floor(t / knotSpacing())), segments_ - 1);
  const int span = seg + p;

  // Derivatives of the B-spline basis functions: Piegl & Tiller, The NURBS Book, A2.3.
  double ndu[p + 1][p + 1], left[p + 1], right[p + 1], a[2][p + 1], ders[3][p + 1];
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - knot(span + 1 - j);
    right[j] = knot(span + j) - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  for (int j = 0; j <= p; ++j) ders[0][j] = ndu[j][p];
  constexpr int n = 2;
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= n; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      ders[k][r] = d;
      std::swap(s1, s2);
    }
  }
  double factor = p;
  for (int k = 1; k <= n; ++k) {
    for (int j = 0; j <= p; ++j) ders[k][j] *= factor;
    factor *= (p - k);
  }

  Row row;
  row.first = span - p;
  for (int j = 0; j <= p; ++j) {
    row.value[j] = ders[0][j];
    row.d1[j] = ders[1][j];
    row.d2[j] = ders[2][j];
  }
  return row;
}

void CubicBSplineBasis::boundaryControlPoints(double h, const Eigen::VectorXd& q0,
                                              const Eigen::VectorXd& qd0, const Eigen::VectorXd& qT,
                                              const Eigen::VectorXd& qdT, Eigen::VectorXd& c0,
                                              Eigen::VectorXd& c1, Eigen::VectorXd& c_second_last,
                                              Eigen::VectorXd& c_last) {
  // qd(0) = 3 (c1 - c0) / h and qd(T) = 3 (c_last - c_second_last) / h for clamped knots.
  c0 = q0;
  c1 = q0 + (h / kDegree) * qd0;
  c_last = qT;
  c_second_last = qT - (h / kDegree) * qdT;
}

}  // namespace reach_trajopt
