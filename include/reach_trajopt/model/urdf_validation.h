#pragma once
/// \file urdf_validation.h
/// URDF checks run before urdfdom and KDL see a robot, so that bad robots fail with a message
/// naming the link or joint instead of a crash (a link loop overflows kdl_parser's recursion),
/// a silent NaN (a zero joint axis) or a silently dropped value (an unparsable mass).
///
/// validateUrdfXml (on the text, before urdfdom builds its tree):
///   - every number urdfdom or we read (origin xyz/rpy, mass, inertia, axis, limit, dynamics,
///     calibration, safety_controller) parses completely and is finite;
///   - link and joint names are unique, every joint names existing parent and child links;
///   - the links form one tree: no link is the child of two joints, no loop, exactly one root;
///   - at most kMaxUrdfBytes of text and kMaxUrdfLinks links (bounds the recursion depth of
///     kdl_parser and of our loader).
/// validateUrdf (on urdfdom's model):
///   - the axis of a revolute, continuous or prismatic joint is finite and non-zero (a non-unit
///     axis is legal: it is normalized, as urdfdom and Pinocchio do);
///   - masses: finite, >= 0; a massless link (mass exactly 0) must have zero inertia (entries
///     within kInertiaAbsTolerance);
///   - inertias with mass > 0: symmetric positive semidefinite within kInertiaAbsTolerance +
///     kInertiaRelTolerance * largest principal moment; triangle inequality (every principal
///     second moment (sum - 2 lambda_k) / 2 >= 0) within kInertiaTriangleAbsTolerance or an
///     equivalent negative "thickness" sqrt(violation / (2 mass)) <= kInertiaTriangleLength.
///     Real URDFs carry placeholder inertias that break it mildly (romeo_small: 0.07 m,
///     anymal_c: 0.10 m in example-robot-data); pr2's diag(1e-3, 1e-3, 1e-2) at 50 g (0.28 m)
///     and gross violations (diag(1, 1, 3) kg m^2 at 1 kg: 0.7 m) are rejected.
/// Every check throws ReachError "<what> in link|joint '<name>' of <source>".

#include <urdf_model/model.h>

#include <cstddef>
#include <string>

namespace reach_trajopt {

constexpr int kMaxUrdfLinks = 10000;
constexpr std::size_t kMaxUrdfBytes = 64u << 20;       ///< larger URDF texts are rejected
constexpr double kInertiaAbsTolerance = 1e-6;          ///< [kg m^2]
constexpr double kInertiaRelTolerance = 1e-3;          ///< of the largest principal moment
constexpr double kInertiaTriangleAbsTolerance = 1e-5;  ///< [kg m^2] (dummy links of 1e-6 kg)
constexpr double kInertiaTriangleLength = 0.12;        ///< [m]

/// Checks the URDF text (numbers, names, tree structure) before it is parsed by urdfdom.
void validateUrdfXml(const std::string& xml, const std::string& source);

/// Checks the physical values of a parsed URDF (axes, masses, inertias).
void validateUrdf(const urdf::ModelInterface& urdf, const std::string& source);

}  // namespace reach_trajopt
