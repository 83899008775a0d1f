#pragma once
/// \file verdict_recheck.h
/// verdict_grid's own re-check of a "reachable" verdict's certificate, written apart from the
/// check it judges: eq. (1) assembled from M, b and the sole Jacobian, the stance cone, the
/// limits, the held sole and the ground from the forward kinematics, the legs' collision
/// primitives by Bullet's GJK (testing/exact_leg_distance.h, not the check's capsules), the
/// Euler steps of the bridge, x(0) = x_0 and x(t_f) against x_f.

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "reach_trajopt/contact/contact_wrench_cone.h"
#include "reach_trajopt/step/footstep_transition_planner.h"
#include "reach_trajopt/testing/exact_leg_distance.h"

namespace reach_trajopt {
namespace verdict {

/// A path to re-check: samples k = 0..L-1 at time[k]; step k (k < L-1) has the acceleration
/// qdd[k], torques u[k] and the stance wrench lambda[k] (world orientation at the sole centre).
struct CheckedPath {
  std::vector<double> time;
  Eigen::MatrixXd q, qd, qdd, u, lambda;
  bool euler = false;  ///< a 1 ms Euler path (the bridge): q_{k+1} = q_k + dt qd_{k+1} (or qd_k)
  std::vector<char> semi_implicit;
};

/// The re-check's verdict: a sentence naming the first family beyond its tolerance.
struct Recheck {
  bool passed = true;
  std::string failure;
  void require(const char* family, double value, double tolerance) {
    if (passed && !(value <= tolerance)) {
      passed = false;
      failure =
          std::string(family) + " " + std::to_string(value) + " > " + std::to_string(tolerance);
    }
  }
};

/// The bridge's witness as a CheckedPath (step k: qdd = (qd_{k+1} - qd_k) / dt).
inline CheckedPath fromWitness(const WitnessPath& w, double dt) {
  CheckedPath p;
  p.time = w.time;
  p.q = w.q;
  p.qd = w.qd;
  p.u = w.u;
  p.lambda = w.lambda.topRows(6);
  p.qdd.resize(w.q.rows(), w.u.cols());
  for (int k = 0; k + 1 < w.q.cols(); ++k) p.qdd.col(k) = (w.qd.col(k + 1) - w.qd.col(k)) / dt;
  p.euler = true;
  p.semi_implicit = w.semi_implicit_step;
  return p;
}

/// The OCP's trajectory as a CheckedPath (its 1 ms samples, analytic qdd).
inline CheckedPath fromTrajectory(const TransitionResult& t, Side stance) {
  CheckedPath p;
  p.time.assign(t.time.data(), t.time.data() + t.time.size());
  p.q = t.q;
  p.qd = t.qd;
  const Eigen::Index steps = t.q.cols() - 1;
  p.qdd = t.qdd.leftCols(steps);
  p.u = t.u.leftCols(steps);
  p.lambda = t.lambda.block(stance == Side::kLeft ? 0 : 6, 0, 6, steps);
  return p;
}

/// The oracle's own 1 ms re-check: eq. (1) assembled from M, b and the sole Jacobian; the
/// stance cone (8) in the held sole's orientation; torque, position and velocity limits; the
/// held sole's pose and velocity and the swing sole's height from the forward kinematics; the
/// Euler steps of an Euler path; x(0) = x_0, t_f and x(t_f) against x_f.
inline Recheck recheckPath(const RobotModel& model, const ContactConfig& contact,
                           const ReachConfig& reach, double dynamics_tolerance,
                           const FootstepTransition& step, const CheckedPath& p) {
  Recheck out;
  const int L = static_cast<int>(p.time.size()), nq = model.nq(), nu = model.nu();
  if (L < 2) {
    out.require("samples", 0, 2);
    return out;
  }
  const double dt = L > 1 ? p.time[1] - p.time[0] : 0.0;
  const FrameId stance = model.frameId(contact.soleFrame(step.transition.stance));
  const FrameId swing = model.frameId(contact.soleFrame(opposite(step.transition.stance)));
  const Eigen::Isometry3d held = step.transition.stance_contact.pose();
  const ContactWrenchCone::Matrix C = ContactWrenchCone(contact).worldMatrix(held.linear());
  const Eigen::VectorXd u_max = model.effortLimits(), qd_max = model.velocityLimits();
  const Eigen::VectorXd q_lo = model.positionLowerLimits(), q_hi = model.positionUpperLimits();
  // The legs' shapes must not touch along a path that starts with them apart (the check keeps
  // their capsules, which contain them, contact.leg_clearance_margin apart).
  const std::optional<ExactLegDistance> legs =
      contact.leg_clearance
          ? std::optional<ExactLegDistance>(std::in_place, model, contact.left_sole_frame,
                                            contact.right_sole_frame)
          : std::nullopt;
  double legs_start = HUGE_VAL, legs_min = HUGE_VAL;
  Workspace ws(model);
  Eigen::MatrixXd M(nq, nq), J(6, nq);
  Eigen::VectorXd b(nq);
  double dyn = 0, cone = 0, torque = 0, pos = 0, vel = 0, sole = 0, sole_v = 0, depth = 0,
         euler = 0;
  for (int k = 0; k < L; ++k) {
    const auto q = p.q.col(k), qd = p.qd.col(k);
    model.update(ws, q, qd);
    const Eigen::Isometry3d X = model.framePose(ws, stance);
    const Eigen::AngleAxisd rot(held.linear().transpose() * X.linear());
    sole = std::max({sole, (X.translation() - held.translation()).norm(), std::abs(rot.angle())});
    model.frameJacobian(ws, stance, J);
    sole_v = std::max(sole_v, (J * qd).cwiseAbs().maxCoeff());
    depth = std::max(
        depth, step.transition.target.position.z() - model.framePose(ws, swing).translation().z());
    if (legs) {
      const double d = (*legs)(model, ws);
      if (k == 0) legs_start = d;
      legs_min = std::min(legs_min, d);
    }
    pos = std::max({pos, (q_lo - q).maxCoeff(), (q - q_hi).maxCoeff()});
    for (int i = 0; i < nq; ++i)
      if (std::isfinite(qd_max[i]) && qd_max[i] > 0)
        vel = std::max(vel, std::abs(qd[i]) - qd_max[i]);
    if (k + 1 == L) break;
    model.massMatrix(ws, M);
    model.bias(ws, b);
    Eigen::VectorXd r = M * p.qdd.col(k) + b - J.transpose() * p.lambda.col(k);
    r.tail(nu) -= p.u.col(k);
    dyn = std::max(dyn, r.cwiseAbs().maxCoeff());
    cone = std::max(cone, -(C * p.lambda.col(k)).minCoeff());
    torque = std::max(torque, (p.u.col(k).cwiseAbs() - u_max).maxCoeff());
    if (p.euler) {
      const Eigen::VectorXd v = p.semi_implicit[k] ? p.qd.col(k + 1) : p.qd.col(k);
      euler = std::max(euler, (p.q.col(k + 1) - q - dt * v).cwiseAbs().maxCoeff());
    }
  }
  const double W = model.totalMass() * model.gravity().norm();
  out.require("eq. (1) [N, Nm]", dyn, dynamics_tolerance);
  // The cone is written in the held (planned) sole orientation; the sole may be tilted from
  // it by up to the contact tolerance, which moves a row by at most |lambda| times that.
  out.require("stance cone [N]", cone, dynamics_tolerance + 2.0 * W * reach.contact_tolerance);
  out.require("torque limits [Nm]", torque, 1e-6);
  out.require("position limits [m, rad]", pos, 1e-6);
  out.require("velocity limits [m/s, rad/s]", vel, 1e-6);
  out.require("held sole pose [m, rad]", sole, 2.0 * reach.contact_tolerance);
  out.require("held sole velocity [m/s, rad/s]", sole_v,
              reach.certificate_contact_velocity_tolerance);
  out.require("swing sole below the ground [m]", depth, reach.certificate_tolerance);
  if (legs_start > 0.0) out.require("legs' shapes touching (exact distance 0)", -legs_min, -1e-9);
  out.require("Euler steps [m, rad]", euler, 1e-9);
  out.require("x(0) - x_0",
              std::max((p.q.col(0) - step.transition.q0).cwiseAbs().maxCoeff(),
                       (p.qd.col(0) - step.transition.qd0).cwiseAbs().maxCoeff()),
              1e-9);
  out.require("t_f", std::abs(p.time[L - 1] - step.transition.horizon), 1e-9);
  out.require("|q(t_f) - q_f|", (p.q.col(L - 1) - step.check.kinematics.q_f).cwiseAbs().maxCoeff(),
              reach.terminal_position_tolerance);
  out.require("|qd(t_f) - qd_f|", (p.qd.col(L - 1) - step.check.qdf).cwiseAbs().maxCoeff(),
              reach.terminal_velocity_tolerance);
  return out;
}

/// The re-check of a "reachable" step's certificate: the bridged witness, or the local solve.
inline Recheck recheckCertificate(const RobotModel& model, const ContactConfig& contact,
                                  const FootstepPlannerConfig& cfg, const ReachConfig& reach,
                                  const FootstepTransition& step) {
  if (step.certificate == Certificate::kBridge)
    return recheckPath(model, contact, reach, reach.certificate_tolerance, step,
                       fromWitness(step.check.reach.witness, reach.dt));
  // The OCP's tolerance is relative to m g and u_max; in newtons that is at most this.
  const double W = model.totalMass() * model.gravity().norm();
  const double tol = cfg.ocp.tolerance * std::max(W, model.effortLimits().maxCoeff());
  return recheckPath(model, contact, reach, tol, step,
                     fromTrajectory(step.trajectory, step.transition.stance));
}

}  // namespace verdict
}  // namespace reach_trajopt
