#include "reach_trajopt/walk/proposed_step.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <Eigen/QR>

namespace reach_trajopt {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double yawOf(const Eigen::Isometry3d& T) {
  return std::atan2(T.linear()(1, 0), T.linear()(0, 0));
}

}  // namespace

ProposedStepPlanner::ProposedStepPlanner(std::shared_ptr<const RobotModel> model,
                                         const ContactConfig& contact,
                                         const KinematicFeasibilityConfig& kinematics,
                                         const ReachConfig& reach, const TransitionOcpConfig& ocp)
    : model_(model),
      contact_(contact),
      reach_config_(reach),
      kinematics_(std::make_shared<KinematicFeasibility>(model, kinematics, contact)),
      footsteps_(std::make_shared<ReachabilityAnalyzer>(model, contact, reach), kinematics_),
      ocp_(model, ocp, contact) {}

ProposedStep ProposedStepPlanner::plan(Side stance, const Eigen::Isometry3d& stance_pose,
                                       const Eigen::Vector3d& target, const Eigen::VectorXd& q,
                                       const Eigen::VectorXd& qd) const {
  const RobotModel& m = *model_;
  m.checkState(q, qd);
  requireFinite("ProposedStepPlanner: target", target);
  // x_0 on the current mode's contact manifold: the simulator's stance sole creeps by
  // micrometres per step, which the check's tolerances (1e-4 m, 1e-3 m/s) would reject.
  // The landed stance sole may also be tilted by a degree or so: the whole robot is rotated
  // about the sole centre so that the sole is flat (the check's footholds are flat).
  Eigen::VectorXd q0 = q.cwiseMax(m.positionLowerLimits()).cwiseMin(m.positionUpperLimits());
  Workspace ws(m);
  const FrameId stance_frame =
      m.frameId(stance == Side::kLeft ? contact_.left_sole_frame : contact_.right_sole_frame);
  m.update(ws, q0, qd);
  {
    const Eigen::Isometry3d sole = m.framePose(ws, stance_frame);
    const Eigen::Matrix3d R_fix =
        Eigen::AngleAxisd(yawOf(sole), Eigen::Vector3d::UnitZ()).toRotationMatrix() *
        sole.linear().transpose();
    const Eigen::Matrix3d R_base =
        (Eigen::AngleAxisd(q0[3], Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(q0[4], Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(q0[5], Eigen::Vector3d::UnitX()))
            .toRotationMatrix();
    const Eigen::Matrix3d R = R_fix * R_base;
    q0.head<3>() = sole.translation() + R_fix * (q0.head<3>() - sole.translation());
    q0[3] = std::atan2(R(1, 0), R(0, 0));
    q0[4] = std::asin(std::max(-1.0, std::min(1.0, -R(2, 0))));
    q0[5] = std::atan2(R(2, 1), R(2, 2));
    m.update(ws, q0, qd);
  }
  Matrix6Xd J(6, m.nq());
  m.frameJacobian(ws, stance_frame, J);
  const Eigen::VectorXd qd0 =
      qd - J.transpose() * (J * J.transpose()).ldlt().solve(J * qd);
  const Eigen::Isometry3d held = m.framePose(ws, stance_frame);

  ProposedStep out;
  const auto check_start = std::chrono::steady_clock::now();
  FootstepRequest request;
  request.stance = stance;
  request.stance_foothold.position = held.translation();
  request.stance_foothold.yaw = yawOf(held);
  request.target.position = target;
  request.target.yaw = yawOf(stance_pose);
  request.q0 = q0;
  request.qd0 = qd0;
  out.check = footsteps_.check(request);
  const FootstepResult& check = out.check;
  out.check_time_s = secondsSince(check_start);
  out.kinematically_feasible = check.kinematically_feasible;
  out.reachable = check.reachable;
  out.verdict = !check.kinematically_feasible ? "kinematically_infeasible"
                                               : (check.reachable ? "reachable" : "unreachable");
  out.reason = check.reason;
  for (const SliceComparison& c : check.reach.window)
    out.hausdorff_distance = out.hausdorff_distance < 0.0
                                 ? c.distance.hausdorff
                                 : std::min(out.hausdorff_distance, c.distance.hausdorff);

  // The OCP: strict to the checked foothold when reachable, relaxed otherwise. Its final
  // state is the IK's q_f when the foothold is kinematically feasible; otherwise the IK is
  // solved for the closest point of the target's direction the legs can still reach, and the
  // relaxation decides the landing.
  TransitionRequest ocp;
  ocp.stance = stance;
  ocp.stance_pose = held;
  ocp.swing_target = request.target.pose();
  ocp.horizon = reach_config_.horizon;
  ocp.q0 = q0;
  ocp.qd0 = qd0;
  ocp.qdf = Eigen::VectorXd::Zero(m.nq());
  ocp.relaxation = check.reachable ? RelaxationMode::kStrict : RelaxationMode::kRelaxed;
  Eigen::Vector3d nearest_feasible = target;
  if (check.kinematically_feasible) {
    ocp.qf = check.kinematics.q_f;
  } else {
    // The closest kinematically feasible foothold (rings of growing radius around the target)
    // gives the relaxed OCP its terminal posture; the relaxation then decides the landing.
    constexpr double kRingStep = 0.02;  // [m]
    constexpr int kRings = 15, kDirections = 12;
    for (int ring = 1; ring <= kRings && ocp.qf.size() == 0; ++ring) {
      double best = HUGE_VAL;
      for (int d = 0; d < kDirections; ++d) {
        const double angle = 2.0 * M_PI * d / kDirections;
        FlatContact p = request.target;
        p.position = target + ring * kRingStep * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0);
        const KinematicFeasibilityResult k =
            kinematics_->check(stance, request.stance_foothold, p, q0);
        if (k.feasible && ring * kRingStep < best) {
          best = ring * kRingStep;
          ocp.qf = k.q_f;
          nearest_feasible = p.position;
        }
      }
    }
    if (ocp.qf.size() == 0) {
      out.reason += "; no kinematically feasible foothold toward the target";
      out.trajectory.status = OcpStatus::kFailed;
      out.trajectory.reason = "no kinematically feasible foothold toward the target";
      out.foothold = target;
      return out;
    }
  }
  if (check.reach.witness.valid) {
    const WitnessPath& w = check.reach.witness;
    ocp.seed.time = Eigen::Map<const Eigen::VectorXd>(w.time.data(), w.time.size());
    ocp.seed.q = w.q;
  }
  const auto ocp_start = std::chrono::steady_clock::now();
  out.trajectory = ocp_.solve(ocp);
  out.ocp_time_s = secondsSince(ocp_start);
  // Without a usable trajectory the swing still goes to the nearest kinematically feasible
  // foothold (the target itself when it is feasible).
  out.foothold = out.usable() ? out.trajectory.landing_position : nearest_feasible;
  if (!out.trajectory.reason.empty()) out.reason += "; OCP: " + out.trajectory.reason;
  return out;
}

}  // namespace reach_trajopt
