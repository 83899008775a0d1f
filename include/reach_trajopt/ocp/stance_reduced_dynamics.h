#pragma once
/// \file stance_reduced_dynamics.h
/// Eq. (1) with the stance contact of eq. (5) held exactly, in the actuated coordinates q_a.
///
/// In single support the stance sole is fixed at its planned pose P_s. Given q_a, the floating
/// base is the unique pose that puts the stance sole there: T_wb = P_s T_bs(q_a)^-1 (T_bs by
/// forward kinematics with the base at the origin), read as x, y, z, yaw, pitch, roll
/// (R = Rz Ry Rx). Differentiating J_s qd = 0 gives qd = T qd_a and qdd = T qdd_a + k with
///   T = [G; I],  G = -J_sb^-1 J_sa,  k = [-J_sb^-1 Jdot_s qd; 0],
/// (J_sb: the 6 x 6 base block of the stance sole Jacobian, invertible away from pitch = +-90
/// degrees). So phi_s = phidot_s = phiddot_s = 0 hold by construction at every t. With
/// tau = M qdd + b - J_2^T lambda_2 (lambda_2: the new contact's wrench, non-zero only at t_f),
/// the base rows of eq. (1) give the stance wrench and the actuated rows the torques uniquely:
///   lambda_s = J_sb^-T tau_b,   u = T^T tau = tau_a + G^T tau_b.
/// Eq. (1) therefore holds exactly for any joint trajectory: no wrench variables are needed in
/// single support, and the OCP only keeps the inequality constraints (cones, torque bounds).
///
/// The "signals" evaluated at one time are, in this order:
///   u (n_u) [N m], lambda_s (6) [N, N m], swing sole position (3) [m], phi_2 (6) [m, rad],
///   phidot_2 (6), phiddot_2 (6), q (n_q), qd (n_q)
/// with phi_2 the new contact's eq. (5) error to the swing target. Their Jacobian with respect
/// to the inputs [q_a, qd_a, qdd_a, lambda_2]:
///  - qdd_a and lambda_2: analytic (the signals are affine in both);
///  - the dynamics (u, lambda_s) in q_a and qd_a: by the chain rule through the full state,
///      d tau = dtau/dq dq + dtau/dqd dqd + M dqdd,
///    with dtau/dq, dtau/dqd the analytic RNEA derivatives (model/rnea_derivatives.h), and
///    u = T^T (tau - J_2^T lambda_2), lambda_s = J_sb^-T (tau - J_2^T lambda_2)_b differentiated
///    as products;
///  - the kinematic chain (the full state q, qd, qdd as functions of q_a, qd_a; G, J_sb^-1, J_2;
///    the swing sole's position, phi_2, phidot_2, phiddot_2), by one of two schemes:
///    * analytic (the default): dq/dq_a = T and dqd/dqd_a = T exactly (J_s dq = 0 defines
///      both); the rest from differentiating the stance contact, J_s qd = 0 and
///      J_s qdd + Jdot_s qd = 0: for q_a (dq = T dq_a)
///        dqd_b = Qd dq_a,    Qd  = -J_sb^-1 d(J_s qd)/dq T,
///        dqdd_b = Qdd dq_a,  Qdd = -J_sb^-1 [(d(J_s qdd)/dq + d(Jdot_s qd)/dq) T
///                                             + d(Jdot_s qd)/dqd_b Qd],
///      for qd_a (dqd = T dqd_a at fixed q) Qdd = -J_sb^-1 d(Jdot_s qd)/dqd T; and from
///      r = tau - J_2^T lambda_2 = J_s^T lambda_s + S^T u
///        du = T^T dr',  dlambda_s = J_sb^-T dr'_b,
///        dr' = dtau - d(J_2^T lambda_2)/dq dq - d(J_s^T lambda_s)/dq dq  (the wrenches held);
///      the swing terms likewise (phidot_2 = B J_2 qd, phiddot_2 = B (J_2 qdd + Jdot_2 qd),
///      B = blkdiag(I, Jl^-1(e)) with d Jl^-1(e) in closed form). The soles' d(J x)/dq,
///      d(J qd)/dq, d(Jdot qd)/dq, d(Jdot qd)/dqd, d(J^T lambda)/dq come from
///      model/kinematic_derivatives.h as matrices, so all 2 n_u columns are matrix products:
///      no finite difference and no per-column kinematics (measured on the biped: about 0.3x
///      the forward-difference Jacobian's time, and 0.2x on the 38-dof TALOS).
///    * finite_differences: differences of kinematics only, no inverse dynamics: in qd_a exact
///      central differences (quadratic in qd at fixed q; velocity pass only); in q_a forward or
///      central differences (step from TransitionOcpConfig). A joint off the stance sole's
///      support path (the swing leg) moves neither the reconstructed base nor G, J_sb, the
///      stance drift: its column needs the swing terms only, and dq = e_i exactly.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "reach_trajopt/contact/contact_constraint.h"
#include "reach_trajopt/contact/contact_mode.h"
#include "reach_trajopt/model/kinematic_derivatives.h"
#include "reach_trajopt/model/rnea_derivatives.h"
#include "reach_trajopt/model/robot_model.h"

