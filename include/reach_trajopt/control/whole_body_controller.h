#pragma once
/// \file whole_body_controller.h
/// The whole-body controller of the paper's Sec. IV: an inverse-dynamics QP on the bundled
/// solver, run at the simulator's rate (1 kHz).
///
/// Variables x = [qdd (n_q); lambda_i (6 per sole in contact)], torques eliminated through
/// eq. (1): u = M_a qdd + b_a - J_a^T lambda (the actuated rows). The QP is
///   min  sum_k w_k |J_k qdd + Jdot_k qd - a_k|^2 + w_qdd |qdd|^2 + w_lambda |lambda|^2
///   s.t. M_b qdd + b_b = J_b^T lambda                 (floating-base rows of eq. 1)
///        J_i qdd + Jdot_i qd = 0                      (contacts, eq. 5)
///        C R lambda_i >= 0                            (wrench cones, eq. 7-8)
///        -u_max <= M_a qdd + b_a - J_a^T lambda <= u_max   (torque limits)
///        g_d qdd + drift_d >= kp_l (m - d) - kd_l g_d qd  (single support: the legs apart)
/// with tasks k: CoM position, pelvis orientation, swing sole pose (6-D) and joint posture,
/// each a PD law a_k = a_ref + Kd (v_ref - v) + Kp (x_ref - x), plus an optional joint
/// acceleration feed-forward (the OCP's trajectory in the proposed mode). The barrier rows
/// hold d, the distance of each pair of the legs' collision capsules (model/leg_clearance.h;
/// gradient g_d) closer than `leg_clearance_activation`: a swing leg carried toward the stance
/// leg off its plan (a push) stays `leg_clearance_margin` from it. When the rows cannot all hold,
/// the torque limits are dropped first, then the barrier.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/contact/contact_mode.h"
#include "reach_trajopt/contact/contact_wrench_cone.h"
#include "reach_trajopt/model/leg_clearance.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/qp/dual_active_set_qp.h"

namespace reach_trajopt {

class YamlSection;
template <typename Config>
class ConfigFields;

/// Task weights and PD gains of the whole-body controller (gains in 1/s^2 and 1/s).
/// Larger weights make a task win over the others; larger gains track faster but amplify
/// the simulator's contact noise.
struct WbcConfig {
  double w_com = 100.0, kp_com = 120.0, kd_com = 22.0;  ///< CoM height (z)
  /// Horizontal CoM weight. Small: the horizontal CoM moves as the pendulum the TVR planner
  /// assumes and the footsteps stabilize it, rather than the ankles fighting the swing leg.
  double w_com_xy = 2.0;
  double w_pelvis = 50.0, kp_pelvis = 300.0, kd_pelvis = 35.0;    ///< pelvis orientation
  double w_swing = 200.0, kp_swing = 900.0, kd_swing = 60.0;      ///< swing sole pose
  double w_posture = 0.03, kp_posture = 60.0, kd_posture = 12.0;  ///< actuated joints
  double w_qdd = 1e-4;                                            ///< regularization of qdd
  double w_lambda = 1e-6;  ///< regularization of contact wrenches (N^2 -> cost)
  /// The legs' barrier in single support: d'' >= kp (margin - d) - kd d' on the distance d
  /// [m] of each pair of the legs' capsules closer than `leg_clearance_activation` [m] (gains
  /// 1/s^2, 1/s; off: no barrier).
  bool leg_clearance = true;
  double leg_clearance_margin = 0.005, leg_clearance_activation = 0.15;  ///< [m]
  double kp_leg_clearance = 400.0, kd_leg_clearance = 40.0;
  /// Double support: each sole's wrench is a normal force of this much at the sole centre plus
  /// a wrench of its cone, C (lambda - lambda_min) >= 0 [N]: both soles stay loaded (0: the cone
  /// alone, a sole may be unloaded to nothing and lift off the ground under contact noise).
  double min_normal_force = 0.0;
  /// Frame whose orientation the pelvis task holds; "" is the URDF root link. Not a YAML key:
  /// the robot's pelvis is kinematic_feasibility.pelvis_frame, which WalkingExperiment copies.
  std::string pelvis_frame;
  /// \throws ConfigError naming a negative or non-finite field.
  void validate() const;
  /// The YAML keys of section `wbc:` (the member names), their units and meaning.
  static const ConfigFields<WbcConfig>& fields();
  /// Reads fields() from a YAML section, then validates.
  static WbcConfig fromYaml(const YamlSection& section);
};

/// What the controller tracks at one tick. Positions in the world [m], orientations as
/// world-from-frame rotations.
struct WbcReference {
  Eigen::Vector3d com_position = Eigen::Vector3d::Zero();
  Eigen::Vector3d com_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d com_acceleration = Eigen::Vector3d::Zero();
  Eigen::Matrix3d pelvis_rotation = Eigen::Matrix3d::Identity();
  /// Swing sole target (used in single support for the sole not in contact).
  Eigen::Vector3d swing_position = Eigen::Vector3d::Zero();
  Eigen::Vector3d swing_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d swing_acceleration = Eigen::Vector3d::Zero();
  Eigen::Matrix3d swing_rotation = Eigen::Matrix3d::Identity();
  /// Posture target of all n_q coordinates (only the actuated ones are used); empty: the
  /// model's configuration at construction.
  Eigen::VectorXd posture;
  /// Optional joint trajectory (n_q each, empty when unused): tracked by the posture task in
  /// place of `posture`, with qdd_ff as its acceleration feed-forward.
  Eigen::VectorXd q_ff, qd_ff, qdd_ff;
  /// Weight of the horizontal CoM task for this tick; < 0: WbcConfig::w_com_xy.
  double w_com_xy = -1.0;
};

/// Result of one tick.
struct WbcOutput {
  qp::QpStatus status = qp::QpStatus::kInvalidInput;
  Eigen::VectorXd u;                        ///< joint torques, size n_u [Nm]
  Eigen::VectorXd qdd;                      ///< planned accelerations, size n_q
  Vector6d lambda_left = Vector6d::Zero();  ///< [f; tau] world orientation at the sole [N, Nm]
  Vector6d lambda_right = Vector6d::Zero();
  std::string message;
};

/// @brief Inverse-dynamics QP whole-body controller (Sec. IV). Not thread-safe: one per sim.
class WholeBodyController {
 public:
  /// \param posture  nominal configuration (n_q) for the posture task.
  /// \throws ReachError on invalid configs, unknown sole frames or a wrong-size posture.
  WholeBodyController(std::shared_ptr<const RobotModel> model, const ContactConfig& contact,
                      const WbcConfig& config, const Eigen::VectorXd& posture);

