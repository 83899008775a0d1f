#pragma once
/// \file transition_nlp.h
/// The transcription of the transition OCP (eq. 22-23) that NLopt's SLSQP solves.
///
/// Why this transcription. SLSQP is a dense SQP method whose cost per iteration grows as n^3
/// (measured beside IPOPT in bench/README.md), so the variable count must stay in the hundreds. We
/// therefore
///  1. write the 12 actuated joint trajectories as clamped cubic B-splines with few segments
///     (cubic_bspline.h): q_a(t) = sum_k N_k(t) c_k. The first two and (strict problem) last two
///     control points encode x(t_0) = x_0 and x(t_f) = x_f exactly, so the boundary states are
///     eliminated rather than constrained; joint limits become bounds on the control points
///     (the convex-hull property of B-splines keeps q_a(t) inside them for every t);
///  2. hold the stance contact of eq. (5) exactly by construction: the floating base follows
///     from q_a and the fixed stance sole (stance_reduced_dynamics.h), so phi_s, phidot_s and
///     phiddot_s vanish at every t, not only at collocation points;
///  3. eliminate torques and stance wrenches by inverse dynamics: in single support the base
///     rows of eq. (1) fix lambda_s and the actuated rows give u, so eq. (1) holds exactly at
///     every t. Only the new contact's wrench lambda_2 at t_f (double support: the split between
///     the feet is free) is a variable (6, scaled by m g);
///  4. keep the inequality constraints (both cones of eq. 8, torque bounds, reachable-set hulls
///     A y <= b of the swing sole, optional ground clearance, the legs' clearance of
///     leg_clearance.h, eq. 4's h_state) at a set of samples: a uniform
///     grid (check_interval), the times of the hull slices used, and any time the 1 ms
///     re-check found violated (refinement, see transition_ocp.h). t_f is sampled twice: just
///     before touchdown (single support, lambda_2 = 0) and at touchdown (double support);
///  5. new-mode contact at t_f: phi_2 = 0 and phidot_2 = 0 follow from x(t_f) = x_f (checked on
///     the input); phiddot_2 = 0 is an equality (6 rows). Relaxed problem: the last two control
///     points are free, eps = (eps_x, eps_y) are variables, and the equalities are
///     phi_2 - [eps; 0 0 0 0] = 0, phidot_2 = 0, phiddot_2 = 0 (18 rows), and, unless disabled,
///     the base upright at the nominal height (3 rows: TransitionOcpConfig::
///     terminal_pelvis_height, or the request's), so the landing is a kinematically feasible stance
///     (Sec. III-B). The phidot_2 and phiddot_2 rows are multiplied by h and h^2 (h the knot
///     spacing) so all equality rows are in metres and equally sensitive to the control points.
/// Variables: 12 (N - 1) + 6 (strict) or 12 (N + 1) + 8 (relaxed); N = 4 segments gives 42 / 68.
///
/// Gradients: per sample, the signals' Jacobian with respect to (q_a, qd_a, qdd_a, lambda_2)
/// (stance_reduced_dynamics.h: analytic in qdd_a and lambda_2, the dynamics through the analytic
/// RNEA derivatives, the kinematic chain by differences) chained with the spline basis (each
/// sample depends on 4 control points per joint). Checked against central finite differences of
/// this class's functions in test/unit/test_ocp_gradients.cpp. The samples are evaluated on
/// TransitionOcpConfig::threads OpenMP threads, with the same bits for any count.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <vector>

#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/contact/contact_wrench_cone.h"
#include "reach_trajopt/model/leg_clearance.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/ocp/cubic_bspline.h"
#include "reach_trajopt/ocp/ocp_config.h"
#include "reach_trajopt/ocp/stance_reduced_dynamics.h"
#include "reach_trajopt/ocp/transition_request.h"
#include "reach_trajopt/ocp/transition_result.h"

