#pragma once
/// \file proposed_step.h
/// The proposed method's per-step pipeline (paper Sec. III, used in Sec. IV): from the measured
/// single-support state x_0 a short time before the nominal touchdown, the TVR foothold is
/// checked (kinematic feasibility III-B, then the bidirectional reachability test (13)-(21));
/// the transition OCP (22)-(23) then produces the trajectory to it, seeded with the witness
/// path, or, when the foothold is unreachable, the relaxed OCP lands on the closest reachable
/// foothold. The walking loop tracks the resulting trajectory with its feed-forward.

#include <memory>
#include <optional>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/ocp/ocp_config.h"
#include "reach_trajopt/ocp/transition_ocp.h"
#include "reach_trajopt/planner/kinematic_feasibility.h"
#include "reach_trajopt/planner/lipm.h"
#include "reach_trajopt/reach/footstep_reachability.h"
#include "reach_trajopt/reach/reach_config.h"

namespace reach_trajopt {

/// What one proposed step decided.
struct ProposedStep {
  bool kinematically_feasible = false;
  bool reachable = false;
  std::string verdict;        ///< "reachable", "unreachable", "kinematically_infeasible"
  std::string reason;         ///< the check's and the OCP's explanations
  double hausdorff_distance = -1.0;  ///< smallest d_H over the window [m], -1 if not computed
  double check_time_s = 0.0;  ///< kinematic + reachability check wall time
  double ocp_time_s = 0.0;    ///< OCP wall time
  TransitionResult trajectory;  ///< converged, relaxed or failed
  /// The full check (kinematics, reachable sets, witness) for recorders and the ROS layer.
  FootstepResult check;
  /// Where the swing sole will land [m]: the OCP's landing when usable, else the nearest
  /// kinematically feasible foothold to the target (the target when it is feasible).
  Eigen::Vector3d foothold = Eigen::Vector3d::Zero();
  /// True when the trajectory may be tracked (OCP converged or relaxed).
  bool usable() const { return trajectory.status != OcpStatus::kFailed; }
};

/// @brief Reachability check + transition OCP of one footstep (Sec. III).
class ProposedStepPlanner {
 public:
  /// \throws ReachError on invalid configs or unknown frames.
  ProposedStepPlanner(std::shared_ptr<const RobotModel> model, const ContactConfig& contact,
                      const KinematicFeasibilityConfig& kinematics, const ReachConfig& reach,
                      const TransitionOcpConfig& ocp);

  /// Plans the rest of the swing from the measured state (q, qd) in single support on
  /// `stance` (sole held at `stance_pose`) to the swing sole on `target` (flat).
  /// The state is first made consistent with the contact: qd projected onto the null space of
  /// the stance sole Jacobian, q clamped into the joint limits.
  /// `touchdown_com` is the CoM's horizontal state predicted at touchdown (the LIPM about the
  /// stance sole): the final state x_f then has the pelvis where the CoM will have carried it
  /// (the kinematic check holds the pelvis there, at its current height) and moves with the
  /// CoM at its predicted velocity with both soles still (doubleSupportVelocity). Without it,
  /// x_f is the Sec. III-B posture (pelvis x, y free, nominal height) at rest.
  /// \throws ReachError on bad input (sizes, NaN, a target outside the workspace).
  ProposedStep plan(Side stance, const Eigen::Isometry3d& stance_pose,
                    const Eigen::Vector3d& target, const Eigen::VectorXd& q,
                    const Eigen::VectorXd& qd,
                    const std::optional<LipmState>& touchdown_com = std::nullopt) const;

  /// Time from the check to touchdown [s] (the reachability horizon t_f - t_0).
  double horizon() const { return reach_config_.horizon; }

 private:
  std::shared_ptr<const RobotModel> model_;
  ContactConfig contact_;
  ReachConfig reach_config_;
  std::shared_ptr<const KinematicFeasibility> kinematics_;
  FootstepReachability footsteps_;
  TransitionOcp ocp_;
};

}  // namespace reach_trajopt
