#pragma once
/// \file reachable_slice.h
/// What the transition OCP takes from the reachability check's forward set (eq. 23): one
/// convex hull of the swing sole's outputs per time slice. A plain struct of its own so the OCP
/// does not depend on the reachability engine's headers.

#include <Eigen/Core>

namespace reach_trajopt {

/// One time slice of the swing sole's reachable output set: the 2-D convex hull
/// {y = (x, y) of the swing sole centre in the world [m] : A y <= b}.
struct ReachableSlice {
  double time = 0.0;   ///< since t_0 [s], in [0, horizon]
  Eigen::MatrixX2d A;  ///< m x 2 half-space normals (need not be normalized)
  Eigen::VectorXd b;   ///< m offsets [m times |row of A|]
};

}  // namespace reach_trajopt
