#include "reach_trajopt/ocp/transition_check.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/contact/contact_constraint.h"
#include "reach_trajopt/contact/contact_wrench_cone.h"
#include "reach_trajopt/model/leg_clearance.h"

namespace reach_trajopt {

namespace {

void requireTrajectorySizes(const RobotModel& model, const TransitionResult& traj) {
  const int nq = model.nq(), nu = model.nu();
  const int n = static_cast<int>(traj.time.size());
  if (n < 2) throw RequestError("checkTransition: the trajectory needs at least two samples");
  requireSize("checkTransition: q columns", traj.q.cols(), n);
  requireSize("checkTransition: q rows", traj.q.rows(), nq);
  requireSize("checkTransition: qd", traj.qd.cols(), n);
  requireSize("checkTransition: qdd", traj.qdd.cols(), n);
  requireSize("checkTransition: u rows", traj.u.rows(), nu);
  requireSize("checkTransition: u", traj.u.cols(), n);
  requireSize("checkTransition: lambda rows", traj.lambda.rows(), 12);
  requireSize("checkTransition: lambda", traj.lambda.cols(), n);
}

/// Eq. (1), (5), (8), the torque bounds and the limits at each sample of a trajectory.
class SampleCheck {
 public:
  SampleCheck(const RobotModel& model, const ContactConfig& contact,
              const TransitionRequest& request, const TransitionResult& traj)
      : model_(model),
        traj_(traj),
        f_stance_(model.frameId(contact.soleFrame(request.stance))),
        f_swing_(model.frameId(contact.soleFrame(opposite(request.stance)))),
        c_stance_(f_stance_, request.heldPose()),
        c_new_(f_swing_, newContact(request, traj)),
        C_s_(ContactWrenchCone(contact).worldMatrix(request.heldPose().linear())),
        C_n_(ContactWrenchCone(contact).worldMatrix(request.targetPose().linear())),
        W_(model.totalMass() * model.gravity().norm()),
        legs_(contact.leg_clearance
                  ? LegClearance(model, contact.left_sole_frame, contact.right_sole_frame)
                  : LegClearance()),
        u_max_(model.effortLimits()),
        qd_max_(model.velocityLimits()),
        q_lo_(model.positionLowerLimits()),
        q_hi_(model.positionUpperLimits()),
        is_(request.stance == Side::kLeft ? 0 : 6),
        in_(6 - is_),
        ws_(model),
        M_(model.nq(), model.nq()),
        b_(model.nq()),
        r_(model.nq()),
        Js_(6, model.nq()),
        Jn_(6, model.nq()),
        terms_(model.nq()) {}

  FrameId swingFrame() const { return f_swing_; }

  /// The legs' margin for a path from q0 (ContactConfig::legMarginFrom).
  void startAt(const ContactConfig& contact, const Eigen::VectorXd& q0) {
    if (legs_.empty() || !contact.leg_clearance) return;
    leg_margin_ = contact.legMarginFrom(legs_.distanceAt(model_, q0));
  }

  /// Checks sample k into `v`; returns its worst cone / torque / leg clearance violation.
  double check(int k, ConstraintViolations& v) {
    const int nq = model_.nq(), nu = model_.nu();
    const int n = static_cast<int>(traj_.time.size());
    const auto q = traj_.q.col(k), qd = traj_.qd.col(k), qdd = traj_.qdd.col(k);
    model_.update(ws_, q, qd);
    model_.massMatrix(ws_, M_);
    model_.bias(ws_, b_);
    model_.frameJacobian(ws_, f_stance_, Js_);
    model_.frameJacobian(ws_, f_swing_, Jn_);
    const Vector6d ls = traj_.lambda.col(k).segment<6>(is_);
    const Vector6d ln = traj_.lambda.col(k).segment<6>(in_);
    // Eq. (1): M qdd + b - S^T u - sum J^T lambda.
    r_.noalias() = M_ * qdd + b_ - Js_.transpose() * ls - Jn_.transpose() * ln;
    r_.tail(nu) -= traj_.u.col(k);
    v.dynamics = std::max(v.dynamics, r_.head<6>().cwiseAbs().maxCoeff() / W_);
    v.dynamics = std::max(v.dynamics, r_.tail(nu).cwiseAbs().cwiseQuotient(u_max_).maxCoeff());
    // Eq. (5), stance sole.
    c_stance_.evaluate(model_, ws_, terms_);
    const double cs =
        std::max({terms_.phi.cwiseAbs().maxCoeff(), terms_.phidot.cwiseAbs().maxCoeff(),
                  terms_.phiddot(qdd).cwiseAbs().maxCoeff()});
    v.stance_contact = std::max(v.stance_contact, cs);
    // Eq. (8), stance cone; torque bounds.
    const double cone_v = std::max(0.0, -(C_s_ * ls).minCoeff() / W_);
    v.stance_cone = std::max(v.stance_cone, cone_v);
    const double tq =
        std::max(0.0, (traj_.u.col(k).cwiseAbs() - u_max_).cwiseQuotient(u_max_).maxCoeff());
    v.torque = std::max(v.torque, tq);
    // A wrench on the new contact before t_f would be an error.
    if (k + 1 < n) v.new_cone = std::max(v.new_cone, ln.cwiseAbs().maxCoeff() / W_);
    // Joint and velocity limits.
    v.joint_limits =
        std::max({v.joint_limits, (q_lo_ - q).maxCoeff(), (q - q_hi_).maxCoeff(), 0.0});
    for (int i = 0; i < nq; ++i) {
      if (std::isfinite(qd_max_[i]) && qd_max_[i] > 0) {
        v.velocity_limits =
            std::max(v.velocity_limits, (std::abs(qd[i]) - qd_max_[i]) / qd_max_[i]);
      }
    }
    if (k + 1 == n) {  // new mode at t_f: eq. (5) and (8) for the new contact
      c_new_.evaluate(model_, ws_, terms_);
      v.new_contact =
          std::max({terms_.phi.cwiseAbs().maxCoeff(), terms_.phidot.cwiseAbs().maxCoeff(),
                    terms_.phiddot(qdd).cwiseAbs().maxCoeff()});
      v.new_cone = std::max(v.new_cone, std::max(0.0, -(C_n_ * ln).minCoeff() / W_));
    }
    // The legs' clearance (eq. 4's h_state), every sample.
    double leg_v = 0.0;
    if (leg_margin_ > -HUGE_VAL) {
      leg_v = std::max(0.0, leg_margin_ - legs_.closest(model_, ws_).distance);
      v.leg_clearance = std::max(v.leg_clearance, leg_v);
    }
    return std::max({cone_v, tq, leg_v});
  }