namespace reach_trajopt {

/// Reduced single-support dynamics of eq. (1) + (5) (see file comment). Immutable; each thread
/// passes its own Scratch.
class StanceReducedDynamics {
 public:
  /// \param stance_frame, swing_frame  sole frames (RobotModel::frameId)
  /// \param stance_pose   planned stance sole pose (world)
  /// \param swing_target  planned new contact pose (world)
  /// \param yaw_reference base yaw [rad] near which the reconstructed yaw is unwrapped
  /// Throws ReachError for a fixed-base model or invalid poses.
  StanceReducedDynamics(std::shared_ptr<const RobotModel> model, FrameId stance_frame,
                        const Eigen::Isometry3d& stance_pose, FrameId swing_frame,
                        const Eigen::Isometry3d& swing_target, double yaw_reference);

  const RobotModel& model() const { return *model_; }
  int nq() const { return nq_; }
  int nu() const { return nu_; }

  // Signal layout.
  int uOffset() const { return 0; }
  int lambdaOffset() const { return nu_; }
  int swingPositionOffset() const { return nu_ + 6; }
  int phi2Offset() const { return nu_ + 9; }
  int phidot2Offset() const { return nu_ + 15; }
  int phiddot2Offset() const { return nu_ + 21; }
  int qOffset() const { return nu_ + 27; }
  int qdOffset() const { return nu_ + 27 + nq_; }
  int signalCount() const { return nu_ + 27 + 2 * nq_; }
  /// Inputs: [q_a (n_u), qd_a (n_u), qdd_a (n_u), lambda_2 (6)].
  int inputCount() const { return 3 * nu_ + 6; }

  /// Per-thread buffers (a Workspace and the intermediate matrices), sized once.
  struct Scratch {
    explicit Scratch(const StanceReducedDynamics& d);
    Workspace ws;
    Eigen::VectorXd qz, vz, q, qd, qdd, tau, tau_ext, qd_nominal, signals_pert, input_pert;
    Matrix6Xd Js, J2;
    ContactConstraintTerms swing;
    Eigen::Matrix<double, 6, 6> Jb_inv;
    Eigen::MatrixXd G, MT, M;
    Vector6d drift_s, lambda_s;
    Eigen::Vector3d swing_position;
    // Jacobian scratch: RNEA derivatives and the kinematic state of the unperturbed input and of
    // one perturbation.
    RneaDerivatives::Data rd;
    Eigen::VectorXd tau_rd, r0;
    Eigen::MatrixXd dtau_dq, dtau_dqd;
    struct Kinematic {
      explicit Kinematic(int nq, int nu);
      Eigen::VectorXd q, qd, qdd;
      Eigen::MatrixXd G;
      Eigen::Matrix<double, 6, 6> Jb_inv;
      Matrix6Xd J2;
      Eigen::Vector3d swing_position;
      Vector6d phi2, phidot2, phiddot2;
    };
    Kinematic k0, kp, km;
    Eigen::VectorXd dq, dqd, dqdd, dtau, dr;
    // Analytic chain: the soles' kinematic derivatives, a column's direction and the changes of
    // J_s, J_2 along it.
    KinematicDerivatives::Data kd;
    KinematicDerivatives::FrameMatrices fs, f2;  // stance and swing sole
    Matrix6Xd Qd, Qdd, D6, dvel2, dacc2;         // 6 x n_u: d(base qd), d(base qdd), ...
    Eigen::MatrixXd dr_cols;                     // n_q x n_u: dr' of the columns
  };

  /// Full configuration for q_a: base from the stance sole (see file comment).
  void configuration(Scratch& s, const Eigen::Ref<const Eigen::VectorXd>& qa,
                     Eigen::Ref<Eigen::VectorXd> q) const;

  /// Signals at (q_a, qd_a, qdd_a, lambda_2). Afterwards s.q, s.qd, s.qdd, s.tau (= M qdd + b),
  /// s.lambda_s hold the full state of this sample. No allocation.
  void evaluate(Scratch& s, const Eigen::Ref<const Eigen::VectorXd>& input,
                Eigen::Ref<Eigen::VectorXd> signals) const;

  /// Signals and their Jacobian (signalCount x inputCount), the kinematic chain by finite
  /// differences (see file comment). The Scratch's state afterwards is unspecified (it holds
  /// perturbed evaluations).
  /// \param fd_step  step in q_a [rad]; \param central  central instead of forward differences
  void evaluate(Scratch& s, const Eigen::Ref<const Eigen::VectorXd>& input,
                Eigen::Ref<Eigen::VectorXd> signals, Eigen::Ref<Eigen::MatrixXd> jacobian,
                double fd_step, bool central) const;
  /// Signals and their Jacobian, the kinematic chain analytic (see file comment). Afterwards the
  /// Scratch holds the state of this sample, as after the signals-only evaluate().
  void evaluate(Scratch& s, const Eigen::Ref<const Eigen::VectorXd>& input,
                Eigen::Ref<Eigen::VectorXd> signals, Eigen::Ref<Eigen::MatrixXd> jacobian) const;

