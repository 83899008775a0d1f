#include "reach_trajopt/contact/contact_constraint.h"

#include <cmath>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/model/spatial_algebra.h"

namespace reach_trajopt {

namespace {

void checkPose(const Eigen::Isometry3d& pose) {
  requireFinite("ContactConstraint: planned pose", pose.matrix());
  const Eigen::Matrix3d R = pose.linear();
  if (!(R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-9) || R.determinant() < 0) {
    throw RequestError("ContactConstraint: planned pose rotation is not a proper rotation matrix");
  }
}

}  // namespace

Vector6d ContactConstraintTerms::phiddot(const Eigen::Ref<const Eigen::VectorXd>& qdd) const {
  requireSize("ContactConstraintTerms::phiddot qdd", qdd.size(), J_phi.cols());
  Vector6d out = drift;
  out.noalias() += J_phi * qdd;
  return out;
}

ContactConstraint::ContactConstraint(FrameId frame, const Eigen::Isometry3d& planned_pose)
    : frame_(frame), planned_(planned_pose) {
  if (frame < 0) throw ModelError("ContactConstraint: invalid frame id " + std::to_string(frame));
  checkPose(planned_pose);
}

ContactConstraint::ContactConstraint(const RobotModel& model, const std::string& frame_name,
                                     const Eigen::Isometry3d& planned_pose)
    : ContactConstraint(model.frameId(frame_name), planned_pose) {}

Vector6d ContactConstraint::error(const Eigen::Isometry3d& pose, const Eigen::Isometry3d& planned) {
  Vector6d e;
  e.head<3>() = pose.translation() - planned.translation();
  const Eigen::AngleAxisd aa(Eigen::Matrix3d(pose.linear() * planned.linear().transpose()));
  e.tail<3>() = aa.angle() * aa.axis();
  return e;
}

Eigen::Matrix3d ContactConstraint::inverseLeftJacobian(const Eigen::Vector3d& e) {
  const double theta = e.norm();
  const Eigen::Matrix3d E = skew(e);
  // Jl^-1 = I - E/2 + c E^2, c = 1/theta^2 - (1 + cos theta) / (2 theta sin theta);
  // its series 1/12 + theta^2/720 avoids the cancellation near zero.
  double c;
  if (theta < 1e-4) {
    c = 1.0 / 12.0 + theta * theta / 720.0;
  } else {
    c = 1.0 / (theta * theta) - (1.0 + std::cos(theta)) / (2.0 * theta * std::sin(theta));
  }
  return Eigen::Matrix3d::Identity() - 0.5 * E + c * E * E;
}

Vector6d ContactConstraint::phi(const RobotModel& model, const Workspace& ws) const {
  return error(model.framePose(ws, frame_), planned_);
}

void ContactConstraint::evaluate(const RobotModel& model, const Workspace& ws,
                                 ContactConstraintTerms& out) const {
  requireSize("ContactConstraint::evaluate J_phi columns", out.J_phi.cols(), model.nq());
  out.phi = phi(model, ws);
  const Eigen::Matrix3d Jinv = inverseLeftJacobian(out.phi.tail<3>());
  model.frameJacobian(ws, frame_, out.J_phi);
  // Angular rows: J_phi = Jl^-1(e) J (in place, 3 x n_q block, column by column: no temporary).
  for (Eigen::Index c = 0; c < out.J_phi.cols(); ++c) {
    const Eigen::Vector3d w = out.J_phi.block<3, 1>(3, c);
    out.J_phi.block<3, 1>(3, c) = Jinv * w;
  }
  const Vector6d v = model.frameVelocity(ws, frame_);
  out.phidot.head<3>() = v.head<3>();
  out.phidot.tail<3>() = Jinv * v.tail<3>();
  const Vector6d a = model.frameJdotQd(ws, frame_);
  out.drift.head<3>() = a.head<3>();
  out.drift.tail<3>() = Jinv * a.tail<3>();
}

}  // namespace reach_trajopt