  /// Largest distance outside the slice's hull (A y <= b) of the swing sole at the sample
  /// nearest to the slice's time [m].
  double reachableSetViolation(const ReachableSlice& sl) {
    const int n = static_cast<int>(traj_.time.size());
    int k = 0;
    for (int j = 1; j < n; ++j) {
      if (std::abs(traj_.time[j] - sl.time) < std::abs(traj_.time[k] - sl.time)) k = j;
    }
    model_.update(ws_, traj_.q.col(k), traj_.qd.col(k));
    const Eigen::Vector2d y = model_.framePose(ws_, f_swing_).translation().head<2>();
    double worst = 0.0;
    for (Eigen::Index i = 0; i < sl.A.rows(); ++i) {
      worst = std::max(worst, (sl.A.row(i).dot(y) - sl.b[i]) / sl.A.row(i).norm());
    }
    return worst;
  }

 private:
  static Eigen::Isometry3d newContact(const TransitionRequest& request,
                                      const TransitionResult& traj) {
    Eigen::Isometry3d target = request.targetPose();
    if (traj.relaxed) target.translation().head<2>() += traj.eps;
    return target;
  }

  const RobotModel& model_;
  const TransitionResult& traj_;
  const FrameId f_stance_, f_swing_;
  const ContactConstraint c_stance_, c_new_;
  const ContactWrenchCone::Matrix C_s_, C_n_;
  const double W_;
  const LegClearance legs_;
  double leg_margin_ = -HUGE_VAL;  ///< set by startAt() [m]
  const Eigen::VectorXd u_max_, qd_max_, q_lo_, q_hi_;
  const int is_, in_;
  Workspace ws_;
  Eigen::MatrixXd M_;
  Eigen::VectorXd b_, r_;
  Matrix6Xd Js_, Jn_;
  ContactConstraintTerms terms_;
};

/// The time of the worst sample of each run of samples violating `threshold`.
std::vector<double> violatingTimes(const std::vector<double>& time,
                                   const std::vector<double>& violation, double threshold) {
  std::vector<double> out;
  const int n = static_cast<int>(violation.size());
  for (int k = 0; k < n;) {
    if (violation[k] <= threshold) {
      ++k;
      continue;
    }
    int worst = k;
    while (k < n && violation[k] > threshold) {
      if (violation[k] > violation[worst]) worst = k;
      ++k;
    }
    out.push_back(time[worst]);
  }
  return out;
}

}  // namespace

TransitionCheck checkTransition(const RobotModel& model, const ContactConfig& contact,
                                const TransitionRequest& request, const TransitionResult& traj,
                                double threshold) {
  requireTrajectorySizes(model, traj);
  const int n = static_cast<int>(traj.time.size());
  SampleCheck samples(model, contact, request, traj);
  samples.startAt(contact, request.q0);
  TransitionCheck out;
  ConstraintViolations& v = out.violation;
  std::vector<double> ineq(n, 0.0);  // worst cone / torque / leg violation per sample
  for (int k = 0; k < n; ++k) ineq[k] = samples.check(k, v);
  v.initial_state = std::max((traj.q.col(0) - request.q0).cwiseAbs().maxCoeff(),
                             (traj.qd.col(0) - request.qd0).cwiseAbs().maxCoeff());
  if (!traj.relaxed) {
    v.final_state = std::max((traj.q.col(n - 1) - request.qf).cwiseAbs().maxCoeff(),
                             (traj.qd.col(n - 1) - request.qdf).cwiseAbs().maxCoeff());
  }
  for (size_t s = 0; s < request.slices.size(); ++s) {
    const double worst = samples.reachableSetViolation(request.slices[s]);
    v.reachable_set = std::max(v.reachable_set, worst);
    if (worst > threshold) out.violating_slices.push_back(static_cast<int>(s));
  }
  const std::vector<double> time(traj.time.data(), traj.time.data() + traj.time.size());
  out.violating_times = violatingTimes(time, ineq, threshold);
  return out;
}

}  // namespace reach_trajopt
