#include "reach_trajopt/ros/service_requests.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/ros/conversions.h"
#include "reach_trajopt/step/contact_consistent_state.h"

namespace reach_trajopt {
namespace ros_bridge {

namespace {

Eigen::VectorXd toVector(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

std::vector<geometry_msgs::Point> columnsToPoints(const Eigen::MatrixXd& Y,
                                                  const std::vector<int>& columns) {
  std::vector<geometry_msgs::Point> pts;
  pts.reserve(columns.size());
  for (int c : columns) {
    geometry_msgs::Point p;
    p.x = Y.rows() > 0 ? Y(0, c) : 0.0;
    p.y = Y.rows() > 1 ? Y(1, c) : 0.0;
    p.z = Y.rows() > 2 ? Y(2, c) : 0.0;
    pts.push_back(p);
  }
  return pts;
}

std::vector<int> evenlyThinned(int n, int max_points) {
  std::vector<int> idx;
  if (n <= 0 || max_points <= 0) return idx;
  const int m = std::min(n, max_points);
  for (int k = 0; k < m; ++k) idx.push_back(static_cast<int>(static_cast<long>(k) * n / m));
  return idx;
}

// Boundary samples ordered by angle about their centroid (a drawable outline in x, y).
std::vector<int> orderedBoundary(const SampleSlice& s) {
  std::vector<int> b = s.boundary;
  if (b.size() < 3 || s.output.rows() < 2) return b;
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (int i : b) c += s.output.col(i).head<2>();
  c /= static_cast<double>(b.size());
  std::sort(b.begin(), b.end(), [&](int i, int j) {
    const Eigen::Vector2d a = s.output.col(i).head<2>() - c, d = s.output.col(j).head<2>() - c;
    return std::atan2(a.y(), a.x()) < std::atan2(d.y(), d.x());
  });
  return b;
}

void appendRowMajor(const Eigen::MatrixXd& M, std::vector<double>& out) {
  // M is n x N (one column per knot): the message wants knot-major rows.
  out.reserve(out.size() + M.size());
  for (Eigen::Index k = 0; k < M.cols(); ++k)
    for (Eigen::Index i = 0; i < M.rows(); ++i) out.push_back(M(i, k));
}

// Knot-major rows of a message (N x rows) into a rows x N matrix (one column per knot); an
// empty field (a result that did not fill it) gives an empty matrix.
Eigen::MatrixXd fromRowMajor(const std::vector<double>& v, Eigen::Index rows, Eigen::Index knots,
                             const std::string& field) {
  if (v.empty()) return Eigen::MatrixXd();
  if (v.size() != static_cast<size_t>(rows * knots))
    throw ReachError("transition trajectory: " + field + " has " + std::to_string(v.size()) +
                     " numbers, expected " + std::to_string(knots) + " knots x " +
                     std::to_string(rows));
  return Eigen::Map<const Eigen::MatrixXd>(v.data(), rows, knots);
}

}  // namespace

ContactTransition parseFootholdRequest(const RobotModel& model, const ContactConfig& contact,
                                       const std::string& frame_id, const std::string& contact_mode,
                                       const std::vector<double>& q, const std::vector<double>& qd,
                                       const geometry_msgs::Point& foothold, double duration,
                                       double default_duration, const Eigen::VectorXd& standing_q,
                                       const FootholdRequestLimits& limits) {
  requireWorldFrame(frame_id);
  if (contact_mode.empty() || contact_mode == "flight")
    throw RequestError("empty contact set (mode '" + contact_mode +
                       "'): the robot must stand on one sole (SS-L or SS-R)");
  const ContactMode mode = ContactMode::fromName(contact_mode);  // throws on unknown names
  if (!mode.isSingleSupport())
    throw RequestError("contact mode " + contact_mode +
                       " has no swing sole: the check needs single support (SS-L or SS-R)");
  ContactTransition r;
  r.stance = mode.stance();
  if (q.empty() && qd.empty()) {
    r.q0 = standing_q;
    r.qd0 = Eigen::VectorXd::Zero(model.nq());
  } else {
    requireSize("q", static_cast<Eigen::Index>(q.size()), model.nq());
    requireSize("qd", static_cast<Eigen::Index>(qd.size()), model.nq());
    r.q0 = toVector(q);
    r.qd0 = toVector(qd);
  }
  requireFinite("q", r.q0);
  requireFinite("qd", r.qd0);
  const Eigen::Vector3d target = fromPointMsg(foothold);
  requireFinite("foothold", target);
  r.horizon = duration == 0.0 ? default_duration : duration;
  if (!std::isfinite(r.horizon))
    throw RequestError("swing_duration must be finite, got " + std::to_string(r.horizon));
  if (!(r.horizon > 0.0))
    throw RequestError("swing_duration " + std::to_string(r.horizon) + " s must be positive");
  if (r.horizon > limits.max_duration)
    throw RequestError("swing_duration " + std::to_string(r.horizon) + " s is over the limit of " +
                       std::to_string(limits.max_duration) + " s");

  Workspace ws(model);
  model.update(ws, r.q0, r.qd0);
  const std::string& stance_frame =
      r.stance == Side::kLeft ? contact.left_sole_frame : contact.right_sole_frame;
  const Eigen::Isometry3d stance = model.framePose(ws, model.frameId(stance_frame));
  r.stance_contact = FlatContact::fromPose(stance);
  const double height = target.z() - stance.translation().z();
  if (std::abs(height) > limits.ground_tolerance) {
    std::ostringstream os;
    os << "foothold at z = " << target.z() << " m is " << height
       << " m from the ground (stance sole at z = " << stance.translation().z() << " m, tolerance "
       << limits.ground_tolerance << " m): a foothold must lie on the ground";
    throw RequestError(os.str());
  }
  r.target.position = target;
  r.target.yaw = r.stance_contact.yaw;
  return r;
}

reach_trajopt::ReachabilityResult reachabilityVerdictMsg(const std::string& verdict,
                                                         const std::string& message,
                                                         const ros::Time& t0) {
  reach_trajopt::ReachabilityResult m;
  m.header.stamp = t0;
  m.header.frame_id = kWorldFrame;
  m.verdict = verdict;
  m.message = message;
  m.hausdorff_distance = -1.0;
  m.witness_distance = -1.0;
  return m;
}

reach_trajopt::TransitionTrajectory errorTrajectoryMsg(const std::string& reason,
                                                       const ros::Time& t0) {
  reach_trajopt::TransitionTrajectory m;
  m.header.stamp = t0;
  m.header.frame_id = kWorldFrame;
  m.status = "error";
  m.message = reason;
  return m;
}

const std::string& swingFrame(const ContactConfig& contact, Side stance) {
  return stance == Side::kLeft ? contact.right_sole_frame : contact.left_sole_frame;
}

ReachConfig reachConfigForDuration(const ReachConfig& base, double duration) {
  ReachConfig config = base;
  const double s = duration / config.horizon;
  config.horizon = duration;
  config.window_start *= s;
  config.window_end *= s;
  // Shorter than one step of the check (and of the OCP's output): name swing_duration, not the
  // scaled window (1e-9 s was answered about window_start multiples of dt).
  if (std::isfinite(duration) && duration < base.dt * (1.0 - 1e-9)) {
    std::ostringstream os;
    os << "swing_duration " << duration << " s is shorter than one time step of the check "
       << "(reach.dt = " << base.dt << " s)";
    throw RequestError(os.str());
  }
  return config;
}

reach_trajopt::ReachabilityResult infeasibleFootholdMsg(const std::string& ik_reason,
                                                        const std::string& swing_frame,
                                                        const Eigen::Vector3d& foothold,
                                                        const ros::Time& t0) {
  reach_trajopt::ReachabilityResult m =
      reachabilityVerdictMsg("unreachable", "kinematically infeasible foothold: " + ik_reason, t0);
  m.swing_frame = swing_frame;
  m.foothold = toPointMsg(foothold);
  return m;
}

reach_trajopt::ReachabilityResult toReachabilityResultMsg(const ReachResult& r,
                                                          const ContactTransition& request,
                                                          const std::string& swing_frame,
                                                          double delta, const ros::Time& t0,
                                                          bool samples, int max_points) {
  return toReachabilityResultMsg(r, request.target.position, swing_frame, delta, t0, samples,
                                 max_points);
}

reach_trajopt::ReachabilityResult toReachabilityResultMsg(const ReachResult& r,
                                                          const Eigen::Vector3d& foothold,
                                                          const std::string& swing_frame,
                                                          double delta, const ros::Time& t0,
                                                          bool samples, int max_points) {
  reach_trajopt::ReachabilityResult m =
      reachabilityVerdictMsg(r.reachable ? "reachable" : "unreachable", r.reason, t0);
  m.swing_frame = swing_frame;
  m.foothold = toPointMsg(foothold);
  m.delta = delta;
  double best = HUGE_VAL, gap = HUGE_VAL;
  for (const SliceComparison& c : r.window) {
    reach_trajopt::ReachabilitySlice s;
    s.header.frame_id = kWorldFrame;
    s.header.stamp = t0 + ros::Duration(c.time);
    s.time = c.time;
    s.hausdorff_distance = std::isfinite(c.distance.hausdorff) ? c.distance.hausdorff : -1.0;
    s.overlap = c.overlap;
    if (std::isfinite(c.distance.hausdorff)) best = std::min(best, c.distance.hausdorff);
    gap = std::min(gap, c.distance.resolution());
    const SampleSlice& f = r.forward.at(c.forward_slice);
    const SampleSlice& b = r.backward.at(c.backward_slice);
    s.forward_count = static_cast<uint32_t>(f.size());
    s.backward_count = static_cast<uint32_t>(b.size());
    s.forward_boundary = columnsToPoints(f.output, orderedBoundary(f));
    s.backward_boundary = columnsToPoints(b.output, orderedBoundary(b));
    if (samples) {
      s.forward_outputs = columnsToPoints(f.output, evenlyThinned(f.size(), max_points));
      s.backward_outputs = columnsToPoints(b.output, evenlyThinned(b.size(), max_points));
    }
    m.slices.push_back(s);
  }
  if (!r.window.empty()) {
    m.overlap_start = r.window.front().time;
    m.overlap_end = r.window.back().time;
  }
  m.hausdorff_distance = std::isfinite(best) ? best : -1.0;
  m.gap_bound = std::isfinite(gap) ? gap : -1.0;
  m.forward_samples = static_cast<uint32_t>(r.counts.forward_samples);
  m.backward_samples = static_cast<uint32_t>(r.counts.backward_samples);
  m.forward_rejected = static_cast<uint32_t>(r.counts.forward_rejected);
  m.backward_rejected = static_cast<uint32_t>(r.counts.backward_rejected);
  m.qps = static_cast<uint32_t>(r.counts.forward_qps + r.counts.backward_qps);
  m.budgets = static_cast<uint32_t>(r.budgets);
  m.gave_up = r.gave_up;
  if (r.best >= 0 && r.best < static_cast<int>(r.window.size())) {
    const SliceComparison& c = r.window[r.best];
    m.witness_time = c.time;
    m.witness_distance = c.distance.closest;
    const SampleSlice& f = r.forward.at(c.forward_slice);
    const SampleSlice& b = r.backward.at(c.backward_slice);
    if (c.distance.closest_a >= 0)
      m.witness_forward = columnsToPoints(f.output, {c.distance.closest_a})[0];
    if (c.distance.closest_b >= 0)
      m.witness_backward = columnsToPoints(b.output, {c.distance.closest_b})[0];
  }
  m.certificate = certificateName(r.reachable ? Certificate::kBridge : Certificate::kNone);
  m.witness_terminal_position_gap = m.witness_terminal_velocity_gap = -1.0;
  if (r.witness.valid) {
    m.witness_max_violation = r.witness.violation.max();
    m.witness_path_length = static_cast<uint32_t>(r.witness.time.size());
    if (std::isfinite(r.witness.terminal_position_gap)) {
      m.witness_terminal_position_gap = r.witness.terminal_position_gap;
      m.witness_terminal_velocity_gap = r.witness.terminal_velocity_gap;
    }
  }
  m.forward_time = r.timings.forward;
  m.backward_time = r.timings.backward;
  m.test_time = r.timings.boundary + r.timings.hausdorff + r.timings.witness;
  m.total_time = r.timings.total;
  return m;
}

void applyPlannerVerdict(const FootstepTransition& step, reach_trajopt::ReachabilityResult& m) {
  m.verdict = stepVerdictName(step.reachable ? StepVerdict::kReachable : StepVerdict::kUnreachable);
  m.certificate = certificateName(step.certificate);
  m.message = step.reason;
}

reach_trajopt::TransitionTrajectory toTransitionTrajectoryMsg(
    const TransitionResult& r, const RobotModel& model,
    const std::vector<std::string>& lambda_frames, const ros::Time& t0) {
  reach_trajopt::TransitionTrajectory m;
  m.header.stamp = t0;
  m.header.frame_id = kWorldFrame;
  m.status = ocpStatusName(r.status);
  m.message = r.reason.empty() ? r.nlopt_status : r.reason + " (" + r.nlopt_status + ")";
  for (const JointInfo& j : model.joints()) {
    m.joint_names.push_back(j.name);
    if (!j.is_virtual) m.actuated_joint_names.push_back(j.name);
  }
  m.contact_frames = lambda_frames;
  m.time.assign(r.time.data(), r.time.data() + r.time.size());
  m.dt = r.dt;
  appendRowMajor(r.q, m.q);
  appendRowMajor(r.qd, m.qd);
  appendRowMajor(r.qdd, m.qdd);
  appendRowMajor(r.u, m.u);
  appendRowMajor(r.lambda, m.lambda);
  const ConstraintViolations& v = r.violation;
  m.max_dynamics_violation = v.dynamics;
  m.max_contact_violation = std::max(v.stance_contact, v.new_contact);
  m.max_cone_violation = std::max(v.stance_cone, v.new_cone);
  m.max_torque_violation = v.torque;
  m.max_reach_violation = v.reachable_set;
  m.max_leg_clearance_violation = v.leg_clearance;
  m.relaxation = toVector3Msg(Eigen::Vector2d(r.eps), 0.0);
  m.final_foothold = toPointMsg(r.landing_position);
  m.cost = r.cost;
  m.iterations = r.iterations;
  m.solve_time = r.solve_time;
  return m;
}

TransitionResult fromTransitionTrajectoryMsg(const reach_trajopt::TransitionTrajectory& m,
                                             const RobotModel& model) {
  TransitionResult r;
  if (m.status == ocpStatusName(OcpStatus::kConverged))
    r.status = OcpStatus::kConverged;
  else if (m.status == ocpStatusName(OcpStatus::kRelaxed))
    r.status = OcpStatus::kRelaxed;
  else if (m.status == ocpStatusName(OcpStatus::kFailed))
    r.status = OcpStatus::kFailed;
  else
    throw ReachError("transition trajectory: unknown status '" + m.status + "'");
  r.relaxed = r.status == OcpStatus::kRelaxed;
  r.reason = m.message;
  r.eps = Eigen::Vector2d(m.relaxation.x, m.relaxation.y);
  r.landing_position = fromPointMsg(m.final_foothold);
  const Eigen::Index knots = static_cast<Eigen::Index>(m.time.size());
  r.dt = m.dt;
  r.time = Eigen::Map<const Eigen::VectorXd>(m.time.data(), knots);
  r.q = fromRowMajor(m.q, model.nq(), knots, "q");
  r.qd = fromRowMajor(m.qd, model.nq(), knots, "qd");
  r.qdd = fromRowMajor(m.qdd, model.nq(), knots, "qdd");
  r.u = fromRowMajor(m.u, model.nu(), knots, "u");
  const Eigen::Index lambda_rows =
      knots > 0 ? static_cast<Eigen::Index>(m.lambda.size()) / knots : 0;
  r.lambda = fromRowMajor(m.lambda, lambda_rows, knots, "lambda");
  r.violation.dynamics = m.max_dynamics_violation;  // the message keeps the largest of each pair
  r.violation.stance_contact = m.max_contact_violation;
  r.violation.stance_cone = m.max_cone_violation;
  r.violation.torque = m.max_torque_violation;
  r.violation.reachable_set = m.max_reach_violation;
  r.violation.leg_clearance = m.max_leg_clearance_violation;
  r.cost = m.cost;
  r.iterations = m.iterations;
  r.solve_time = m.solve_time;
  return r;
}

}  // namespace ros_bridge
}  // namespace reach_trajopt
