#pragma once
/// \file cubic_bspline.h
/// The clamped, uniform cubic B-spline basis on which the transition OCP (eq. 22-23) writes the
/// actuated joint trajectories q_a(t) = sum_k N_k(t) c_k, t in [0, T].
///
/// Knots: [0 0 0 0, h, 2h, ..., (N-1)h, T T T T], h = T / N for N segments, so there are
/// K = N + 3 control points. Clamping gives the boundary values directly:
///   q(0) = c_0,   qd(0) = 3 (c_1 - c_0) / h,   q(T) = c_{K-1},   qd(T) = 3 (c_{K-1} - c_{K-2}) /
///   h,
/// which is how the OCP eliminates the boundary states x(t_0) = x_0 and x(t_f) = x_f.
/// q is C2: qd is continuous and qdd is continuous and piecewise linear, so torques and contact
/// wrenches obtained by inverse dynamics are continuous too. Each control point acts on at most
/// four segments (local support), which makes the fitting matrix sparse.

#include <Eigen/Core>

namespace reach_trajopt {

/// Clamped uniform cubic B-spline basis on [0, T] (see file comment). Immutable.
class CubicBSplineBasis {
 public:
  static constexpr int kDegree = 3;

  /// \param duration  T [s], > 0 and finite
  /// \param segments  N >= 1
  /// Throws ReachError on a bad duration or segment count.
  CubicBSplineBasis(double duration, int segments);

  double duration() const { return duration_; }
  int segments() const { return segments_; }
  int controlPoints() const { return segments_ + kDegree; }     ///< K = N + 3
  double knotSpacing() const { return duration_ / segments_; }  ///< h [s]

  /// The four basis functions that can be non-zero at t (clamped to [0, T]) and their first and
  /// second time derivatives: q(t) = sum_{i<4} value[i] c_{first + i}, and so on.
  struct Row {
    int first = 0;                                    ///< index of the first control point
    Eigen::Vector4d value = Eigen::Vector4d::Zero();  ///< N_k(t)
    Eigen::Vector4d d1 = Eigen::Vector4d::Zero();     ///< dN_k/dt [1/s]
    Eigen::Vector4d d2 = Eigen::Vector4d::Zero();     ///< d2N_k/dt2 [1/s^2]
  };
  /// Basis row at time t [s]; t is clamped to [0, T]. No allocation.
  Row evaluate(double t) const;

  /// Control points of a curve with the given boundary values (each column one coordinate):
  /// c_0, c_1 from (q0, qd0) and c_{K-2}, c_{K-1} from (qT, qdT). Needs K >= 4.
  static void boundaryControlPoints(double h, const Eigen::VectorXd& q0, const Eigen::VectorXd& qd0,
                                    const Eigen::VectorXd& qT, const Eigen::VectorXd& qdT,
                                    Eigen::VectorXd& c0, Eigen::VectorXd& c1,
                                    Eigen::VectorXd& c_second_last, Eigen::VectorXd& c_last);

 private:
  double knot(int i) const;  ///< the i-th knot of the clamped knot vector [s]

  double duration_;
  int segments_;
};

}  // namespace reach_trajopt
