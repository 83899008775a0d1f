/// \file contact_transition.cpp
/// The flat contact's pose (see the header).

#include "reach_trajopt/contact/contact_transition.h"

namespace reach_trajopt {

Eigen::Isometry3d FlatContact::pose() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = position;
  return T;
}

}  // namespace reach_trajopt
