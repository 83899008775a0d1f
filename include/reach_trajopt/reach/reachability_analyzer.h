#pragma once
/// \file reachability_analyzer.h
/// The reachability check of the paper's Sec. III-C/D (eq. 13-21, Prop. 1-2), in the corrected
/// reading of docs/method.md Sec. 4: can the robot, in contact mode m_k from x_0, reach x_f (a
/// state of the next mode m_{k+1}, e.g. the touchdown of the swing sole) within the horizon?
///
///  1. Forward set (15)-(16) from x_0 over [0, t_1], backward set (17)-(20) from x_f over
///     [t_2, t_f], dt apart. With the pass's SamplingBudget (sample_budget.h), the first step of
///     each direction draws `initial_samples` inputs (paper: 1e4); every later step draws
///     `children_per_parent` (backward:
///     `backward_children_per_parent`) from each kept sample of the previous slice: its
///     boundary samples (21) plus `interior_samples` interior ones. Slices hold the outputs
///     y = swing sole position (13).
///  2. On each slice t in the overlap window [t_2, t_1]: the Hausdorff distance (14) between
///     the forward and backward output sets (k-d trees), the resolution K of Prop. 2 and the
///     closest pair.
///  3. Certificate (witness_certificate.h): the junction pairs of the window ranked by the
///     effort of closing their full-state gap, bridged from the forward sample to x_f by a
///     QP-controlled segment (junction_bridge.h), every 1 ms step re-checked with the full
///     model (eq. 1, 5, 8, limits, ground) and x(t_f) compared with x_f.
///  4. Verdict: reachable only with a certified path x_0 -> x_f (the witness). Otherwise
///     "not shown reachable" (reachable = false) with the closest attempt: its terminal gaps
///     and the swing sole's miss distance. The output-set test of step 2 (overlap: a sample of
///     one set inside the other's convex hull, or a pair closer than min(K, overlap_gap_max);
///     Prop. 2: d_H <= min(delta, K)) is reported (sets_meet, window) but decides nothing by
///     itself: in the walk the sets "overlapped" on steps no path joined.
///  5. Sample budget (PassSchedule::forCheck, sample_budget.h; docs/method.md Sec. 4.6): with
///     ReachConfig::quick_pass, steps 1-4 with budgets.quick first; budgets.full only when that
///     one neither certified the step nor ended its closest attempt beyond give_up_gap terminal
///     tolerances of x_f (gave up).
///
/// Choosing the time line (see ReachConfig): for the biped's single support -> double support
/// check, x_0 is a mid-swing state (swing sole in the air, moving toward the target; see
/// swing_state.h) and x_f the touchdown state (KinematicFeasibility's q_f, qd_f = 0). The sets
/// can only meet where the swing sole can travel between the two states in the horizon; the
/// window should sit in the middle, where both sets have spread (the paper's sets met at
/// t = 0.04 s). Defaults: horizon 0.08 s, window [0.03, 0.05] s. With the biped's torque limits
/// the forward set of the swing sole spreads by about +-8 cm in 30 ms, while the backward set
/// of (17)-(19) stays within a few mm of x_f (most backward draws violate the cone), so the
/// output sets answer "can the sole get from where it is to the target in t_f - t_0". The
/// certificate asks more: the whole state must arrive on x_f, and on bench/reach's case (the
/// sole 3 cm short at 0.75 m/s, 80 ms before touchdown, x_f at rest) no path is found, nor
/// does the strict OCP find one; the walk checks 0.2 s before touchdown (WalkConfig).
///
/// Choices beyond the paper (all in ReachConfig): the forward step is semi-implicit (the exact
/// inverse of the backward step (20)), contact drift stabilization, antithetic bang-bang draws,
/// boundary selection on y + tau ydot, interior samples, the swing sole kept above the ground,
/// and the hull test for overlap.
///
/// Parallelism: OpenMP over (parent, chunk of children); one ForwardStep / BackwardStep
/// (model workspace and QP solver) per thread; the random numbers of a sample depend only on
/// (seed, direction, step, parent, child) and results are written at fixed indices, so the
/// sets, verdict and witness are bit-identical for any thread count.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/contact/contact_mode.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/reach/hausdorff.h"
#include "reach_trajopt/reach/reach_config.h"
#include "reach_trajopt/reach/reach_progress.h"
#include "reach_trajopt/reach/sample_slice.h"
#include "reach_trajopt/reach/window_comparison.h"
#include "reach_trajopt/reach/witness_path.h"

