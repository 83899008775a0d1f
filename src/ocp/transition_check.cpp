#include "reach_trajopt/ocp/transition_check.h"

#include <algorithm>
#include <cmath>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/contact/contact_constraint.h"
#include "reach_trajopt/contact/contact_wrench_cone.h"

namespace reach_trajopt {

TransitionCheck checkTransition(const RobotModel& model, const ContactConfig& contact,
                                const TransitionRequest& request, const TransitionResult& traj,
                                double threshold) {
  const int nq = model.nq(), nu = model.nu();
  const int n = static_cast<int>(traj.time.size());
  if (n < 2) throw ReachError("checkTransition: the trajectory needs at least two samples");
  requireSize("checkTransition: q columns", traj.q.cols(), n);
  requireSize("checkTransition: q rows", traj.q.rows(), nq);
  requireSize("checkTransition: qd", traj.qd.cols(), n);
  requireSize("checkTransition: qdd", traj.qdd.cols(), n);
  requireSize("checkTransition: u rows", traj.u.rows(), nu);
  requireSize("checkTransition: u", traj.u.cols(), n);
  requireSize("checkTransition: lambda rows", traj.lambda.rows(), 12);
  requireSize("checkTransition: lambda", traj.lambda.cols(), n);

  const Side stance = request.stance, swing = opposite(request.stance);
  const FrameId f_stance = model.frameId(stance == Side::kLeft ? contact.left_sole_frame
                                                               : contact.right_sole_frame);
  const FrameId f_swing =
      model.frameId(swing == Side::kLeft ? contact.left_sole_frame : contact.right_sole_frame);
  const ContactConstraint c_stance(f_stance, request.stance_pose);
  Eigen::Isometry3d target = request.swing_target;
  if (traj.relaxed) target.translation().head<2>() += traj.eps;
  const ContactConstraint c_new(f_swing, target);
  const ContactWrenchCone cone(contact);
  const ContactWrenchCone::Matrix C_s = cone.worldMatrix(request.stance_pose.linear());
  const ContactWrenchCone::Matrix C_n = cone.worldMatrix(request.swing_target.linear());
  const double W = model.totalMass() * model.gravity().norm();
  const Eigen::VectorXd u_max = model.effortLimits();
  const Eigen::VectorXd qd_max = model.velocityLimits();
  const Eigen::VectorXd q_lo = model.positionLowerLimits(), q_hi = model.positionUpperLimits();
  const int is = stance == Side::kLeft ? 0 : 6, in = 6 - is;

  Workspace ws(model);
  Eigen::MatrixXd M(nq, nq);
  Eigen::VectorXd b(nq), r(nq);
  Matrix6Xd Js(6, nq), Jn(6, nq);
  ContactConstraintTerms terms(nq);
  TransitionCheck out;
  ConstraintViolations& v = out.violation;
  std::vector<double> ineq(n, 0.0);  // worst cone / torque violation per sample

  for (int k = 0; k < n; ++k) {
    const auto q = traj.q.col(k), qd = traj.qd.col(k), qdd = traj.qdd.col(k);
    model.update(ws, q, qd);
    model.massMatrix(ws, M);
    model.bias(ws, b);
    model.frameJacobian(ws, f_stance, Js);
    model.frameJacobian(ws, f_swing, Jn);
    const Vector6d ls = traj.lambda.col(k).segment<6>(is);
    const Vector6d ln = traj.lambda.col(k).segment<6>(in);
    // Eq. (1): M qdd + b - S^T u - sum J^T lambda.
    r.noalias() = M * qdd + b - Js.transpose() * ls - Jn.transpose() * ln;
    r.tail(nu) -= traj.u.col(k);
    v.dynamics = std::max(v.dynamics, r.head<6>().cwiseAbs().maxCoeff() / W);
    v.dynamics = std::max(v.dynamics, r.tail(nu).cwiseAbs().cwiseQuotient(u_max).maxCoeff());
    // Eq. (5), stance sole.
    c_stance.evaluate(model, ws, terms);
    const double cs = std::max({terms.phi.cwiseAbs().maxCoeff(), terms.phidot.cwiseAbs().maxCoeff(),
                                terms.phiddot(qdd).cwiseAbs().maxCoeff()});
    v.stance_contact = std::max(v.stance_contact, cs);
    // Eq. (8), stance cone; torque bounds.
    const double cone_v = std::max(0.0, -(C_s * ls).minCoeff() / W);
    v.stance_cone = std::max(v.stance_cone, cone_v);
    const double tq = std::max(
        0.0, (traj.u.col(k).cwiseAbs() - u_max).cwiseQuotient(u_max).maxCoeff());
    v.torque = std::max(v.torque, tq);
    ineq[k] = std::max(cone_v, tq);
    // A wrench on the new contact before t_f would be an error.
    if (k + 1 < n) v.new_cone = std::max(v.new_cone, ln.cwiseAbs().maxCoeff() / W);
    // Joint and velocity limits.
    v.joint_limits = std::max(
        {v.joint_limits, (q_lo - q).maxCoeff(), (q - q_hi).maxCoeff(), 0.0});
    for (int i = 0; i < nq; ++i) {
      if (std::isfinite(qd_max[i]) && qd_max[i] > 0) {
        v.velocity_limits =
            std::max(v.velocity_limits, (std::abs(qd[i]) - qd_max[i]) / qd_max[i]);
      }
    }
    if (k + 1 == n) {  // new mode at t_f: eq. (5) and (8) for the new contact
      c_new.evaluate(model, ws, terms);
      v.new_contact = std::max({terms.phi.cwiseAbs().maxCoeff(),
                                terms.phidot.cwiseAbs().maxCoeff(),
                                terms.phiddot(qdd).cwiseAbs().maxCoeff()});
      v.new_cone = std::max(v.new_cone, std::max(0.0, -(C_n * ln).minCoeff() / W));
    }
  }
  v.initial_state = std::max((traj.q.col(0) - request.q0).cwiseAbs().maxCoeff(),
                             (traj.qd.col(0) - request.qd0).cwiseAbs().maxCoeff());
  if (!traj.relaxed) {
    v.final_state = std::max((traj.q.col(n - 1) - request.qf).cwiseAbs().maxCoeff(),
                             (traj.qd.col(n - 1) - request.qdf).cwiseAbs().maxCoeff());
  }
  // Reachable-set hulls at the sample nearest to each slice's time.
  for (size_t s = 0; s < request.slices.size(); ++s) {
    const ReachableSlice& sl = request.slices[s];
    int k = 0;
    for (int j = 1; j < n; ++j) {
      if (std::abs(traj.time[j] - sl.time) < std::abs(traj.time[k] - sl.time)) k = j;
    }
    model.update(ws, traj.q.col(k), traj.qd.col(k));
    const Eigen::Vector2d y = model.framePose(ws, f_swing).translation().head<2>();
    double worst = 0.0;
    for (Eigen::Index i = 0; i < sl.A.rows(); ++i) {
      worst = std::max(worst, (sl.A.row(i).dot(y) - sl.b[i]) / sl.A.row(i).norm());
    }
    v.reachable_set = std::max(v.reachable_set, worst);
    if (worst > threshold) out.violating_slices.push_back(static_cast<int>(s));
  }
  // The worst sample of each run of violating samples.
  for (int k = 0; k < n;) {
    if (ineq[k] <= threshold) {
      ++k;
      continue;
    }
    int worst = k;
    while (k < n && ineq[k] > threshold) {
      if (ineq[k] > ineq[worst]) worst = k;
      ++k;
    }
    out.violating_times.push_back(traj.time[worst]);
  }
  return out;
}

}  // namespace reach_trajopt
