#include "reach_trajopt/planner/lipm.h"

#include <cmath>
#include <sstream>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

Lipm::Lipm(double height, double gravity) : height_(height), gravity_(gravity) {
  if (!std::isfinite(height) || height <= 0.0 || !std::isfinite(gravity) || gravity <= 0.0) {
    std::ostringstream os;
    os << "Lipm: CoM height and gravity must be positive and finite, got h = " << height
       << " m, g = " << gravity << " m/s^2";
    throw ConfigError(os.str());
  }
  omega_ = std::sqrt(gravity / height);
}

LipmState Lipm::propagate(const LipmState& x0, const Eigen::Vector2d& a, double t) const {
  requireFinite("Lipm::propagate CoM position", x0.p);
  requireFinite("Lipm::propagate CoM velocity", x0.pd);
  requireFinite("Lipm::propagate contact point", a);
  if (!std::isfinite(t)) throw RequestError("Lipm::propagate: non-finite time");
  const double C = std::cosh(omega_ * t), S = std::sinh(omega_ * t);
  LipmState x;
  x.p = a + (x0.p - a) * C + x0.pd * (S / omega_);
  x.pd = omega_ * S * (x0.p - a) + C * x0.pd;
  return x;
}

Eigen::Vector2d Lipm::acceleration(const Eigen::Vector2d& p, const Eigen::Vector2d& a) const {
  return omega_ * omega_ * (p - a);
}

Eigen::Matrix4d Lipm::A(double t) const {
  const double C = std::cosh(omega_ * t), S = std::sinh(omega_ * t);
  Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
  for (int i = 0; i < 2; ++i) {
    A(i, i) = C;
    A(i, i + 2) = S / omega_;
    A(i + 2, i) = omega_ * S;
    A(i + 2, i + 2) = C;
  }
  return A;
}

Eigen::Matrix<double, 4, 2> Lipm::B(double t) const {
  const double C = std::cosh(omega_ * t), S = std::sinh(omega_ * t);
  Eigen::Matrix<double, 4, 2> B = Eigen::Matrix<double, 4, 2>::Zero();
  for (int i = 0; i < 2; ++i) {
    B(i, i) = 1.0 - C;
    B(i + 2, i) = -omega_ * S;
  }
  return B;
}

}  // namespace reach_trajopt
