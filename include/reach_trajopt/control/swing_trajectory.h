#pragma once
/// \file swing_trajectory.h
/// The baseline's interpolated swing-sole trajectory (Sec. IV-A): horizontal position by a
/// minimum-jerk (quintic) blend from lift-off to the planned contact, height by a smooth bump
/// 64 h s^3 (1 - s)^3 (zero velocity and acceleration at both ends, apex h at mid-swing) that
/// ends `touchdown_depth` below the ground so that touchdown is made by contact, not by time.

#include <Eigen/Core>
#include <vector>

namespace reach_trajopt {

/// Position, velocity and acceleration of the swing sole centre [m, m/s, m/s^2], world frame.
struct SwingSample {
  Eigen::Vector3d position, velocity, acceleration;
};

class SwingTrajectory {
 public:
  /// \param start           sole centre at lift-off [m]
  /// \param target          planned contact (sole centre on the ground) [m]
  /// \param duration        swing time [s] (> 0)
  /// \param apex_height     apex above the straight line [m] (>= 0)
  /// \param touchdown_depth how far below target.z the nominal end lies [m] (>= 0)
  /// \throws ReachError on non-finite input or a non-positive duration.
  SwingTrajectory(const Eigen::Vector3d& start, const Eigen::Vector3d& target, double duration,
                  double apex_height, double touchdown_depth);
  /// Sample at time t [s] since lift-off; past `duration` the sole keeps descending slowly
  /// at the final horizontal position (late touchdown).
  SwingSample sample(double t) const;
  /// Moves the end point (re-planned footstep) from `t` [s] since lift-off on: the change of
  /// the target is added by its own minimum-jerk blend over the time left, so that position,
  /// velocity and acceleration stay continuous at `t` (a target moved at lift-off is the
  /// constructor's). Past the swing's end the sole goes straight to it.
  void retarget(const Eigen::Vector3d& target, double t);
  double duration() const { return duration_; }
  const Eigen::Vector3d& target() const { return target_; }

 private:
  /// A change of the target made at `time` [s], blended in over [time, duration].
  struct Correction {
    double time;
    Eigen::Vector3d change;
  };
  Eigen::Vector3d start_, target_;
  Eigen::Vector3d first_target_;  ///< the target of the blend from start_
  std::vector<Correction> corrections_;
  double duration_, apex_, depth_;
};

}  // namespace reach_trajopt
