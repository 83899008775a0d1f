#pragma once
/// \file contact_wrench_cone.h
/// The contact wrench cone (CWC) of eq. (7)-(8) for a rectangular sole, in the corrected form
/// of docs/method.md Sec. 2 (Caron, Pham, Nakamura, ICRA 2015; the paper's printed matrix is
/// wrong).
///
/// With w = [fx fy fz tx ty tz] in the sole frame at the sole centre, X, Y the half-length and
/// half-width and mu the friction coefficient, w is admissible iff C w >= 0 with the 16 rows
///   |fx|, |fy| <= mu fz;  |tx| <= Y fz;  |ty| <= X fz;  tz_min <= tz <= tz_max,
///   tz_min = -mu(X+Y) fz + |Y fx - mu tx| + |X fy - mu ty|,
///   tz_max =  mu(X+Y) fz - |Y fx + mu tx| - |X fy + mu ty|.
/// This is exactly the set of wrenches produced by forces at the four sole corners that each
/// lie in a friction pyramid |fx_c|, |fy_c| <= mu fz_c (verified against an LP in
/// test/oracle/test_wrench_cone.py). In the world (eq. 8): C blkdiag(R^T, R^T) lambda >= 0,
/// lambda = [f; tau] in world orientation at the sole centre, R the sole's world orientation.

#include <Eigen/Core>

#include "reach_trajopt/contact/contact_config.h"

namespace reach_trajopt {

/// The 16 x 6 contact wrench cone of one rectangular sole (eq. 7-8). Immutable.
class ContactWrenchCone {
 public:
  static constexpr int kRows = 16;
  using Matrix = Eigen::Matrix<double, kRows, 6>;
  using Wrench = Eigen::Matrix<double, 6, 1>;

  /// The largest friction coefficient and sole half-size [m] accepted (far beyond any sole:
  /// larger ones only overflow the cone's entries).
  static constexpr double kMaxFriction = 1e3;
  static constexpr double kMaxSoleHalfSize = 10.0;

  /// \param mu           friction coefficient, in (0, kMaxFriction]
  /// \param half_length  X [m], in (0, kMaxSoleHalfSize], along the sole's x axis
  /// \param half_width   Y [m], in (0, kMaxSoleHalfSize], along the sole's y axis
  /// Throws ConfigError naming a parameter outside its range.
  ContactWrenchCone(double mu, double half_length, double half_width);
  explicit ContactWrenchCone(const ContactConfig& config);

  double mu() const { return mu_; }
  double halfLength() const { return half_length_; }
  double halfWidth() const { return half_width_; }

  /// C of eq. (7), acting on [f; tau] in the sole frame.
  const Matrix& soleMatrix() const { return C_; }
  /// C blkdiag(R^T, R^T) of eq. (8), acting on [f; tau] in world orientation.
  /// \param R_world_sole  sole orientation in the world (3 x 3 rotation)
  Matrix worldMatrix(const Eigen::Matrix3d& R_world_sole) const;
  /// Same, written into caller storage (no allocation; for hot loops).
  void worldMatrix(const Eigen::Matrix3d& R_world_sole, Matrix& out) const;

  /// min_i (C w)_i: >= 0 iff w (sole frame) is in the cone.
  double margin(const Wrench& w_sole) const;
  /// True iff C w >= -tolerance componentwise (w in the sole frame).
  bool contains(const Wrench& w_sole, double tolerance = 0.0) const;

 private:
  double mu_, half_length_, half_width_;
  Matrix C_;
};

}  // namespace reach_trajopt
