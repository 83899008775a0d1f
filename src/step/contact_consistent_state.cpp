/// \file contact_consistent_state.cpp
/// A measured state moved onto the stance sole's contact manifold (see the header).

#include "reach_trajopt/step/contact_consistent_state.h"

#include <Eigen/Cholesky>
#include <cmath>

#include "reach_trajopt/model/euler_angles.h"

namespace reach_trajopt {

ContactConsistentState contactConsistentState(const RobotModel& m, FrameId stance_frame,
                                              const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  m.checkState(q, qd);
  ContactConsistentState out;
  out.q = q.cwiseMax(m.positionLowerLimits()).cwiseMin(m.positionUpperLimits());
  Workspace ws(m);
  m.update(ws, out.q, qd);
  {  // rotate the whole robot about the sole centre so that the sole is flat
    const Eigen::Isometry3d sole = m.framePose(ws, stance_frame);
    const Eigen::Matrix3d R_fix =
        Eigen::AngleAxisd(yawOf(sole), Eigen::Vector3d::UnitZ()).toRotationMatrix() *
        sole.linear().transpose();
    out.q.head<3>() = sole.translation() + R_fix * (out.q.head<3>() - sole.translation());
    out.q.segment<3>(3) = eulerFromRotation(R_fix * rotationFromEuler(out.q.segment<3>(3)));
    m.update(ws, out.q, qd);
  }
  Matrix6Xd J(6, m.nq());
  m.frameJacobian(ws, stance_frame, J);
  out.qd = qd - J.transpose() * (J * J.transpose()).ldlt().solve(J * qd);
  out.stance_sole = m.framePose(ws, stance_frame);
  return out;
}

}  // namespace reach_trajopt
