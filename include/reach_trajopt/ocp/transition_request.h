#pragma once
/// \file transition_request.h
/// Input of the transition OCP (eq. 22-23): one contact transition (contact/contact_transition.h)
/// from single support (SS-L or SS-R) at x_0 to double support at x_f, the reachable-set slices
/// that constrain the swing sole (reach/reachable_slice.h), and an optional seed path (the
/// reachability witness). Plain structs, so the OCP does not depend on the reachability engine.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "reach_trajopt/contact/contact_mode.h"
#include "reach_trajopt/contact/contact_transition.h"
#include "reach_trajopt/reach/reachable_slice.h"

namespace reach_trajopt {

/// A state path to warm-start from (e.g. the reachability witness x_0 -> x_f, one column per
/// 1 ms). Only q is used: its actuated part is least-squares fitted onto the spline basis.
struct SeedPath {
  Eigen::VectorXd time;  ///< N sample times since t_0 [s], within [0, horizon]
  Eigen::MatrixXd q;     ///< n_q x N configurations [m, rad]
  bool empty() const { return time.size() == 0; }
};

/// How to treat the final state.
enum class RelaxationMode {
  kStrict,   ///< x(t_f) = x_f and phi_2 = 0 (eq. 22-23 as written)
  kRelaxed,  ///< drop x(t_f) = x_f; phi_2 - eps = 0, eps = [eps_x, eps_y, 0, 0, 0, 0]
  kAuto,     ///< strict first; if it fails, relaxed
};

/// Upper bound of TransitionRequest::horizon [s] (docs/limits.md): a swing lasts well under a
/// second; the OCP's evaluations grow with the horizon, so longer ones could not keep their
/// time limit.
constexpr double kMaxTransitionHorizon = 5.0;

/// One transition OCP request (eq. 22-23): the contact transition (contact_transition.h:
/// current mode SS-<stance> with the held sole at stance_contact, new mode DS at t_f with the
/// moving sole on `target`, horizon = t_f - t_0, x_0 = (q0, qd0), x_f = (qf, qdf), e.g.
/// KinematicFeasibility's q_f with qd_f = 0; its `touchdown` is not read) and what the OCP adds.
struct TransitionRequest : ContactTransition {
  TransitionRequest() = default;
  /// The OCP of `transition` (the other fields at their defaults).
  explicit TransitionRequest(ContactTransition transition)
      : ContactTransition(std::move(transition)) {}

  /// The held sole's pose as measured at x_0 (flat up to rounding: a contact-consistent x_0's
  /// stance sole), held exactly; none: stance_contact.pose().
  std::optional<Eigen::Isometry3d> stance_pose;
  std::vector<ReachableSlice> slices;  ///< optional; empty: no reachable-set constraint
  SeedPath seed;                       ///< optional; empty: cubic Hermite x_0 -> x_f
  RelaxationMode relaxation = RelaxationMode::kAuto;
  /// Relaxed landing: the base's height above the mean sole height [m] (e.g. the walking
  /// robot's predicted pelvis height); NaN: TransitionOcpConfig::terminal_pelvis_height.
  double terminal_pelvis_height = std::numeric_limits<double>::quiet_NaN();

  /// The held sole a_k: stance_pose when given, else stance_contact.pose().
  Eigen::Isometry3d heldPose() const { return stance_pose ? *stance_pose : stance_contact.pose(); }
  /// The new contact a_{k+1}: target.pose().
  Eigen::Isometry3d targetPose() const { return target.pose(); }
};

}  // namespace reach_trajopt
