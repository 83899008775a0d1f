#include "reach_trajopt/walk/proposed_step.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <Eigen/Cholesky>

#include "reach_trajopt/planner/double_support_velocity.h"
#include "reach_trajopt/sim/base_coordinates.h"

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
                                       const Eigen::VectorXd& qd,
                                       const std::optional<LipmState>& touchdown_com) const {
  const RobotModel& m = *model_;
  m.checkState(q, qd);
  requireFinite("ProposedStepPlanner: target", target);
  if (touchdown_com) {
    requireFinite("ProposedStepPlanner: touchdown CoM position", touchdown_com->p);
    requireFinite("ProposedStepPlanner: touchdown CoM velocity", touchdown_com->pd);
  }
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
    q0.head<3>() = sole.translation() + R_fix * (q0.head<3>() - sole.translation());
    q0.segment<3>(3) = eulerFromRotation(R_fix * rotationFromEuler(q0.segment<3>(3)));
    m.update(ws, q0, qd);
  }
  Matrix6Xd J(6, m.nq());
  m.frameJacobian(ws, stance_frame, J);
  const Eigen::VectorXd qd0 =
      qd - J.transpose() * (J * J.transpose()).ldlt().solve(J * qd);
  const Eigen::Isometry3d held = m.framePose(ws, stance_frame);
  // x_f: where the CoM will have carried the pelvis by touchdown, at its current height.
  std::optional<Eigen::Vector3d> touchdown_pelvis;
  Eigen::Vector3d touchdown_com_velocity = Eigen::Vector3d::Zero();
  if (touchdown_com) {
    const Eigen::Vector3d com = m.centerOfMass(ws);
    const Eigen::Vector3d com_shift(touchdown_com->p.x() - com.x(), touchdown_com->p.y() - com.y(),
                                    0.0);
    touchdown_pelvis =
        m.framePose(ws, m.frameId(kinematics_->config().pelvis_frame)).translation() + com_shift;
    touchdown_com_velocity.head<2>() = touchdown_com->pd;
  }

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
  request.touchdown_com_velocity = touchdown_com_velocity.head<2>();
  request.touchdown_pelvis_position = touchdown_pelvis;
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

  // The OCP: strict to the checked foothold when reachable, relaxed (to the closest reachable
  // foothold) when unreachable. A kinematically infeasible target (e.g. one sole through the
  // other) has no reachable sets: the closest kinematically feasible foothold (rings of growing
  // radius around the target) is taken instead, with its IK posture as x_f, strict first and
  // relaxed if that fails.
  TransitionRequest ocp;
  ocp.stance = stance;
  ocp.stance_pose = held;
  ocp.swing_target = request.target.pose();
  ocp.horizon = reach_config_.horizon;
  ocp.q0 = q0;
  ocp.qd0 = qd0;
  if (touchdown_pelvis)  // a relaxed landing stands at the predicted pelvis height
    ocp.terminal_pelvis_height =
        touchdown_pelvis->z() - 0.5 * (held.translation().z() + target.z());
  Eigen::Vector3d nearest_feasible = target;
  if (check.kinematically_feasible) {
    ocp.qf = check.kinematics.q_f;
    ocp.qdf = check.qdf;
    ocp.relaxation = check.reachable ? RelaxationMode::kStrict : RelaxationMode::kRelaxed;
  } else {
    constexpr double kRingStep = 0.02;  // [m]
    constexpr int kRings = 15, kDirections = 12;
    for (int ring = 1; ring <= kRings && ocp.qf.size() == 0; ++ring) {
      for (int d = 0; d < kDirections && ocp.qf.size() == 0; ++d) {
        const double angle = 2.0 * M_PI * d / kDirections;
        FlatContact p = request.target;
        p.position = target + ring * kRingStep * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0);
        const KinematicFeasibilityResult k =
            kinematics_->check(stance, request.stance_foothold, p, q0, touchdown_pelvis);
        if (k.feasible) {
          ocp.qf = k.q_f;
          nearest_feasible = p.position;
        }
      }
    }
    if (ocp.qf.size() == 0) {
      out.reason += "; no kinematically feasible foothold within " +
                    std::to_string(kRings * kRingStep) + " m of the target";
      out.trajectory.status = OcpStatus::kFailed;
      out.trajectory.reason = "no kinematically feasible foothold near the target";
      out.foothold = target;
      return out;
    }
    ocp.swing_target.translation() = nearest_feasible;
    ocp.qdf = doubleSupportVelocity(
        m, ocp.qf, m.frameId(contact_.left_sole_frame), m.frameId(contact_.right_sole_frame),
        touchdown_com_velocity);
    ocp.relaxation = RelaxationMode::kAuto;
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
