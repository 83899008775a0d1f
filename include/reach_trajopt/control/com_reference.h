#pragma once
/// \file com_reference.h
/// The horizontal CoM reference of the walking loop: the LIPM (eq. 9) integrated tick by tick
/// about a pivot, the stance sole in single support and, in double support, a pivot moving
/// from the old stance sole to the new one as the weight transfers. Standing (settle phase):
/// held at the standing CoM. The height is the standing CoM height throughout.

#include <Eigen/Core>

#include "reach_trajopt/control/whole_body_controller.h"
#include "reach_trajopt/planner/lipm.h"

namespace reach_trajopt {

/// @brief LIPM CoM reference (position, velocity, acceleration) for the whole-body controller.
class LipmComReference {
 public:
  /// \param standing_com  the CoM of the standing pose [m] (its height is the reference height)
  LipmComReference(const Lipm& lipm, const Eigen::Vector3d& standing_com);

  /// Single support from the measured CoM state, about the stance sole centre [m].
  void startSingleSupport(const LipmState& com, const Eigen::Vector2d& stance);
  /// Double support from the measured CoM state, the pivot moving `from` -> `to` [m].
  void startDoubleSupport(const LipmState& com, const Eigen::Vector2d& from,
                          const Eigen::Vector2d& to);
  /// The reference's CoM state becomes the measured `com`, its pivot kept (DCM feedback: the
  /// next steerCapturePoint() steers the measured capture point).
  void restart(const LipmState& com) { com_ = com; }
  /// One tick of `dt` [s] while walking; `transfer` in [0, 1] is how far the pivot has moved
  /// (1 in single support). Fills the CoM fields of `ref`.
  void advance(double dt, double transfer, WbcReference& ref);
  /// One tick of `dt` [s] of double support that steers the reference's capture point
  /// xi = p + pd / omega (eq. 9) to `target` [m] at the rate `gain` [1/s]: the pivot
  /// r = xi + (gain / omega) (xi - target), so that xi' = omega (xi - r) = -gain (xi - target),
  /// clamped to the box [support_min, support_max] [m] (the soles' support region; a capture
  /// point the box cannot steer keeps moving, as the robot's would). A non-finite target
  /// component leaves that axis unsteered: its pivot is the capture point (xi' = 0, held).
  /// Englsberger, Ott, Albu-Schaeffer, "Three-dimensional bipedal walking control based on
  /// divergent component of motion", IEEE T-RO 2015. Fills the CoM fields of `ref`.
  void steerCapturePoint(double dt, const Eigen::Vector2d& target, double gain,
                         const Eigen::Vector2d& support_min, const Eigen::Vector2d& support_max,
                         WbcReference& ref);
  /// One tick while standing: the standing CoM at rest.
  void hold(WbcReference& ref);

 private:
  void fill(WbcReference& ref) const;

  const Lipm& lipm_;
  Eigen::Vector3d standing_com_;
  LipmState com_;
  Eigen::Vector2d pivot_from_ = Eigen::Vector2d::Zero(), pivot_to_ = Eigen::Vector2d::Zero();
};

}  // namespace reach_trajopt