namespace reach_trajopt {

/// One check: mode m_k, x_0, x_f and the footholds.
struct ReachProblem {
  ContactMode mode = ContactMode::singleSupport(Side::kLeft);  ///< m_k during [t_0, t_f]
  Eigen::VectorXd q0, qd0;  ///< x_0 (size n_q each): must satisfy m_k's contacts and limits
  Eigen::VectorXd qf, qdf;  ///< x_f: must satisfy m_k's contacts, the target's, and limits
  /// Planned world poses of the left (0) and right (1) soles held in m_k.
  std::optional<Eigen::Isometry3d> footholds[2];
  /// The swing sole's next foothold (m_{k+1} = m_k plus this contact); x_f must have the swing
  /// sole on it. Empty for systems without contacts (then x_f is only checked for limits).
  std::optional<Eigen::Isometry3d> target;
};

/// Counts of one check.
struct ReachCounts {
  long forward_samples = 0, backward_samples = 0;    ///< kept samples (roots excluded)
  long forward_qps = 0, backward_qps = 0;            ///< QPs solved
  long forward_rejected = 0, backward_rejected = 0;  ///< draws that gave no sample
  /// Backward draws rejected by the linearized (19) before their dynamics (part of
  /// backward_rejected; ReachConfig::backward_prefilter).
  long backward_prefiltered = 0;
  int threads = 1;
  /// Adds another check's counts (threads kept): the work of two sample budgets.
  void add(const ReachCounts& other);
};

/// Wall times of one check [s].
/// The two directions are propagated side by side (set_propagation.h): forward and backward
/// (each without its boundary selection) overlap, and with boundary they can add up to more
/// than total.
struct ReachTimings {
  double forward = 0.0, backward = 0.0, boundary = 0.0, hausdorff = 0.0, witness = 0.0;
  double total = 0.0;
  /// Adds another check's times: the wall times of two sample budgets run one after the other.
  void add(const ReachTimings& other);
};

/// Everything a check returns.
struct ReachResult {
  bool reachable = false;               ///< a certified witness path x_0 -> x_f exists
  std::string reason;                   ///< one sentence explaining the verdict
  std::vector<SampleSlice> forward;     ///< slice j at time j dt (slice 0 = x_0)
  std::vector<SampleSlice> backward;    ///< slice j at time t_f - j dt (slice 0 = x_f)
  std::vector<SliceComparison> window;  ///< the test (14) on [t_2, t_1]
  int best = -1;  ///< index into window of the closest (or first overlapping) slice
  /// The output-set test (14) / Prop. 2 passed on some slice (informative, not the verdict).
  bool sets_meet = false;
  WitnessPath witness;  ///< certified when reachable, else the closest attempt
  /// Sample budgets drawn (ReachConfig::quick_pass): 2 when the quick budget was followed by
  /// the full one (the sets and the witness are the full budget's; counts and timings sum
  /// both), else 1.
  int budgets = 1;
  /// The check stopped after an uncertified quick budget whose closest attempt ended beyond
  /// ReachConfig::give_up_gap: the full budget was not drawn.
  bool gave_up = false;
  ReachCounts counts;
  ReachTimings timings;
  double dt = 0.0;                       ///< time step used [s]
  bool semi_implicit = true;             ///< forward integrator used
  std::vector<std::string> joint_names;  ///< names of q's coordinates
};

/// @brief Bidirectional sampling-based reachability check of eq. (13)-(21) and Prop. 1-2.
/// Immutable; check() may run concurrently from several threads.
class ReachabilityAnalyzer {
 public:
  /// \throws ReachError on an invalid config or contact config.
  ReachabilityAnalyzer(std::shared_ptr<const RobotModel> model, const ContactConfig& contact,
                       const ReachConfig& config);

  /// Runs the check. Throws ReachError on bad input: wrong sizes or non-finite states, x_0
  /// violating m_k's contacts (phi, J qd beyond the tolerances) or the limits, x_f violating
  /// m_k's or the target's contacts or the limits (an infeasible x_f), a mode without
  /// footholds, or a config with an empty window or zero samples.
  ReachResult check(const ReachProblem& problem) const;
  /// Same with another configuration (e.g. more samples) for this one call, reporting its
  /// progress after each slice to `progress` (reach_progress.h; may be empty; with two
  /// budgets each reports its own slices). Runs PassSchedule::forCheck(config): with
  /// config.quick_pass the budget adapts: config.budgets.quick first; the check ends there when
  /// it certifies the step, or when its closest attempt ended beyond config.give_up_gap
  /// terminal tolerances of x_f (gave_up); otherwise config.budgets.full decides.
  /// \throws ReachCancelled when `progress` returns false.
  ReachResult check(const ReachProblem& problem, const ReachConfig& config,
                    const ReachProgressCallback& progress = {}) const;
  /// One pass: steps 1-4 of the file comment with `pass`'s budget and sets (the step
  /// planner's passes). With PassSets::kForwardOnly the forward set alone, up to
  /// pass.forward_until_s, and no verdict (reachable false).
  ReachResult checkPass(const ReachProblem& problem, const ReachConfig& config,
                        const CheckPass& pass, const ReachProgressCallback& progress = {}) const;

  /// The configuration q of sample `index` of a slice (exact, from its parent chain).
  /// \param forward  true: result.forward, false: result.backward
  Eigen::VectorXd sampleConfiguration(const ReachResult& result, bool forward, int slice,
                                      int index) const;

  const ReachConfig& config() const { return config_; }
  const ContactConfig& contactConfig() const { return contact_; }
  const RobotModel& model() const { return *model_; }
  std::shared_ptr<const RobotModel> modelPtr() const { return model_; }

 private:
  std::shared_ptr<const RobotModel> model_;
  ContactConfig contact_;
  ReachConfig config_;
};

}  // namespace reach_trajopt
