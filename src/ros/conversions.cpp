#include "reach_trajopt/ros/conversions.h"

#include <cmath>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {
namespace ros_bridge {

namespace {
/// A geometry_msgs message with fields x, y, z (Point, Vector3) from `v`.
template <class Msg>
Msg xyzMsg(const Eigen::Vector3d& v) {
  Msg m;
  m.x = v.x();
  m.y = v.y();
  m.z = v.z();
  return m;
}
}  // namespace

geometry_msgs::Point toPointMsg(const Eigen::Vector3d& p) {
  return xyzMsg<geometry_msgs::Point>(p);
}

geometry_msgs::Point toPointMsg(const Eigen::Vector2d& xy, double z) {
  return toPointMsg(Eigen::Vector3d(xy.x(), xy.y(), z));
}

geometry_msgs::Vector3 toVector3Msg(const Eigen::Vector3d& v) {
  return xyzMsg<geometry_msgs::Vector3>(v);
}

geometry_msgs::Vector3 toVector3Msg(const Eigen::Vector2d& xy, double z) {
  return toVector3Msg(Eigen::Vector3d(xy.x(), xy.y(), z));
}

namespace {
geometry_msgs::Quaternion toQuaternionMsg(const Eigen::Matrix3d& R) {
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // one representative: w >= 0
  geometry_msgs::Quaternion m;
  m.x = q.x();
  m.y = q.y();
  m.z = q.z();
  m.w = q.w();
  return m;
}

Eigen::Matrix3d fromQuaternionMsg(const geometry_msgs::Quaternion& m, const char* what) {
  const Eigen::Vector4d c(m.x, m.y, m.z, m.w);
  requireFinite(what, c);
  if (std::abs(c.norm() - 1.0) > 1e-3)
    throw RequestError(std::string(what) + ": quaternion norm " + std::to_string(c.norm()) +
                       " is not 1");
  return Eigen::Quaterniond(m.w, m.x, m.y, m.z).normalized().toRotationMatrix();
}
}  // namespace

geometry_msgs::Pose toPoseMsg(const Eigen::Isometry3d& T) {
  geometry_msgs::Pose m;
  m.position = toPointMsg(Eigen::Vector3d(T.translation()));
  m.orientation = toQuaternionMsg(T.linear());
  return m;
}

geometry_msgs::Transform toTransformMsg(const Eigen::Isometry3d& T) {
  geometry_msgs::Transform m;
  m.translation = toVector3Msg(Eigen::Vector3d(T.translation()));
  m.rotation = toQuaternionMsg(T.linear());
  return m;
}

geometry_msgs::Wrench toWrenchMsg(const Vector6d& w) {
  geometry_msgs::Wrench m;
  m.force = toVector3Msg(Eigen::Vector3d(w.head<3>()));
  m.torque = toVector3Msg(Eigen::Vector3d(w.tail<3>()));
  return m;
}

Eigen::Vector3d fromPointMsg(const geometry_msgs::Point& p) { return {p.x, p.y, p.z}; }
Eigen::Vector3d fromVector3Msg(const geometry_msgs::Vector3& v) { return {v.x, v.y, v.z}; }

Eigen::Isometry3d fromPoseMsg(const geometry_msgs::Pose& pose) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = fromQuaternionMsg(pose.orientation, "pose orientation");
  T.translation() = fromPointMsg(pose.position);
  return T;
}

Eigen::Isometry3d fromTransformMsg(const geometry_msgs::Transform& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = fromQuaternionMsg(t.rotation, "transform rotation");
  T.translation() = fromVector3Msg(t.translation);
  return T;
}

Vector6d fromWrenchMsg(const geometry_msgs::Wrench& w) {
  Vector6d v;
  v << w.force.x, w.force.y, w.force.z, w.torque.x, w.torque.y, w.torque.z;
  return v;
}

// ---- TF of every link -------------------------------------------------------------------------

