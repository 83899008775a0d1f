#pragma once
/// \file reach_context.h
/// Everything the propagation steps of one check share read-only: the model, the contact mode
/// m_k with its held footholds (eq. 5), the contact wrench cone (7-8), the limits, the output
/// map y = f_y(x) of (13) and the integrator. Built once per check, shared by all threads.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/contact/contact_constraint.h"
#include "reach_trajopt/contact/contact_mode.h"
#include "reach_trajopt/contact/contact_wrench_cone.h"
#include "reach_trajopt/model/leg_clearance.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/reach/reach_config.h"

namespace reach_trajopt {

/// @brief Read-only data of one reachability check (mode, contacts, limits, output map).
struct ReachContext {
  /// \param footholds  planned world poses of the left / right soles (index 0 / 1); the soles
  ///     in contact in `mode` are held there. `target` (may be empty) is the swing sole's next
  ///     foothold: its height is the ground for the swing clearance check.
  /// \throws ReachError when a sole of the mode has no foothold or frame, or the output frame
  ///     is unknown, or a floating-base model is given no contact (flight).
  ReachContext(std::shared_ptr<const RobotModel> model, const ContactConfig& contact,
               const ReachConfig& config, const SamplingBudget& budget, const ContactMode& mode,
               const std::optional<Eigen::Isometry3d> footholds[2],
               const std::optional<Eigen::Isometry3d>& target);

  std::shared_ptr<const RobotModel> model;
  ReachConfig config;
  SamplingBudget budget;  ///< the pass's sample budget (one of config.budgets)
  ContactMode mode;
  ContactWrenchCone cone;
  std::vector<ContactConstraint> contacts;  ///< held soles, left before right
  int n = 0, nu = 0, nc = 0;                ///< n_q, n_u, contacts
  int m() const { return 6 * nc; }          ///< contact wrench size
  bool floating = false;
  FrameId output_frame = -1;
  std::vector<int> output_axes;  ///< 0 = x, 1 = y, 2 = z
  int ny() const { return static_cast<int>(output_axes.size()); }
  FrameId swing_frame = -1;          ///< -1: no swing clearance check
  double ground_height = -HUGE_VAL;  ///< swing sole origin must stay above this [m]
  /// The legs' capsules (contact.leg_clearance, single support only) and the distance they
  /// keep [m] (-inf: no check; startAt() lowers it to their distance at x_0).
  LegClearance legs;
  double leg_margin = -HUGE_VAL;
  Eigen::VectorXd q_min, q_max, qd_max, u_max;
  std::vector<int> finite_position, finite_velocity;  ///< coordinates with finite limits

  /// Output y and its rate after model.update(ws, q, qd).
  void output(const Workspace& ws, Eigen::Ref<Eigen::VectorXd> y,
              Eigen::Ref<Eigen::VectorXd> y_rate) const;
  /// The state constraints h_state of eq. (4) at the model's last update: the swing sole above
  /// the ground and the legs leg_margin apart (each true without its check).
  bool stateConstraintsHold(const Workspace& ws) const;
  /// leg_margin for a check from configuration q_0: a swing never brings the legs closer than
  /// the margin, or than they are at x_0 (ContactConfig::legMarginFrom).
  void startAt(const Eigen::Ref<const Eigen::VectorXd>& q0);
  /// True when q, qd respect the limits (with config.limit_tolerance).
  bool withinLimits(const Eigen::Ref<const Eigen::VectorXd>& q,
                    const Eigen::Ref<const Eigen::VectorXd>& qd) const;
};

}  // namespace reach_trajopt
