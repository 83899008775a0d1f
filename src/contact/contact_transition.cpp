/// \file contact_transition.cpp
/// Headings and flat contact poses (see the header).

#include "reach_trajopt/contact/contact_transition.h"

#include <cmath>

namespace reach_trajopt {

double yawOf(const Eigen::Isometry3d& T) { return std::atan2(T.linear()(1, 0), T.linear()(0, 0)); }

Eigen::Isometry3d FlatContact::pose() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = position;
  return T;
}

}  // namespace reach_trajopt