LinkTransforms::LinkTransforms(const RobotModel& model, const std::string& world_frame)
    : model_(model) {
  for (const std::string& link : model.linkNames()) {
    if (link == world_frame) continue;  // a fixed-base URDF whose root is "world"
    const std::string& parent = model.parentLink(link);
    geometry_msgs::TransformStamped msg;
    msg.child_frame_id = link;
    child_.push_back(model.frameId(link));
    if (parent.empty() || parent == world_frame) {
      msg.header.frame_id = world_frame;
      parent_.push_back(-1);
    } else {
      msg.header.frame_id = parent;
      parent_.push_back(model.frameId(parent));
    }
    msgs_.push_back(msg);
  }
}

const std::vector<geometry_msgs::TransformStamped>& LinkTransforms::compute(
    const Workspace& ws, const ros::Time& stamp) {
  for (size_t i = 0; i < msgs_.size(); ++i) {
    const Eigen::Isometry3d child = model_.framePose(ws, child_[i]);
    const Eigen::Isometry3d rel =
        parent_[i] < 0 ? child : model_.framePose(ws, parent_[i]).inverse(Eigen::Isometry) * child;
    msgs_[i].header.stamp = stamp;
    msgs_[i].transform = toTransformMsg(rel);
  }
  return msgs_;
}

// ---- Joint states -----------------------------------------------------------------------------

void fillJointState(const RobotModel& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                    const Eigen::VectorXd& u, const ros::Time& stamp,
                    sensor_msgs::JointState& msg) {
  requireSize("joint state q", q.size(), model.nq());
  requireSize("joint state qd", qd.size(), model.nq());
  if (u.size() != 0) requireSize("joint state u", u.size(), model.nu());
  const int first = model.nq() - model.nu();  // the six virtual coordinates come first
  const size_t n = static_cast<size_t>(model.nu());
  if (msg.name.size() != n) {
    msg.name.clear();
    for (int i = first; i < model.nq(); ++i) msg.name.push_back(model.joints()[i].name);
  }
  msg.header.stamp = stamp;
  msg.position.resize(n);
  msg.velocity.resize(n);
  msg.effort.resize(u.size() != 0 ? n : 0);
  for (size_t k = 0; k < n; ++k) {
    msg.position[k] = q[first + static_cast<int>(k)];
    msg.velocity[k] = qd[first + static_cast<int>(k)];
    if (u.size() != 0) msg.effort[k] = u[static_cast<int>(k)];
  }
}

geometry_msgs::WrenchStamped toSoleWrenchMsg(const SoleContact& sole, const ros::Time& stamp) {
  const Eigen::Matrix3d Rt = sole.sole_pose.linear().transpose();
  Vector6d w;
  w << Rt * sole.wrench.head<3>(), Rt * sole.wrench.tail<3>();
  geometry_msgs::WrenchStamped m;
  m.header.stamp = stamp;
  m.header.frame_id = sole.frame;
  m.wrench = toWrenchMsg(w);
  return m;
}

// ---- Walking loop -----------------------------------------------------------------------------

reach_trajopt::CenterOfMassState toCenterOfMassStateMsg(const WalkTick& tick,
                                                        const ros::Time& stamp) {
  reach_trajopt::CenterOfMassState m;
  m.header.stamp = stamp;
  m.header.frame_id = kWorldFrame;
  m.contact_mode = tick.mode.name();
  m.position = toPointMsg(tick.com);
  m.velocity = toVector3Msg(tick.com_velocity);
  m.reference = toPointMsg(tick.com_reference);
  return m;
}

reach_trajopt::ContactState toContactStateMsg(const WalkTick& tick, const ros::Time& stamp) {
  reach_trajopt::ContactState m;
  m.header.stamp = stamp;
  m.header.frame_id = kWorldFrame;
  m.contact_mode = tick.mode.name();
  if (!tick.soles) return m;
  for (size_t i = 0; i < tick.soles->size(); ++i) {
    const SoleContact& s = (*tick.soles)[i];
    m.frames.push_back(s.frame);
    m.in_contact.push_back(s.in_contact);
    m.sole_poses.push_back(toPoseMsg(s.sole_pose));
    m.measured.push_back(toWrenchMsg(s.wrench));
    Vector6d commanded = Vector6d::Zero();
    if (tick.wbc) commanded = i == 0 ? tick.wbc->lambda_left : tick.wbc->lambda_right;
    m.commanded.push_back(toWrenchMsg(commanded));
  }
  return m;
}

