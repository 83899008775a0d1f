/// \file transition_recheck.cpp
/// The tests' re-check of a footstep's OCP trajectory (see the header).

#include "reach_trajopt/testing/transition_recheck.h"

#include <algorithm>

namespace reach_trajopt {

TransitionRecheck recheckTransition(const RobotModel& m, const ContactConfig& contact,
                                    const FootstepTransition& step) {
  const TransitionResult& t = step.trajectory;
  const FrameId left = m.frameId(contact.left_sole_frame);
  const FrameId right = m.frameId(contact.right_sole_frame);
  const bool left_stance = step.transition.stance == Side::kLeft;
  const FrameId stance = left_stance ? left : right, swing = left_stance ? right : left;
  Workspace ws(m);
  Eigen::MatrixXd M(m.nq(), m.nq()), J_left(6, m.nq()), J_right(6, m.nq());
  Eigen::VectorXd b(m.nq());
  TransitionRecheck r;
  for (int k = 0; k < t.q.cols(); ++k) {
    m.update(ws, t.q.col(k), t.qd.col(k));
    r.held_sole = std::max(
        r.held_sole,
        (m.framePose(ws, stance).translation() - step.transition.stance_contact.position).norm());
    m.massMatrix(ws, M);
    m.bias(ws, b);
    m.frameJacobian(ws, left, J_left);
    m.frameJacobian(ws, right, J_right);
    Eigen::VectorXd res = M * t.qdd.col(k) + b - J_left.transpose() * t.lambda.col(k).head<6>() -
                          J_right.transpose() * t.lambda.col(k).tail<6>();
    res.tail(m.nu()) -= t.u.col(k);
    r.dynamics = std::max(r.dynamics, res.cwiseAbs().maxCoeff());
    if (k + 1 == t.q.cols())
      r.landing = (m.framePose(ws, swing).translation() - step.foothold).head<2>().norm();
  }
  const Eigen::Index last = t.q.cols() - 1;
  r.end_q = (t.q.col(last) - step.check.kinematics.q_f).cwiseAbs().maxCoeff();
  r.end_qd = (t.qd.col(last) - step.check.qdf).cwiseAbs().maxCoeff();
  return r;
}

}  // namespace reach_trajopt
