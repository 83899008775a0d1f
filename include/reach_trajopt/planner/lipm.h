#pragma once
/// \file lipm.h
/// The linear inverted pendulum model of eq. (9)-(10): per horizontal axis
///   pdd = omega^2 (p - a),  omega = sqrt(g / h),
/// with the closed form (C = cosh(omega t), S = sinh(omega t))
///   p(t)  = a + (p0 - a) C + pd0 S / omega,
///   pd(t) = omega (p0 - a) S + pd0 C.
/// The state is x_p = [p; pd] = [px py pdx pdy] (the paper's order) and eq. (10) reads
/// x_p(t) = A(t) x_p(0) + B(t) a with A, B below.

#include <Eigen/Core>

namespace reach_trajopt {

/// CoM position and velocity on the horizontal plane.
struct LipmState {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();   ///< CoM position [m]
  Eigen::Vector2d pd = Eigen::Vector2d::Zero();  ///< CoM velocity [m/s]
};

/// Closed-form LIPM of eq. (9)-(10). Immutable.
class Lipm {
 public:
  /// \param height   CoM height h [m] (> 0)
  /// \param gravity  g [m/s^2] (> 0)
  /// Throws ReachError when a parameter is not positive and finite.
  explicit Lipm(double height, double gravity = 9.81);

  double height() const { return height_; }
  double gravity() const { return gravity_; }
  double omega() const { return omega_; }  ///< sqrt(g/h) [1/s]

  /// State after time t [s] (t >= 0 or < 0) with the contact point `a` [m] held fixed.
  /// Throws ReachError on non-finite input.
  LipmState propagate(const LipmState& x0, const Eigen::Vector2d& a, double t) const;
  /// The right-hand side of eq. (9): CoM acceleration [m/s^2].
  Eigen::Vector2d acceleration(const Eigen::Vector2d& p, const Eigen::Vector2d& a) const;

  /// A(t) of eq. (10), 4 x 4, for x_p = [px py pdx pdy].
  Eigen::Matrix4d A(double t) const;
  /// B(t) of eq. (10), 4 x 2.
  Eigen::Matrix<double, 4, 2> B(double t) const;

 private:
  double height_, gravity_, omega_;
};

}  // namespace reach_trajopt
