#pragma once
/// \file exact_leg_distance.h
/// An oracle of the legs' clearance written apart from model/leg_clearance.h: the distance
/// between the legs' URDF collision primitives themselves (boxes, cylinders, spheres; no
/// capsules), computed by Bullet's GJK. Used by test_leg_clearance and verdict_grid's re-check.

#include <memory>
#include <string>

#include "reach_trajopt/common/side.h"
#include "reach_trajopt/model/robot_model.h"

namespace reach_trajopt {

/// @brief Exact distance between the left and the right leg's collision primitives.
class ExactLegDistance {
 public:
  /// A leg: the links from which the path to the root meets the sole's own path to the root
  /// before the other sole's. \throws ReachError naming an unknown sole frame.
  ExactLegDistance(const RobotModel& model, const std::string& left_sole_frame,
                   const std::string& right_sole_frame);
  ~ExactLegDistance();
  ExactLegDistance(ExactLegDistance&&) noexcept;

  /// Primitives of one leg.
  int shapeCount(Side side) const;
  /// Smallest distance between a left and a right primitive at the model's last update() [m];
  /// 0 when two of them touch or overlap (GJK gives no depth here); +inf without shapes.
  double operator()(const RobotModel& model, const Workspace& ws) const;

 private:
  struct Shapes;
  std::unique_ptr<Shapes> shapes_;
};

}  // namespace reach_trajopt