namespace reach_trajopt {

using RowMajorMatrixXd = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Values (and optionally gradients) of the NLP at one point x. Jacobians are row-major, the
/// layout NLopt's vector constraints use.
struct NlpValues {
  double cost = 0.0;
  Eigen::VectorXd cost_gradient;         ///< n
  Eigen::VectorXd equality;              ///< m_eq, = 0 at a solution
  RowMajorMatrixXd equality_jacobian;    ///< m_eq x n
  Eigen::VectorXd inequality;            ///< m_in, <= 0 at a solution
  RowMajorMatrixXd inequality_jacobian;  ///< m_in x n
};

/// One state of the sampled transition trajectory (full coordinates).
struct TransitionSampleState {
  Eigen::VectorXd q, qd, qdd, u;                                             ///< n_q, n_q, n_q, n_u
  Vector6d lambda_stance = Vector6d::Zero(), lambda_new = Vector6d::Zero();  ///< world [N, N m]
  Eigen::Vector3d swing_position = Eigen::Vector3d::Zero();                  ///< [m]
  Vector6d phi2 = Vector6d::Zero(), phidot2 = Vector6d::Zero(), phiddot2 = Vector6d::Zero();
};

/// The NLP of one transition request in strict or relaxed form (see file comment). The request
/// must have been validated (TransitionOcp does it). Not thread-safe (owns scratch buffers).
class TransitionNlp {
 public:
  TransitionNlp(std::shared_ptr<const RobotModel> model, const TransitionOcpConfig& config,
                const ContactConfig& contact, const TransitionRequest& request, bool relaxed);

  bool relaxed() const { return relaxed_; }
  int variableCount() const { return n_x_; }
  int equalityCount() const { return relaxed_ ? (pelvis_posture_ ? 21 : 18) : 6; }
  int inequalityCount() const { return inequality_count_; }
  const Eigen::VectorXd& lowerBounds() const { return lower_; }
  const Eigen::VectorXd& upperBounds() const { return upper_; }
  const CubicBSplineBasis& basis() const { return basis_; }
  const StanceReducedDynamics& dynamics() const { return *dyn_; }
  double weight() const { return weight_; }  ///< m g [N]

  /// Initial guess: the seed path (or a cubic Hermite x_0 -> x_f) fitted by SPQR, clamped
  /// to the bounds; lambda_2 = 0, eps = 0.
  Eigen::VectorXd initialGuess() const;

  /// Cost, equalities (= 0) and inequalities (<= 0) at x; gradients when `gradients`.
  void evaluate(const Eigen::VectorXd& x, bool gradients, NlpValues& out);

  /// The NLP sample times [s] (sorted).
  const std::vector<double>& sampleTimes() const { return sample_times_; }
  /// Adds inequality samples at these times (refinement) and hull slices by index. Returns
  /// whether the NLP changed: false when every time is one it samples already and every slice
  /// is enforced already (solving it again is a restart).
  bool addSamples(const std::vector<double>& times, const std::vector<int>& slices);
  /// Slices currently enforced.
  const std::vector<int>& enforcedSlices() const { return enforced_slices_; }

  /// The solution x sampled every dt and exactly at t_f (q, qd, qdd, u, lambda, landing,
  /// eps, relaxed) into `out`, as the OCP's output before its re-check.
  void sampleSolution(const Eigen::VectorXd& x, double dt, TransitionResult& out);
  /// The full state at time t in [0, T] for the solution x (lambda_2 acts only at t = T).
  void state(const Eigen::VectorXd& x, double t, TransitionSampleState& out);
  /// How far the legs at configuration q are inside the leg clearance margin [m] (0: clear,
  /// or no leg clearance).
  double legClearanceViolation(const Eigen::VectorXd& q) const;
  /// eps of x (zero for the strict problem) [m].
  Eigen::Vector2d eps(const Eigen::VectorXd& x) const;
  /// lambda_2 of x [N, N m].
  Vector6d lambdaNew(const Eigen::VectorXd& x) const;

