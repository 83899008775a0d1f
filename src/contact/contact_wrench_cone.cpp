#include "reach_trajopt/contact/contact_wrench_cone.h"

#include <cmath>
#include <sstream>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

ContactWrenchCone::ContactWrenchCone(const ContactConfig& c)
    : ContactWrenchCone(c.mu, c.half_length, c.half_width) {}

ContactWrenchCone::ContactWrenchCone(double mu, double half_length, double half_width)
    : mu_(mu), half_length_(half_length), half_width_(half_width) {
  const auto check = [](const char* name, double v) {
    if (!std::isfinite(v) || v <= 0.0) {
      std::ostringstream os;
      os << "ContactWrenchCone: " << name << " must be positive and finite, got " << v;
      throw ConfigError(os.str());
    }
  };
  check("mu", mu);
  check("half_length X", half_length);
  check("half_width Y", half_width);
  // Beyond these the cone's entries (mu (X + Y)) and its rotated rows overflow to inf and NaN.
  const auto atMost = [](const char* name, double v, double max, const char* unit) {
    if (v > max) {
      std::ostringstream os;
      os << "ContactWrenchCone: " << name << " must be <= " << max << unit << ", got " << v;
      throw ConfigError(os.str());
    }
  };
  atMost("mu", mu, kMaxFriction, "");
  atMost("half_length X", half_length, kMaxSoleHalfSize, " m");
  atMost("half_width Y", half_width, kMaxSoleHalfSize, " m");
  const double X = half_length, Y = half_width;
  C_.setZero();
  // Rows 1-4: friction pyramid of the net force.
  C_.row(0) << 1, 0, mu, 0, 0, 0;
  C_.row(1) << -1, 0, mu, 0, 0, 0;
  C_.row(2) << 0, 1, mu, 0, 0, 0;
  C_.row(3) << 0, -1, mu, 0, 0, 0;
  // Rows 5-8: centre of pressure inside the sole.
  C_.row(4) << 0, 0, Y, 1, 0, 0;
  C_.row(5) << 0, 0, Y, -1, 0, 0;
  C_.row(6) << 0, 0, X, 0, 1, 0;
  C_.row(7) << 0, 0, X, 0, -1, 0;
  // Rows 9-16: yaw torque bounds tz_min <= tz <= tz_max.
  int r = 8;
  for (const double s1 : {1.0, -1.0}) {
    for (const double s2 : {1.0, -1.0}) {
      C_.row(r) << s1 * Y, s2 * X, mu * (X + Y), -s1 * mu, -s2 * mu, 1.0;
      C_.row(r + 4) << -s1 * Y, -s2 * X, mu * (X + Y), -s1 * mu, -s2 * mu, -1.0;
      ++r;
    }
  }
}

void ContactWrenchCone::worldMatrix(const Eigen::Matrix3d& R, Matrix& out) const {
  out.leftCols<3>().noalias() = C_.leftCols<3>() * R.transpose();
  out.rightCols<3>().noalias() = C_.rightCols<3>() * R.transpose();
}

ContactWrenchCone::Matrix ContactWrenchCone::worldMatrix(const Eigen::Matrix3d& R) const {
  Matrix out;
  worldMatrix(R, out);
  return out;
}

double ContactWrenchCone::margin(const Wrench& w) const { return (C_ * w).minCoeff(); }

bool ContactWrenchCone::contains(const Wrench& w, double tolerance) const {
  return margin(w) >= -tolerance;
}

}  // namespace reach_trajopt
