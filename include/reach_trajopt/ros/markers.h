#pragma once
/// \file markers.h
/// Pure builders of visualization_msgs markers (no node, no master) for the walking loop and the
/// reachability check, all in the world frame "world" (REP 103: x forward, y left, z up, m):
/// footholds planned and executed (sole rectangles), the CoM path, the swing sole path, and the
/// forward/backward reachable output sets with their boundaries (paper Fig. 3).
/// Every marker carries a namespace (ns) naming what it shows; ids are stable per namespace, so
/// publishing a new array replaces the previous markers of the same ns/id.

#include <ros/time.h>
#include <visualization_msgs/Marker.h>
#include <visualization_msgs/MarkerArray.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "reach_trajopt/ReachabilityResult.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/ocp/transition_result.h"

namespace reach_trajopt {
namespace ros_bridge {

/// Marker namespaces (what analyze_bag and the rostest look for).
inline constexpr char kNsFootholdsPlanned[] = "footholds_planned";
inline constexpr char kNsFootholdsExecuted[] = "footholds_executed";
inline constexpr char kNsComPath[] = "com_path";
inline constexpr char kNsSwingPath[] = "swing_path";
inline constexpr char kNsForwardSet[] = "forward_set";
inline constexpr char kNsBackwardSet[] = "backward_set";
inline constexpr char kNsForwardBoundary[] = "forward_boundary";
inline constexpr char kNsBackwardBoundary[] = "backward_boundary";
inline constexpr char kNsWitness[] = "witness";
inline constexpr char kNsCheckedFoothold[] = "checked_foothold";
inline constexpr char kNsTransitionSwingPath[] = "transition_swing_path";
inline constexpr char kNsTransitionLanding[] = "transition_landing";

/// Colour of a marker, components in [0, 1].
struct Rgba {
  float r, g, b, a;
};

/// @brief Sole rectangles (CUBE_LIST, one cube per foothold, 2X x 2Y x 5 mm, paper Sec. IV):
/// one marker for the planned footholds, one for the executed ones (either may be empty).
/// \param half_length, half_width  sole half sizes X, Y [m] (> 0)
/// \throws ReachError on non-positive sole sizes or non-finite points.
visualization_msgs::MarkerArray footholdMarkers(const std::vector<Eigen::Vector3d>& planned,
                                                const std::vector<Eigen::Vector3d>& executed,
                                                double half_length, double half_width,
                                                const ros::Time& stamp);

/// @brief A path as a LINE_STRIP of width `width` [m] in namespace `ns` (CoM path, swing path).
/// \throws ReachError on a non-positive width or non-finite points.
visualization_msgs::Marker pathMarker(const std::vector<Eigen::Vector3d>& path,
                                      const std::string& ns, int id, double width,
                                      const Rgba& color, const ros::Time& stamp);

/// @brief The reachable sets of one check (paper Fig. 3(a, b)): per slice, the forward and
/// backward output samples (POINTS, ids = slice index) and boundaries (closed LINE_STRIP), the
/// witness pair (SPHERE_LIST, when the sets were compared: witness_distance >= 0), and the
/// checked foothold (SPHERE, green reachable, red unreachable). At most `max_slices` slices are
/// drawn, evenly spread. An "error" result draws nothing. Frame and stamp are the result's
/// header (empty frame: "world").
visualization_msgs::MarkerArray reachabilityMarkers(const reach_trajopt::ReachabilityResult& r,
                                                    int max_slices = 20);

/// @brief The OCP's planned transition (eq. 22-23): the swing sole's path, by forward kinematics
/// of every output sample (LINE_STRIP, ns transition_swing_path), and its landing point
/// (SPHERE, ns transition_landing; green converged, orange relaxed, red failed), both id `id`.
/// An empty trajectory gives an empty array.
/// \throws ReachError on a trajectory whose q rows do not match the model.
visualization_msgs::MarkerArray transitionMarkers(const TransitionResult& trajectory,
                                                  const RobotModel& model, FrameId swing_sole,
                                                  int id, const ros::Time& stamp);

/// A marker deleting every marker of every namespace (action DELETEALL).
visualization_msgs::Marker deleteAllMarker(const ros::Time& stamp);

}  // namespace ros_bridge
}  // namespace reach_trajopt
