#pragma once
/// \file ocp_config.h
/// Parameters of the transition OCP (eq. 22-23). Speed against accuracy:
///  - segments: spline segments over the horizon; variables = 12 (N - 1) + 6 (strict) or
///    12 (N + 1) + 8 (relaxed), 42 / 68 for N = 4. More segments: richer motions, but SLSQP
///    needs more iterations (measured: N = 6 about 1.5x the iterations of N = 4). The biped's
///    walk: N = 4 over its 0.2 s check horizon (N = 5: 1.8x the OCP time, and no more pushes
///    survived on the envelope's grid); TALOS keeps N = 5 (with 4, more of its pushed walk's
///    strict OCPs failed).
///  - check_interval: spacing of the samples where cones, torque bounds, hulls and the cost are
///    evaluated inside the NLP. Smaller: more rows, slower; the result is always re-checked at
///    output_dt and samples that violate are added (refinement), up to max_refinements.
///  - cone_margin, torque_margin: how far inside the cones and torque bounds the NLP samples
///    must stay, so that the samples in between (re-checked at 1 ms) stay inside too; larger
///    margins mean fewer refinement re-solves but a slightly smaller feasible set.
///  - chain_derivatives: how the per-sample Jacobian differentiates the kinematic chain (the full
///    state and the soles' terms as functions of the actuated joints, stance_reduced_dynamics.h):
///    analytic (exact up to roundoff, the default) or finite_differences (fd_step,
///    central_differences below), kept to compare the two. The analytic Jacobian of one sample
///    costs about 0.3x the forward-difference one on the biped (0.2x on the 38-dof TALOS); a
///    whole biped OCP about 0.5-0.7x (the NLP's other work stays). Both reach the same optima
///    within the solver's tolerances, not the same bits, so a walk's trajectories differ.
///  - central_differences: with finite_differences, d/dq by central instead of forward
///    differences (2x the kinematic part of the gradient cost, about 1e-10 instead of 1e-7
///    relative error).
///  - row_screening: SLSQP's own work per iteration (a dense least-squares subproblem) grows with
///    the inequality rows; it sees only those near active, the others are checked at its answer
///    (issue 41: on the demo walk's OCPs 0.58x the time, the same answers). 0 turns it off.
///  - threads: the NLP's samples on OpenMP threads (same bits for any count); with OpenMP's
///    active wait policy on a loaded machine a second thread can cost more than it saves
///    (scripts/env.sh sets OMP_WAIT_POLICY=passive).

#include <string>