  const ContactConstraint& swingContact() const { return swing_; }
  FrameId stanceFrame() const { return stance_frame_; }
  FrameId swingFrame() const { return swing_frame_; }
  const Eigen::Isometry3d& stancePose() const { return stance_pose_; }

 private:
  /// Base reconstruction, update(q, qd), Jacobians, drifts.
  void kinematics(Scratch& s, const Eigen::Ref<const Eigen::VectorXd>& qa,
                  const Eigen::Ref<const Eigen::VectorXd>& qda) const;
  /// update(q, qd) at the current s.q and the velocity terms (drifts, phidot_2).
  void velocityTerms(Scratch& s) const;
  /// qdd, tau, lambda_s, u and the signal vector.
  void dynamics(Scratch& s, const Eigen::Ref<const Eigen::VectorXd>& qdda,
                const Eigen::Ref<const Vector6d>& lambda2, Eigen::Ref<Eigen::VectorXd> out) const;
  /// The kinematic state of the Scratch (after kinematics() or a swing-only update) into `k`,
  /// qdd = T qdd_a + k and phiddot_2 included.
  /// evaluate()'s Jacobian, column c from the changes kp - km over `span` about s.k0.
  void chainRuleColumn(Scratch& s, int c, const Scratch::Kinematic& kp,
                       const Scratch::Kinematic& km, double span, bool kinematic_terms_move,
                       const Eigen::Ref<const Vector6d>& lambda2,
                       Eigen::Ref<Eigen::MatrixXd> jac) const;
  /// Both Jacobian schemes: the signals, the qdd_a and lambda_2 columns, s.k0, s.M and the RNEA
  /// derivatives at the sample (the rest of `jac` zero).
  void jacobianCommon(Scratch& s, const Eigen::Ref<const Eigen::VectorXd>& input,
                      Eigen::Ref<Eigen::VectorXd> signals, Eigen::Ref<Eigen::MatrixXd> jac) const;
  /// evaluate()'s analytic Jacobian: the q_a and qd_a columns.
  void analyticColumns(Scratch& s, const Eigen::Ref<const Eigen::VectorXd>& input,
                       Eigen::Ref<Eigen::MatrixXd> jac) const;
  /// evaluate()'s Jacobian: the qd_a columns (central differences of the velocity pass).
  void velocityColumns(Scratch& s, const Eigen::Ref<const Eigen::VectorXd>& qdda,
                       const Eigen::Ref<const Vector6d>& lambda2,
                       Eigen::Ref<Eigen::MatrixXd> jac) const;
  /// evaluate()'s Jacobian: the q_a columns (differences of the kinematic chain).
  void positionColumns(Scratch& s, const Eigen::Ref<const Eigen::VectorXd>& input, double fd_step,
                       bool central, Eigen::Ref<Eigen::MatrixXd> jac) const;
  void saveKinematic(const Scratch& s, const Eigen::Ref<const Eigen::VectorXd>& qdda,
                     Scratch::Kinematic& k) const;
  /// qdd = [G qdd_a - J_sb^-1 drift_s; qdd_a] and the swing terms phi_2, phidot_2,
  /// phiddot_2 = drift + J_phi qdd of `swing` into `k` (the rest of `k` as it is).
  void accelerationTerms(const Eigen::MatrixXd& G, const Eigen::Matrix<double, 6, 6>& Jb_inv,
                         const Vector6d& drift_s, const ContactConstraintTerms& swing,
                         const Eigen::Ref<const Eigen::VectorXd>& qdda,
                         Scratch::Kinematic& k) const;
  /// Full kinematics at q_a (perturbed) into `k`: the base reconstructed, or, for a joint off the
  /// stance support path (`swing_only`), the base state of s.k0 kept and only the swing terms
  /// updated.
  void perturbedKinematic(Scratch& s, const Eigen::Ref<const Eigen::VectorXd>& qa,
                          const Eigen::Ref<const Eigen::VectorXd>& qda,
                          const Eigen::Ref<const Eigen::VectorXd>& qdda, bool swing_only,
                          Scratch::Kinematic& k) const;

  std::shared_ptr<const RobotModel> model_;
  int nq_, nu_;
  FrameId stance_frame_, swing_frame_;
  Eigen::Isometry3d stance_pose_;
  ContactConstraint swing_;
  double yaw_reference_;
  RneaDerivatives rnea_;
  KinematicDerivatives kin_;
  std::vector<bool>
      on_stance_path_;  ///< actuated joint i moves the stance sole relative to the base
};

}  // namespace reach_trajopt
