#pragma once
/// \file reach_config.h
/// Parameters of the reachability check (docs/method.md Sec. 4, eq. 13-21, Prop. 1-2), YAML
/// section `reach:` (docs/parameters.md). The paper gives dt = 1 ms, 1e4 samples at the first
/// step and delta = 1e-5; the rest are ours (docs/method.md says where each value came from).
///
/// Time line of one check (all times relative to t_0, the time of x_0):
///   forward set  from x_0 at 0 up to t_1 = window_end            (eq. 15-16)
///   backward set from x_f at t_f = horizon back to t_2 = window_start  (eq. 17-20)
///   the test (14) on every slice t in [t_2, t_1] (the overlap window).
/// Forward-only checking (the paper's earlier method) is window_start = window_end = horizon.
///
/// Speed: a check costs about the QPs it solves, set by its sample budget (sample_budget.h:
/// `budgets.full`, `budgets.quick`, `budgets.hull`) and the number of steps
/// window_end / dt + (horizon - window_start) / dt.

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "reach_trajopt/reach/sample_budget.h"

namespace reach_trajopt {

class YamlSection;
template <typename Config>
class ConfigFields;

/// Upper bounds of ReachConfig (docs/limits.md), checked by validate(): a request beyond them
/// is rejected up front instead of running for minutes or exhausting memory. The paper's
/// values (1e4 samples, 1 ms, 0.1 s horizons) sit far inside.
struct ReachLimits {
  static constexpr int kMaxInitialSamples = 200000;   ///< 20 x the paper's 1e4
  static constexpr int kMaxChildrenPerParent = 1000;  ///< also backward_children_per_parent
  static constexpr int kMaxBoundary = 10000;          ///< also interior_samples
  static constexpr int kMaxAngularBins = 4096;
  static constexpr int kMaxLookahead = 16;                ///< entries of boundary_lookahead
  static constexpr int kMaxSteps = 20000;                 ///< horizon / dt
  static constexpr int kMaxCertificateCandidates = 1000;  ///< bridges of one check
  static constexpr int kMaxRedrawRounds = 8;              ///< redraw_rounds
  /// Estimated memory of one check (estimatedMemoryBytes) allowed [bytes].
  static constexpr double kMaxMemoryBytes = 1024.0 * 1024 * 1024;
  /// Estimated QPs of one check (estimatedQps) allowed: about 10-30 s on one core; the
  /// shipped configuration needs 3.3e5.
  static constexpr double kMaxQps = 2.0e6;
};

/// Configuration of ReachabilityAnalyzer. validate() throws ConfigError naming a bad field.
struct ReachConfig {
  // ---- time line -------------------------------------------------------------------------
  double dt = 1e-3;            ///< time step of (16) and (20) [s] (paper: 1 ms)
  double horizon = 0.08;       ///< t_f - t_0 [s]
  double window_start = 0.03;  ///< t_2 - t_0 [s]: the backward set reaches back to here
  double window_end = 0.05;    ///< t_1 - t_0 [s]: the forward set reaches up to here
  // ---- sampling ------------------------------------------------------------------------
  /// The sample budgets of the passes (sample_budget.h; YAML `budgets: {full, quick, hull}`).
  ReachBudgets budgets;
  int angular_bins = 16;  ///< bins around the centroid per plane (keeps concave parts)
  /// Boundary selection (21) uses y + tau * ydot for each tau here [s]: with tau = 0 only the
  /// positions count; tau > 0 also keeps the samples whose velocity points outward, which are
  /// the ones the next steps' extremes come from.
  std::vector<double> boundary_lookahead = {0.0, 0.005, 0.02};
  /// Fraction of the draws of each parent (u of (15), d of (17)) that are vertices of their
  /// box (every component at a random bound), in antithetic pairs +v, -v; the rest are
  /// uniform. The extremes of a reachable set come from bang-bang inputs, which uniform draws
  /// almost never produce. 0 = the paper's uniform draws.
  double vertex_fraction = 0.25;
  /// Extra rounds of draws at a step whose slice keeps fewer samples than redraw_below x
  /// (max_boundary + interior_samples): each round draws as many children per parent again
  /// (new draws, uniform), until the slice has that many or the rounds are spent. Where (19)
  /// rejects nearly every backward draw, a slice can otherwise thin out to nothing within a few
  /// steps and end the set. 0: the paper's fixed draws per parent. A step then draws at most
  /// (1 + redraw_rounds) times its draws; estimatedQps() counts one round.
  int redraw_rounds = 3;
  /// The share of max_boundary + interior_samples below which a slice gets another round, in
  /// [0, 1]: small, so only slices on their way to nothing draw again.
  double redraw_below = 0.125;
  std::uint64_t seed = 1;  ///< random stream: results are identical for any thread count
  int threads = 0;         ///< OpenMP threads (0: OpenMP's default)
  // ---- forward QP (15) ----------------------------------------------------------------------
  /// "semi_implicit": q_{j+1} = q_j + dt qd_{j+1}, the exact inverse of the backward step (20),
  /// so both sets and the witness path belong to one discrete-time system; positions then
  /// depend on the sample's acceleration. "explicit": q_{j+1} = q_j + dt qd_j as printed in (16)
  /// (all children of a parent then share one position; the position limits are imposed one
  /// step ahead, on q_j + 2 dt qd_j + dt^2 qdd).
  std::string forward_integrator = "semi_implicit";
  double w_qdd = 1e-4;     ///< W_qdd of (15) [per (rad/s^2)^2]
  double w_du = 1.0;       ///< W_u of (15): large, so u + du stays close to the drawn u
  double w_lambda = 1e-6;  ///< W_lambda of (15)
  /// beta in [0, 1] of the contact acceleration rows: J_phi qdd = -Jdot_phi qd -
  /// beta (phi / dt^2 + 2 phidot / dt); 0 is eq. (5) as printed; > 0 removes the O(dt^2)
  /// drift of the Euler steps (1 = deadbeat in two steps). Also used by the backward step.
  double contact_stabilization = 0.5;
  // ---- backward draws (17) ----------------------------------------------------------------
  double backward_joint_accel = 10.0;  ///< a_max of the actuated coordinates [rad/s^2 or m/s^2]
  double backward_base_accel = 2.0;    ///< a_max of the six floating-base coordinates
  /// With one held sole, reject a draw d before its dynamics when (19) linearized at the
  /// parent (the bias at d = 0, exact otherwise) is violated by more than a tenth of the
  /// row's range over the draw box: the same children as without it (backward_step.h), at a
  /// fraction of the cost of the draws that (19) rejects. false: every draw gets the exact test.
  bool backward_prefilter = true;
  // ---- the test (14), Prop. 1-2 -------------------------------------------------------------
  double delta = 1e-5;  ///< Prop. 2 threshold on d_H [m] (paper 1e-5), used as min(delta, K)
  /// The sets overlap at a slice when a sample of one lies inside the other's convex hull, or
  /// a forward and a backward output lie closer than min(K, overlap_gap_max): closer than the
  /// sampling resolution K of Prop. 2 (largest nearest-neighbour gap of the sparser set), but
  /// never farther apart than this [m].
  double overlap_gap_max = 5e-3;
  // ---- the certificate (witness_certificate.h, junction_bridge.h) -------------------------
  /// Largest violation along a certified path of eq. (1) [N, Nm], the cones (8) [N], the
  /// torque limits [Nm], the position / velocity limits [m, rad; m/s, rad/s], the Euler steps
  /// [m, rad] and the ground [m]; the held soles' |phi| within contact_tolerance.
  double certificate_tolerance = 1e-4;
  /// |J_phi qd| of the held soles along a certified path [m/s, rad/s]. Looser than at x_0 and
  /// x_f: the Euler steps of (16) / (20) leave |phi| ~ 1e-6 per step on the curved contact
  /// manifold, and the drift stabilization answers with |J qd| ~ beta |phi| / dt.
  double certificate_contact_velocity_tolerance = 1e-2;
  double terminal_position_tolerance = 1e-3;  ///< |q(t_f) - q_f|_inf of a certified path [m, rad]
  double terminal_velocity_tolerance = 1e-2;  ///< |qd(t_f) - qd_f|_inf [m/s, rad/s]
  // ---- output and states ----------------------------------------------------------------
  std::string output_frame;         ///< frame of y; empty: the swing sole of the mode
  std::string output_axes = "xyz";  ///< world axes of the frame origin in y (1-3 of x, y, z)
  /// Samples whose swing sole origin is below the target foothold height minus this are
  /// rejected (the ground); negative infinity disables. [m]
  double swing_ground_margin = 0.0;
  double contact_tolerance = 1e-4;           ///< |phi| allowed at x_0 and x_f [m, rad]
  double contact_velocity_tolerance = 1e-3;  ///< |J qd| allowed at x_0 and x_f [m/s, rad/s]
  double limit_tolerance = 1e-9;             ///< slack on position / velocity / torque limits
  // ---- the passes (PassSchedule, sample_budget.h) ------------------------------------------
  /// Draw budgets.quick first. The step planner (step/footstep_transition_planner.h) plans the
  /// step with it and runs its later passes only when that pass certifies nothing or its strict
  /// OCP fails (a quick certificate is kept if the full pass finds none); a check on its own
  /// (ReachabilityAnalyzer::check) ends after the quick budget when it certifies the step or
  /// gives up (give_up_gap), and draws budgets.full otherwise. false: budgets.full alone.
  bool quick_pass = true;
  /// A check on its own stops after an uncertified quick budget whose closest attempt ends
  /// more than this many terminal tolerances from x_f (terminalGapInTolerances of
  /// witness_certificate.h: the sets are too far apart for the full budget to join them):
  /// "not shown reachable" without the full budget. 0: never. The step planner never gives up.
  double give_up_gap = 20.0;
  /// When the quick pass's strict OCP fails, the step planner first solves it again, seeded as
  /// before, in the quick pass's own hulls grown to this margin [m] (no sampling: one OCP),
  /// before the hull pass. 0 (or not above budgets.quick.constraint_margin): no such retry.
  double quick_retry_constraint_margin = 0.0;
  /// When the quick pass's strict OCP fails (its certified step has no trajectory, or its local
  /// solve does not converge), the step planner solves that OCP again, seeded as before, in the
  /// eq. (23) hulls of a forward set alone drawn with budgets.hull up to the quick witness's
  /// junction, and plans the full pass only when that fails too.
  bool hull_pass = true;