  /// One control tick at the measured state (q, qd) in contact mode `mode`.
  /// On a QP failure the status says so and u holds the last successful torques.
  /// \throws ReachError on wrong sizes or non-finite input.
  const WbcOutput& compute(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                           const ContactMode& mode, const WbcReference& ref);

  const RobotModel& model() const { return *model_; }
  const WbcConfig& config() const { return config_; }
  /// Sole frame ids (left, right).
  FrameId soleFrame(Side s) const { return s == Side::kLeft ? left_sole_ : right_sole_; }

 private:
  /// The weighted tasks (CoM, pelvis, swing sole, posture, regularization) into G_, g_.
  void addTasks(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const ContactMode& mode,
                const WbcReference& ref);
  /// Floating-base dynamics, contacts (5), cones (8), the legs' barrier and torque limits
  /// into A_eq_, A_in_.
  void addConstraints(const ContactMode& mode, const Eigen::VectorXd& qd);
  /// The legs' barrier rows (single support) into A_in_ from row `row`, one per capsule pair
  /// closer than leg_clearance_activation; returns their count (0 when the barrier is off or
  /// the robot's legs have no collision primitive).
  int addLegBarrier(int row, int nx, const Eigen::VectorXd& qd);
  /// Solves the QP (without the torque limits, then without the legs' barrier, when they are
  /// infeasible) into out_.
  const WbcOutput& solveQp(const ContactMode& mode);
  void fillOutput(const qp::QpResult& r, const ContactMode& mode, int n, int nu);
  void addTask(const Eigen::Ref<const Eigen::MatrixXd>& J,
               const Eigen::Ref<const Eigen::VectorXd>& drift,
               const Eigen::Ref<const Eigen::VectorXd>& a_des, double weight);

  std::shared_ptr<const RobotModel> model_;
  ContactConfig contact_;
  WbcConfig config_;
  ContactWrenchCone cone_;
  FrameId left_sole_, right_sole_, pelvis_;
  Eigen::VectorXd posture_;
  LegClearance legs_;     ///< empty when wbc.leg_clearance is off
  int barrier_rows_ = 0;  ///< this tick's barrier rows
  std::vector<LegClearance::Closest> leg_pairs_;
  Eigen::MatrixXd leg_gradients_;  ///< the barrier rows' gradients (pairCount() x n_q)
  Eigen::VectorXd leg_drifts_;     ///< and their acceleration drifts
  Workspace ws_;
  qp::DualActiveSetQp qp_single_, qp_double_;
  std::vector<int> warm_single_, warm_double_;
  // Scratch, sized once.
  Eigen::MatrixXd M_, G_, A_eq_, A_in_;
  Eigen::VectorXd b_, g_, b_eq_, b_in_;
  Eigen::VectorXd u_max_;        ///< effort limits (n_u) [Nm]
  Eigen::VectorXd posture_acc_;  ///< posture task acceleration (n_u)
  Matrix6Xd J_sole_[2], J_pelvis_;
  Eigen::Matrix3Xd J_com_;
  WbcOutput out_;
};

}  // namespace reach_trajopt