reach_trajopt::StepReport toStepReportMsg(const StepRecord& r, const WalkingPolicy& policy,
                                          bool fell, double ground_z) {
  reach_trajopt::StepReport m;
  m.header.frame_id = kWorldFrame;
  const double stamp = r.touched_down ? r.touchdown_time : r.plan_time;
  m.header.stamp = ros::Time(std::max(0.0, stamp));
  m.index = static_cast<uint32_t>(std::max(0, r.index));
  m.mode = policy.name;
  m.policy = policy.definition();
  m.failed_check_action = r.failedCheckActionName();
  m.foothold_source = r.footholdSourceName();
  m.swing_side = sideName(r.swing);
  m.plan_time = r.plan_time;
  m.touchdown_time = r.touchdown_time;
  m.touched_down = r.touched_down;
  m.fell = fell;
  m.stance = toPointMsg(r.stance, ground_z);
  m.planned_tvr = toPointMsg(r.planned_tvr, ground_z);
  m.planned = toPointMsg(r.planned, ground_z);
  m.executed = toPointMsg(r.executed);
  m.touchdown_error = r.touchdown_error;
  m.offset_clipped = r.offset_clipped;
  m.com_at_plan = toPointMsg(r.com_at_plan.p);
  m.com_velocity_at_plan = toVector3Msg(r.com_at_plan.pd);
  m.com_predicted = toPointMsg(r.com_predicted.p);
  m.com_velocity_predicted = toVector3Msg(r.com_predicted.pd);
  m.verdict = r.verdictName();
  m.hausdorff_distance = r.hausdorff_distance;
  m.certificate = r.certificateName();
  m.witness_violation = r.witness_violation;
  m.terminal_position_gap = r.terminal_position_gap;
  m.terminal_velocity_gap = r.terminal_velocity_gap;
  m.check_time = r.check_time_s;
  m.ocp_time = r.ocp_time_s;
  m.ocp_status = r.ocpStatusName();
  return m;
}

reach_trajopt::ContactPlan toContactPlanMsg(const TvrInput& input, const TvrStep& step,
                                            double single_support, double double_support,
                                            double ground_z, const ros::Time& stamp) {
  if (!(single_support > 0.0) || !(double_support > 0.0) || !std::isfinite(single_support) ||
      !std::isfinite(double_support))
    throw RequestError("contact plan: phase durations must be positive and finite");
  reach_trajopt::ContactPlan m;
  m.header.stamp = stamp;
  m.header.frame_id = kWorldFrame;
  m.modes = {ContactMode::singleSupport(opposite(input.swing)).name(),
             ContactMode::doubleSupport().name()};
  m.durations = {single_support, double_support};
  m.foothold_sides = {sideName(input.swing)};
  m.footholds = {toPointMsg(step.alpha, ground_z)};
  m.stance = toPointMsg(input.stance, ground_z);
  m.foothold_tvr = toPointMsg(step.alpha_tvr, ground_z);
  m.offset_clipped = step.offset_clipped;
  m.com_position = toPointMsg(input.com.p);
  m.com_velocity = toVector3Msg(step.com_velocity_used);
  return m;
}

void requireWorldFrame(const std::string& frame_id, const std::string& field) {
  if (!frame_id.empty() && frame_id != kWorldFrame)
    throw RequestError(field + "unknown frame '" + frame_id + "': positions must be in 'world'");
}

Eigen::VectorXd responseVector(const std::string& service, const std::vector<double>& v,
                               size_t size, const char* field) {
  requireResponseEntries(service, v, size, field);
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

}  // namespace ros_bridge
}  // namespace reach_trajopt