namespace reach_trajopt {

class YamlSection;
template <typename Config>
class ConfigFields;

/// How the transition OCP's per-sample Jacobian differentiates the kinematic chain.
enum class ChainDerivatives { kAnalytic, kFiniteDifferences };

/// Transition OCP settings. The cost (22) is written in scaled form:
///   J = (1/T) int [ w_torque |u ./ u_max|^2 + w_wrench |lambda / (m g)|^2
///                 + w_position |q - q_f|^2 + w_velocity |qd - qd_f|^2 ] dt + w_eps |eps|^2,
/// i.e. Qu = w_torque diag(u_max)^-2 / T, Ql = w_wrench / (m g)^2 / T, Qx = diag(w_position,
/// w_velocity) / T, integrated by the trapezoid rule over the check samples.
struct TransitionOcpConfig {
  int segments = 4;              ///< cubic B-spline segments over the horizon (2 .. 200)
  double check_interval = 0.02;  ///< NLP sample spacing [s] (>= 1 ms)
  double output_dt = 0.001;      ///< output / verification sample spacing [s] (>= 0.1 ms)
  double w_torque = 1.0;         ///< weight of |u / u_max|^2
  double w_wrench = 0.1;         ///< weight of |lambda / (m g)|^2
  double w_position = 0.1;       ///< weight of |q - q_f|^2 [1/rad^2, 1/m^2]
  double w_velocity = 0.001;     ///< weight of |qd - qd_f|^2 [s^2/rad^2]
  double w_eps = 1.0e3;          ///< weight of |eps|^2 in the relaxed problem [1/m^2]
  /// Relaxed problem only: at t_f the floating base (the URDF root, the pelvis) stands upright
  /// (roll = pitch = 0) at this height above the mean sole height [m], the posture of the
  /// kinematic feasibility check (Sec. III-B), so the landing configuration is an IK solution
  /// of that check. <= 0 disables it (the base is then free, e.g. it may crouch to reach).
  /// Not a YAML key: the YAML readers set it to kinematic_feasibility.pelvis_height
  /// (FootstepPlannerConfig::fromYaml), the one place the robot's pelvis height is written.
  double terminal_pelvis_height = 1.05;
  double cone_margin = 0.01;        ///< cone rows required >= margin m g inside the NLP
  double torque_margin = 0.01;      ///< |u| <= (1 - margin) u_max inside the NLP
  bool ground_clearance = true;     ///< swing sole z >= min(z_target, z(t_0)) at NLP samples,
  double swing_clearance = 0.0075;  ///< plus this much in the middle of the horizon [m], with
                                    ///< quadratic ramps over its first and last thirds (the
                                    ///< sole lands with phidot = 0: z ~ (t_f - t)^2), so it
                                    ///< cannot graze the ground and touch down early
  double tolerance = 1.0e-4;        ///< accepted violation, each family (units: see result)
  double input_tolerance = 1.0e-4;  ///< x_0, x_f on their contacts [m, rad, m/s, rad/s]
  int max_refinements = 3;          ///< re-solves (violating samples added, or a restart)
  int max_evaluations = 400;        ///< NLopt maxeval per solve
  double time_limit = 10.0;         ///< wall-clock limit for the whole request [s]
  double ftol_rel = 1.0e-6;         ///< NLopt relative cost tolerance (strict problem)
  /// Relaxed problem: its cost is dominated by w_eps |eps|^2, so a relative cost test would stop
  /// SLSQP before the equalities converge; it uses this tighter value and stops on xtol_rel.
  double relaxed_ftol_rel = 1.0e-14;
  double xtol_rel = 1.0e-7;  ///< NLopt relative variable tolerance
  ChainDerivatives chain_derivatives = ChainDerivatives::kAnalytic;  ///< see file comment
  double fd_step = 1.0e-6;             ///< finite_differences: step in q [rad, m]
  bool central_differences = false;    ///< finite_differences: see file comment
  double fit_regularization = 1.0e-6;  ///< seed fit: weight of the second differences
  /// SLSQP sees only the inequality rows within this of active (row value > -row_screening at
  /// its start: cone rows in units of m g, torque rows of u_max, hull and clearance rows in m);
  /// the rows left out are checked at its answer, and SLSQP runs again from there with the rows
  /// near active added while one is violated (after two such rounds, or when it stops on a row it
  /// saw, with every row). Its subproblem's cost grows with the row count (most rows are far
  /// from active), and rows that stay inactive change neither its steps nor its merit function:
  /// same answers at a fraction of the cost. 0: every row from the start.
  double row_screening = 0.1;
  /// OpenMP threads evaluating the NLP's samples (0: OpenMP's default); the result has the same
  /// bits for any count (each sample on one thread, the rows assembled in sample order).
  int threads = 0;

  /// Throws ConfigError naming the first bad value.
  void validate() const;
  /// The YAML keys of section `ocp:` (the member names but terminal_pelvis_height), their
  /// units and meaning.
  static const ConfigFields<TransitionOcpConfig>& fields();
  /// Reads fields() from a YAML section, then validates. terminal_pelvis_height keeps its
  /// value: FootstepPlannerConfig::fromYaml sets it from kinematic_feasibility.pelvis_height.
  static TransitionOcpConfig fromYaml(const YamlSection& section);
};

}  // namespace reach_trajopt
