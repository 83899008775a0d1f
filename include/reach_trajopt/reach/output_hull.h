#pragma once
/// \file output_hull.h
/// The convex hull of a slice's output set as half-spaces, to tell whether the other
/// direction's samples lie inside it: boundary propagation (21) leaves the later slices'
/// samples near their set's boundary, so a set lying inside the other's hull has no close
/// sample pair although the sets overlap. 3-D hulls come from Bullet's btConvexHullComputer,
/// 2-D ones from Andrew's monotone chain, 1-D ones are intervals.

#include <Eigen/Core>
#include <vector>

namespace reach_trajopt {

/// @brief Convex hull {y : n_k . y <= c_k} of a point set (n_y = 1, 2 or 3).
class OutputHull {
 public:
  /// \param points  n_y x N. A hull of fewer than n_y + 1 affinely independent points is
  ///     degenerate: it contains nothing.
  explicit OutputHull(const Eigen::Ref<const Eigen::MatrixXd>& points);
  bool degenerate() const { return normals_.cols() == 0; }
  /// True when y lies in the hull, up to `tolerance` [m] outside a face.
  bool contains(const Eigen::Ref<const Eigen::VectorXd>& y, double tolerance = 0.0) const;
  /// Number of columns of `points` inside the hull.
  int countInside(const Eigen::Ref<const Eigen::MatrixXd>& points, double tolerance = 0.0) const;
  const Eigen::MatrixXd& normals() const { return normals_; }  ///< n_y x faces, unit, outward
  const Eigen::VectorXd& offsets() const { return offsets_; }  ///< faces

 private:
  Eigen::MatrixXd normals_;  ///< unit outward normals, n_y x faces
  Eigen::VectorXd offsets_;  ///< c_k
};

}  // namespace reach_trajopt