 private:
  struct Sample {
    double t = 0.0;
    bool final = false;       ///< the double-support sample at t_f (lambda_2 acts)
    std::vector<int> slices;  ///< hull slices enforced at this sample
    double weight = 0.0;      ///< trapezoid cost weight (1/T int dt)
  };
  struct EvalState;  ///< scratch of one evaluate() call (transition_nlp.cpp)
  using StridedRow = Eigen::Ref<const Eigen::RowVectorXd, 0, Eigen::InnerStride<>>;
  /// Constructor parts: the fixed control points, variable layout and bounds; the hulls with
  /// unit normals and the slices enforced at first.
  void layOutVariables();
  void prepareSlices();
  void rebuildSamples();
  /// One thread's scratch for sampleSignals().
  struct Worker {
    Worker(const StanceReducedDynamics& d, int local_columns);
    std::unique_ptr<StanceReducedDynamics::Scratch> scratch;
    Workspace kinematics;  ///< the sample's configuration, for the leg clearance
    Eigen::VectorXd input;
    Eigen::MatrixXd jin;
  };
  /// One sample's signals and their local Jacobian (over its 4 control points and lambda_2).
  struct SampleEval {
    CubicBSplineBasis::Row brow;
    Eigen::VectorXd signals;
    Eigen::MatrixXd jloc;
    double leg_distance = 0.0;        ///< the legs' capsules' distance at the sample's q [m]
    Eigen::RowVectorXd leg_gradient;  ///< its gradient in q (1 x n_q)
  };
  /// TransitionOcpConfig::threads, 0 resolved to OpenMP's default.
  int resolvedThreads() const;
  /// evaluate() per sample: first (in parallel over the samples) the spline input, dynamics and
  /// the local Jacobian into `se`; then, in sample order, with signals_ and jloc_ holding them,
  /// the cost (22) (sets u_scaled_); the stance cone, torque, clearance and hull rows; at t_f
  /// the new contact's cone and the equalities.
  void sampleSignals(const Sample& smp, const Eigen::VectorXd& x, bool gradients, Worker& w,
                     SampleEval& se) const;
  void addSampleCost(const Sample& smp, EvalState& e);
  void addPathInequalities(const Sample& smp, int i, EvalState& e);
  void addTerminalRows(EvalState& e);
  /// Adds a local gradient (over the 4 control points of the current sample and lambda_2) to
  /// a row of the full gradient.
  void scatter(const EvalState& e, Eigen::Ref<Eigen::RowVectorXd> target, const StridedRow& local,
               bool final) const;
  /// q_a, qd_a, qdd_a at t from x into `input` (lambda_2 part set by the caller).
  void splineInput(const Eigen::VectorXd& x, const CubicBSplineBasis::Row& row,
                   Eigen::Ref<Eigen::VectorXd> input) const;
  double controlPoint(const Eigen::VectorXd& x, int k, int joint) const;
  int freeIndex(int k) const;  ///< first variable of control point k, -1 when fixed
  /// True when sample i has the leg clearance row: every sample after t_0 and before t_f, and
  /// in the relaxed problem t_f's single-support sample.
  bool hasLegRow(const Sample& smp, int i) const;
  /// Lowest swing sole height allowed at t [m] (ground_clearance, swing_clearance).
  double groundFloor(double t) const;

  std::shared_ptr<const RobotModel> model_;
  TransitionOcpConfig config_;
  TransitionRequest request_;
  bool relaxed_;
  int nq_, nu_;
  CubicBSplineBasis basis_;
  std::unique_ptr<StanceReducedDynamics> dyn_;
  std::unique_ptr<StanceReducedDynamics::Scratch> scratch_;
  ContactWrenchCone::Matrix C_stance_, C_new_;
  Eigen::MatrixXd fixed_points_;  ///< K x n_u, rows of the fixed control points
  int first_free_, last_free_;    ///< range of free control points
  int n_x_, lambda_index_, eps_index_;
  Eigen::VectorXd lower_, upper_;
  Eigen::VectorXd u_max_inv_;
  double weight_;
  double ground_floor_;
  bool ground_clearance_;
  LegClearance legs_;
  double leg_margin_ = -HUGE_VAL;     ///< -inf: no leg clearance rows [m]
  double leg_row_bound_ = -HUGE_VAL;  ///< the rows' bound, the margin and a pad [m]
  bool pelvis_posture_;
  double pelvis_height_target_;  ///< world z of the base at t_f (relaxed) [m]
  std::vector<double> sample_times_;
  std::vector<Sample> samples_;
  std::vector<int> enforced_slices_;
  std::vector<double> extra_times_;
  std::vector<Eigen::MatrixX2d> slice_A_;  ///< rows normalized
  std::vector<Eigen::VectorXd> slice_b_;
  int inequality_count_ = 0;
  // Scratch for evaluate() (workers_ and sample_eval_ grow on first use).
  Eigen::VectorXd input_, signals_, u_scaled_;
  Eigen::MatrixXd jloc_;
  std::vector<Worker> workers_;
  std::vector<SampleEval> sample_eval_;
};

}  // namespace reach_trajopt
