#include "reach_trajopt/ros/markers.h"

#include <algorithm>
#include <cmath>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/ros/conversions.h"

namespace reach_trajopt {
namespace ros_bridge {

namespace {

constexpr Rgba kPlannedColor{0.1f, 0.8f, 0.2f, 0.6f};
constexpr Rgba kExecutedColor{0.1f, 0.3f, 0.9f, 0.8f};
constexpr Rgba kForwardColor{0.9f, 0.4f, 0.1f, 0.8f};
constexpr Rgba kBackwardColor{0.2f, 0.5f, 0.9f, 0.8f};
constexpr Rgba kWitnessColor{0.9f, 0.1f, 0.6f, 1.0f};
constexpr Rgba kReachableColor{0.1f, 0.8f, 0.2f, 1.0f};
constexpr Rgba kUnreachableColor{0.9f, 0.1f, 0.1f, 1.0f};
constexpr Rgba kRelaxedColor{1.0f, 0.6f, 0.0f, 1.0f};
constexpr Rgba kTransitionColor{0.5f, 0.1f, 0.9f, 1.0f};
constexpr double kSoleThickness = 0.005;    // [m], drawn height of a sole rectangle
constexpr double kSamplePointSize = 0.004;  // [m]
constexpr double kBoundaryWidth = 0.002;    // [m]

visualization_msgs::Marker baseMarker(const std::string& ns, int id, int type,
                                      const std::string& frame, const ros::Time& stamp,
                                      const Rgba& c) {
  visualization_msgs::Marker m;
  m.header.frame_id = frame.empty() ? std::string(kWorldFrame) : frame;
  m.header.stamp = stamp;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;  // points are given in the marker's frame
  m.color.r = c.r;
  m.color.g = c.g;
  m.color.b = c.b;
  m.color.a = c.a;
  return m;
}

void requireFinitePoints(const char* what, const std::vector<Eigen::Vector3d>& pts) {
  for (const Eigen::Vector3d& p : pts) requireFinite(what, p);
}

visualization_msgs::Marker soleCubes(const std::vector<Eigen::Vector3d>& pts, const char* ns,
                                     double half_length, double half_width, const ros::Time& stamp,
                                     const Rgba& c) {
  requireFinitePoints(ns, pts);
  visualization_msgs::Marker m =
      baseMarker(ns, 0, visualization_msgs::Marker::CUBE_LIST, kWorldFrame, stamp, c);
  m.scale.x = 2.0 * half_length;
  m.scale.y = 2.0 * half_width;
  m.scale.z = kSoleThickness;
  for (const Eigen::Vector3d& p : pts) m.points.push_back(toPointMsg(p));
  return m;
}

// A closed outline: the first point repeated at the end (a boundary is a polygon).
void addClosed(visualization_msgs::Marker& m, const std::vector<geometry_msgs::Point>& pts) {
  m.points = pts;
  if (pts.size() > 2) m.points.push_back(pts.front());
}

}  // namespace

visualization_msgs::MarkerArray footholdMarkers(const std::vector<Eigen::Vector3d>& planned,
                                                const std::vector<Eigen::Vector3d>& executed,
                                                double half_length, double half_width,
                                                const ros::Time& stamp) {
  if (!(half_length > 0.0) || !(half_width > 0.0) || !std::isfinite(half_length) ||
      !std::isfinite(half_width))
    throw ReachError("foothold markers: sole half sizes must be positive and finite");
  visualization_msgs::MarkerArray a;
  a.markers.push_back(
      soleCubes(planned, kNsFootholdsPlanned, half_length, half_width, stamp, kPlannedColor));
  a.markers.push_back(
      soleCubes(executed, kNsFootholdsExecuted, half_length, half_width, stamp, kExecutedColor));
  return a;
}

visualization_msgs::Marker pathMarker(const std::vector<Eigen::Vector3d>& path,
                                      const std::string& ns, int id, double width,
                                      const Rgba& color, const ros::Time& stamp) {
  if (!(width > 0.0) || !std::isfinite(width))
    throw ReachError("path marker '" + ns + "': width must be positive and finite");
  requireFinitePoints("path marker", path);
  visualization_msgs::Marker m =
      baseMarker(ns, id, visualization_msgs::Marker::LINE_STRIP, kWorldFrame, stamp, color);
  m.scale.x = width;
  m.points.reserve(path.size());
  for (const Eigen::Vector3d& p : path) m.points.push_back(toPointMsg(p));
  return m;
}

namespace {

/// One layer of a slice's markers: its output samples (points) or their boundary (a closed
/// line strip), forward or backward.
struct SliceLayer {
  const char* ns;
  std::vector<geometry_msgs::Point> reach_trajopt::ReachabilitySlice::*points;
  bool boundary;
  Rgba color;
};

/// The layers in the order their markers are published.
const SliceLayer kSliceLayers[] = {
    {kNsForwardSet, &reach_trajopt::ReachabilitySlice::forward_outputs, false, kForwardColor},
    {kNsBackwardSet, &reach_trajopt::ReachabilitySlice::backward_outputs, false, kBackwardColor},
    {kNsForwardBoundary, &reach_trajopt::ReachabilitySlice::forward_boundary, true, kForwardColor},
    {kNsBackwardBoundary, &reach_trajopt::ReachabilitySlice::backward_boundary, true,
     kBackwardColor},
};

}  // namespace

visualization_msgs::MarkerArray reachabilityMarkers(const reach_trajopt::ReachabilityResult& r,
                                                    int max_slices) {
  visualization_msgs::MarkerArray a;
  const std::string& frame = r.header.frame_id;
  const int n = static_cast<int>(r.slices.size());
  const int shown = std::max(0, std::min(n, max_slices));
  for (int k = 0; k < shown; ++k) {
    // Evenly spread over the slices, always including the first and the last one.
    const int i = shown == 1 ? 0 : static_cast<int>(std::lround(double(k) * (n - 1) / (shown - 1)));
    const reach_trajopt::ReachabilitySlice& s = r.slices[i];
    const ros::Time stamp = s.header.stamp.isZero() ? r.header.stamp : s.header.stamp;
    for (const SliceLayer& layer : kSliceLayers) {
      const std::vector<geometry_msgs::Point>& points = s.*layer.points;
      if (points.empty()) continue;
      auto m = baseMarker(layer.ns, i,
                          layer.boundary ? visualization_msgs::Marker::LINE_STRIP
                                         : visualization_msgs::Marker::POINTS,
                          frame, stamp, layer.color);
      if (layer.boundary) {
        m.scale.x = kBoundaryWidth;
        addClosed(m, points);
      } else {
        m.scale.x = m.scale.y = kSamplePointSize;
        m.points = points;
      }
      a.markers.push_back(m);
    }
  }
  const bool checked = r.verdict == "reachable" || r.verdict == "unreachable";
  // The witness pair exists only when the sets were compared (witness_distance >= 0); a
  // kinematically infeasible foothold has none, its points would sit at the origin.
  if (checked && r.witness_distance >= 0.0) {
    auto m = baseMarker(kNsWitness, 0, visualization_msgs::Marker::SPHERE_LIST, frame,
                        r.header.stamp, kWitnessColor);
    m.scale.x = m.scale.y = m.scale.z = 0.02;
    m.points = {r.witness_forward, r.witness_backward};
    a.markers.push_back(m);
  }
  if (checked) {
    auto m =
        baseMarker(kNsCheckedFoothold, 0, visualization_msgs::Marker::SPHERE, frame, r.header.stamp,
                   r.verdict == "reachable" ? kReachableColor : kUnreachableColor);
    m.scale.x = m.scale.y = m.scale.z = 0.04;
    m.pose.position = r.foothold;
    a.markers.push_back(m);
  }
  return a;
}

visualization_msgs::MarkerArray transitionMarkers(const TransitionResult& trajectory,
                                                  const RobotModel& model, FrameId swing_sole,
                                                  int id, const ros::Time& stamp) {
  visualization_msgs::MarkerArray a;
  const Eigen::Index n = trajectory.q.cols();
  if (n == 0) return a;
  requireSize("transition markers: trajectory q rows", trajectory.q.rows(), model.nq());
  Workspace ws(model);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.nq());
  std::vector<Eigen::Vector3d> path;
  path.reserve(static_cast<size_t>(n));
  for (Eigen::Index k = 0; k < n; ++k) {
    model.update(ws, trajectory.q.col(k), zero);
    path.push_back(model.framePose(ws, swing_sole).translation());
  }
  a.markers.push_back(pathMarker(path, kNsTransitionSwingPath, id, 0.004, kTransitionColor, stamp));
  const Rgba landing_color = trajectory.status == OcpStatus::kConverged ? kReachableColor
                             : trajectory.status == OcpStatus::kRelaxed ? kRelaxedColor
                                                                        : kUnreachableColor;
  auto m = baseMarker(kNsTransitionLanding, id, visualization_msgs::Marker::SPHERE, kWorldFrame,
                      stamp, landing_color);
  m.scale.x = m.scale.y = m.scale.z = 0.03;
  m.pose.position = toPointMsg(path.back());
  a.markers.push_back(m);
  return a;
}

visualization_msgs::Marker deleteAllMarker(const ros::Time& stamp) {
  visualization_msgs::Marker m;
  m.header.frame_id = kWorldFrame;
  m.header.stamp = stamp;
  m.action = visualization_msgs::Marker::DELETEALL;
  m.pose.orientation.w = 1.0;
  return m;
}

}  // namespace ros_bridge
}  // namespace reach_trajopt