  /// Throws ConfigError naming a bad field, also for values over ReachLimits and threads over
  /// the hardware threads of this machine.
  void validate() const;
  /// Estimated peak memory of one check with `budget` for a model with `nq` coordinates
  /// [bytes]: every slice's samples (outputs, rates, velocities, torques, wrenches, kept
  /// configurations).
  double estimatedMemoryBytes(int nq, const SamplingBudget& budget) const;
  /// Same for the largest of the three budgets.
  double estimatedMemoryBytes(int nq) const;
  /// Upper estimate of the QPs (samples) of one check with `budget`: 2 initial_samples + per
  /// later step (max_boundary + interior_samples) x max(children_per_parent,
  /// backward_children_per_parent).
  double estimatedQps(const SamplingBudget& budget) const;
  /// Same for the largest of the three budgets.
  double estimatedQps() const;
  /// Throws ConfigError when estimatedMemoryBytes(nq) > ReachLimits::kMaxMemoryBytes or
  /// estimatedQps() > ReachLimits::kMaxQps for any of the three budgets (called before a check
  /// starts).
  void requireResourcesWithinLimits(int nq) const;
  /// Same for one budget.
  void requireResourcesWithinLimits(int nq, const SamplingBudget& budget) const;
  /// Its YAML keys (section `reach:`, docs/parameters.md).
  static const ConfigFields<ReachConfig>& fields();
  /// Reads fields() of a YAML section on top of `base`, then validates. Unknown keys throw.
  static ReachConfig fromYaml(const YamlSection& section, const ReachConfig& base);
  /// Same on top of the defaults.
  static ReachConfig fromYaml(const YamlSection& section);
  bool semiImplicit() const { return forward_integrator == "semi_implicit"; }
};

}  // namespace reach_trajopt
