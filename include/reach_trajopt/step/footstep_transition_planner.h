#pragma once
/// \file footstep_transition_planner.h
/// The proposed method's per-step pipeline (paper Sec. III, used in Sec. IV), one class for
/// every caller (the walking loop, transition_ocp_node, the tools): from a single-support state
/// x_0 a short time before touchdown,
///   1. x_0 made consistent with the stance contact (contact_consistent_state.h), optionally;
///   2. the kinematic check of the foothold (Sec. III-B), x_f its IK posture;
///   3. the bidirectional reachability check (13)-(21), optionally;
///   4. the transition OCP (22)-(23), seeded with the check's witness path and held in its
///      forward set's swing sole hulls (eq. 23, reachable_set_constraint.h): strict to the
///      foothold when the witness is certified; otherwise strict first, as the local solve
///      that may still certify the step (a converged strict OCP is a checked path x_0 ->
///      x_f), then relaxed (to the closest reachable foothold) when it fails;
///   5. the fallback of a kinematically infeasible foothold: the nearest feasible one
///      (planner/nearest_feasible_foothold.h), the relaxed OCP toward the target, or an error;
///      or, for any foothold not shown reachable (InfeasibleFootholdPolicy::kNearestReachable),
///      the nearest ring point that steps 2-4 certify, with a strict trajectory.
/// The passes follow PassSchedule::forStepPlanner (reach/sample_budget.h). With
/// ReachConfig::quick_pass, steps 1-5 run first with budgets.quick and again with budgets.full
/// only when the quick pass certified nothing or its certified step got no strict trajectory
/// (a quick certificate is kept when the full pass finds none; most of the walk's steps end
/// after the quick pass). Between the two, the quick pass's strict OCP is solved again, its
/// check and witness kept: first in its own hulls grown to
/// ReachConfig::quick_retry_constraint_margin (one OCP, no sampling), then
/// (ReachConfig::hull_pass) in the eq. (23) hulls of a forward set alone drawn with
/// budgets.hull.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/contact/contact_transition.h"
#include "reach_trajopt/ocp/ocp_config.h"
#include "reach_trajopt/ocp/transition_ocp.h"
#include "reach_trajopt/planner/kinematic_feasibility.h"
#include "reach_trajopt/planner/lipm.h"
#include "reach_trajopt/planner/nearest_feasible_foothold.h"
#include "reach_trajopt/reach/footstep_reachability.h"
#include "reach_trajopt/reach/reach_config.h"
#include "reach_trajopt/step/footstep_check.h"
#include "reach_trajopt/step/step_verdict.h"

namespace reach_trajopt {

class YamlSection;

/// Configurations of the pipeline's stages.
struct FootstepPlannerConfig {
  KinematicFeasibilityConfig kinematics;
  ReachConfig reach;  ///< the walk replaces its horizon by WalkConfig::check_horizon
  TransitionOcpConfig ocp;
  NearestFootholdConfig nearest_foothold;
  /// From a config file's root: its `kinematic_feasibility`, `reach`, `ocp` and
  /// `nearest_foothold` sections (each optional: defaults); ocp.terminal_pelvis_height is
  /// kinematics.pelvis_height. \throws ConfigError naming a bad key or value.
  static FootstepPlannerConfig fromYaml(const YamlSection& root);
};

/// What happens when the foothold fails the kinematic check.
enum class InfeasibleFootholdPolicy {
  kNearestFeasible,    ///< the nearest feasible foothold, its IK posture as x_f (OCP strict, then
                       ///< relaxed)
  kRelaxTowardTarget,  ///< the relaxed OCP toward the target, the IK's best posture as x_f
  kReject,             ///< a ReachError naming the IK's reason
  kNoFallback,         ///< no OCP; the foothold stays the target (the caller decides)
  /// Not only for an infeasible foothold: whenever the target is not certified (a certified
  /// target whose strict OCP fails stays the foothold, without a trajectory: its certificate's
  /// witness is the checked path), the nearest point of the rings of
  /// planner/nearest_feasible_foothold.h that is kinematically feasible and that the reachability
  /// check (steps 2-4, every pass) certifies with a strict trajectory, nearest first, at most
  /// NearestFootholdConfig::max_checked candidates checked, then
  /// NearestFootholdConfig::retreat_checks points toward the swing sole (the certified one
  /// nearest the target; before the rings for a kinematically infeasible target, whose ring
  /// points lie at the edge of the leg's reach), all of them within
  /// NearestFootholdConfig::time_limit (or the request's earlier deadline); a candidate solves no
  /// relaxed OCP unless it may be the answer. None certified: the target's own plan when it is
  /// kinematically feasible (its relaxed OCP, solved only then), else the nearest feasible
  /// candidate's (uncertified, its OCP strict then relaxed). Without a reachability check:
  /// kNearestFeasible.
  kNearestReachable,
};

/// Which OCP a kinematically feasible foothold gets.
enum class OcpPolicy {
  kByVerdict,  ///< strict when the witness is certified; else strict (the local solve), then
               ///< relaxed (Sec. III-E)
  kStrict,     ///< strict only
  kAuto,       ///< strict first, relaxed if it fails
};

/// One footstep to plan: its contact transition (contact_transition.h) as measured and planned
/// (the held sole `stance` where it stands, stance_contact; the planned foothold `target`, sole
/// centre [m] and heading [rad]; x_0 = (q0, qd0) [m, rad; m/s, rad/s]; `horizon`, t_f - t_0 of
/// the OCP [s], 0: the reachability horizon) and how to plan it. The transition's qf, qdf and
/// touchdown are not read: the planner builds x_f (step 2) from `touchdown_com`, and step 1
/// holds the stance sole where x_0 puts it.
struct FootstepPlanRequest : ContactTransition {
  FootstepPlanRequest() = default;
  /// The plan of `transition` (the other fields at their defaults).
  explicit FootstepPlanRequest(ContactTransition transition)
      : ContactTransition(std::move(transition)) {}

  /// The CoM's horizontal state predicted at touchdown (LIPM about the stance sole): x_f then
  /// has the pelvis where the CoM will have carried it, at its current height, and moves with
  /// the CoM's velocity with both soles still. None: the Sec. III-B posture at rest.
  std::optional<LipmState> touchdown_com;
  /// Step 1: move x_0 onto the stance contact manifold (a measured state). False: x_0 as given
  /// (the check rejects it when it violates the contact).
  bool make_contact_consistent = true;
  bool check_reachability = true;  ///< step 3 (false: kinematic check and OCP only)
  /// Step 4 (false: the checks only; for an infeasible foothold the nearest feasible one is
  /// still searched with kNearestFeasible). Without it nothing certifies by a local solve.
  bool solve_ocp = true;
  /// Reachability settings for this request (e.g. another horizon); none: the planner's.
  std::optional<ReachConfig> reach;
  OcpPolicy ocp_policy = OcpPolicy::kByVerdict;
  InfeasibleFootholdPolicy on_infeasible = InfeasibleFootholdPolicy::kNearestFeasible;
  /// Wall-clock time by which plan() should answer (e.g. the step's: the plan is needed before
  /// the foot lands); none: no limit. The passes after the first and kNearestReachable's
  /// candidates start only before it, and the OCP stops there (TransitionOcp's anytime solve:
  /// its best feasible iterate, or failed). A check running at the deadline stops before its
  /// next slice and shows nothing reachable ("not shown reachable", its kinematic stage kept;
  /// never a false "reachable"). The messages carry what is left of it (PlanFootstep
  /// time_budget).
  std::optional<std::chrono::steady_clock::time_point> deadline;
  /// The deadline has passed.
  bool pastDeadline() const { return deadline && std::chrono::steady_clock::now() >= *deadline; }
  /// More than `seconds` are left before the deadline (always without one). A pass or a
  /// candidate starts only when it has as long as a pass of this step took so far: one cut at
  /// the deadline shows nothing, and its first slice's draws (before the first deadline test)
  /// would make the answer late (the pushed demo walk paying for its plans: 10-13 ms).
  bool hasTimeFor(double seconds) const {
    return !deadline || std::chrono::steady_clock::now() +
                                std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                    std::chrono::duration<double>(seconds)) <
                            *deadline;
  }
};

/// What one footstep decided.
struct FootstepTransition {
  FootstepPlanRequest request;  ///< the request as given (for recorders and replays)
  bool kinematically_feasible = false;
  /// A checked path x_0 -> x_f exists (see `certificate`).
  bool reachable = false;
  /// What certifies `reachable` (kNone: not shown reachable).
  Certificate certificate = Certificate::kNone;
  /// kReachable, kUnreachable (not shown reachable), kKinematicallyFeasible (no reachability
  /// check) or kKinematicallyInfeasible.
  StepVerdict verdict = StepVerdict::kNotChecked;
  std::string reason;                ///< the check's and the OCP's explanations
  double hausdorff_distance = -1.0;  ///< smallest d_H over the window [m], -1 if not computed
  double check_time_s = 0.0;         ///< kinematic + reachability check wall time
  double ocp_time_s = 0.0;           ///< OCP wall time
  /// The passes that planned the step: 1 when the quick pass (ReachConfig::quick_pass) was
  /// final; otherwise one more for each of the wide hull retry
  /// (ReachConfig::quick_retry_constraint_margin), the hull pass (ReachConfig::hull_pass) and the
  /// full budget that ran, up to the one that ended it (at most 4). The times above are then
  /// the sums of every pass (the retry adds OCP time only).
  int check_passes = 1;
  TransitionResult trajectory;  ///< converged, relaxed or failed
  /// The full check (kinematics, reachable sets, witness) for recorders and the ROS layer.
  FootstepCheckResult check;
  /// The contact transition as checked: x_0 as used (contact-consistent), the held stance sole
  /// where x_0 has it (flat), the foothold checked, the horizon t_f - t_0 used [s], and what
  /// the check built x_f from (qdf zero: at rest; else `touchdown`). Its qf is the check's
  /// (check.kinematics.q_f).
  ContactTransition transition;
  /// Where the swing sole will land [m]: the OCP's landing when usable, else the nearest
  /// kinematically feasible foothold to the target (the target when it is feasible).
  Eigen::Vector3d foothold = Eigen::Vector3d::Zero();
  /// Where `foothold` came from: the target, a ring point (certified or not), the relaxed OCP.
  FootholdSource foothold_source = FootholdSource::kTarget;
  /// kNearestReachable: the candidates whose reachability was checked (0: the target passed).
  int candidates_checked = 0;
  /// kNearestReachable, when the foothold is not the target: the target's own verdict (the
  /// fields above are those of the foothold landed on).
  std::optional<StepVerdict> target_verdict;
  /// True when the trajectory may be tracked (OCP converged or relaxed).
  bool usable() const { return trajectory.status != OcpStatus::kFailed; }
};

/// Progress callbacks of FootstepTransitionPlanner::plan (any may be empty): the
/// reachability check's after each slice, the OCP's after each gradient evaluation. Either
/// returning false cancels the plan (ReachCancelled, common/cancelled.h). `pass` is told the
/// number of the pass that starts (1: the quick pass or the only one; then the wide hull retry,
/// the hull pass and the full budget, each when the one before was not final): the check and
/// the OCP report again in each pass that runs them.
struct FootstepPlanProgress {
  ReachProgressCallback check;
  OcpProgressCallback ocp;
  std::function<void(int)> pass;
};

/// @brief Kinematic check + reachability check + transition OCP of one footstep (Sec. III).
/// Immutable once set up; plan() may run concurrently.
class FootstepTransitionPlanner {
 public:
  /// \throws ReachError on invalid configs or unknown frames.
  FootstepTransitionPlanner(std::shared_ptr<const RobotModel> model, const ContactConfig& contact,
                            const FootstepPlannerConfig& config);

  /// Plans the swing from x_0 to the foothold (see the file comment).
  /// \throws ReachError on bad input (sizes, NaN, a target outside the workspace, a state the
  ///     check rejects) and, with InfeasibleFootholdPolicy::kReject, on an infeasible foothold.
  /// \param progress  where the check and the OCP report their progress (may be empty)
  FootstepTransition plan(const FootstepPlanRequest& request,
                          const FootstepPlanProgress& progress = {}) const;

  /// Where the nearest-feasible search checks each ring's candidates (e.g. worker nodes);
  /// empty (the default): in this process. The results do not depend on it. Set it before
  /// plan() runs, not while it runs.
  void setCandidateCheck(CandidateCheck check) { candidate_check_ = std::move(check); }

  /// Where steps 2-3 (the kinematic and the reachability check of the foothold) run, e.g.
  /// reachability_node's check_footstep; empty (the default): in this process, with the
  /// check's progress reports (a check elsewhere reports none). It must check as
  /// footstepReachability() does (same configuration) for the plans not to change. Set it
  /// before plan() runs, not while it runs.
  void setFootstepCheck(FootstepCheck check) { footstep_check_ = std::move(check); }

  /// Time from the check to touchdown [s] (the reachability horizon t_f - t_0).
  double horizon() const { return config_.reach.horizon; }
  const FootstepPlannerConfig& config() const { return config_; }
  const KinematicFeasibility& kinematics() const { return *kinematics_; }
  const ReachabilityAnalyzer& analyzer() const { return footsteps_.analyzer(); }
  /// The in-process footstep check of steps 2-3.
  const FootstepReachability& footstepReachability() const { return footsteps_; }

 private:
  /// When a pass's OCP for a kinematically feasible foothold may fall back to the relaxed
  /// problem (its OcpPolicy's choice) after the strict one fails.
  enum class RelaxedFallback {
    kAsRequested,    ///< as the request's OcpPolicy says
    kWhenCertified,  ///< only when the check certified the step (the quick pass: otherwise the
                     ///< passes that follow replace its trajectory)
    kNever,          ///< strict only (the retries and the nearest-reachable
                     ///< search's candidates, which only a strict trajectory ends)
  };
  /// plan() without the nearest-reachable search: the pass schedule for one target; its last
  /// pass's OCP falls back to the relaxed problem as `relaxed_fallback` says (the quick pass's
  /// only when certified, and never under kNever). `full_pass_ocp`, when given, gets the OCP
  /// request of the full pass when the answer is that pass's plan (else it is left empty), for
  /// solveDeferredRelaxed().
  FootstepTransition planTarget(const FootstepPlanRequest& r, const FootstepPlanProgress& progress,
                                RelaxedFallback relaxed_fallback = RelaxedFallback::kAsRequested,
                                std::optional<TransitionRequest>* full_pass_ocp = nullptr) const;
  /// The relaxed OCP that `step`'s plan left out (planned with RelaxedFallback::kNever) and its
  /// OcpPolicy asks for after a failed strict solve: solved now from `ocp` (the request of
  /// the pass `step` comes from) and merged into `step` as that pass would have (trajectory,
  /// foothold, its source, reason, certificate); nothing when `ocp` is empty or the policy
  /// does not ask for it. Returns the OCP's wall time it took [s].
  double solveDeferredRelaxed(const FootstepPlanRequest& r,
                              const std::optional<TransitionRequest>& ocp,
                              const FootstepPlanProgress& progress, FootstepTransition& step) const;
  /// InfeasibleFootholdPolicy::kNearestReachable (see there); the times and passes of every
  /// plan it made are summed in the answer.
  FootstepTransition planNearestReachable(const FootstepPlanRequest& r,
                                          const FootstepPlanProgress& progress) const;
  /// Step 1 of a pass of `horizon` [s]: the request and the transition to check into `out`
  /// (x_0, the held sole, the target, the touchdown prediction); returns the held stance sole
  /// pose as measured (the OCP's).
  Eigen::Isometry3d startPass(const FootstepPlanRequest& r, double horizon,
                              FootstepTransition& out) const;
  /// Steps 1-5 with the check's configuration `reach` (one pass of plan()); the OCP's eq. (23)
  /// slices into `slices_used` when given.
  FootstepTransition planWith(const FootstepPlanRequest& r, const ReachConfig& reach,
                              const CheckPass& pass, const FootstepPlanProgress& progress,
                              RelaxedFallback relaxed_fallback = RelaxedFallback::kAsRequested,
                              std::vector<ReachableSlice>* slices_used = nullptr,
                              std::optional<TransitionRequest>* solved_ocp = nullptr) const;
  /// Step 1: x_0, the held sole and the target into `t`; returns the held stance sole pose.
  Eigen::Isometry3d initialState(const FootstepPlanRequest& r, ContactTransition& t) const;
  /// The LIPM's prediction at touchdown from x_0 of `t`: the pelvis position to hold [m] and
  /// the CoM velocity [m/s] (none, zero without r.touchdown_com).
  TouchdownPrediction predictTouchdown(const FootstepPlanRequest& r,
                                       const ContactTransition& t) const;
  /// Steps 2-3 for out.transition: the check and the OCP's slices of its forward set (eq. 23;
  /// empty without a reachability check); its wall time into time_s [s].
  FootstepCheckResult runCheck(const FootstepPlanRequest& r, const ReachConfig& reach,
                               const CheckPass& pass, const ReachProgressCallback& progress,
                               const FootstepTransition& out, double& time_s) const;
  /// Steps 2-3 into out.check and the verdict fields; returns the OCP's slices of the
  /// check's forward set (eq. 23; empty without a reachability check).
  std::vector<ReachableSlice> checkFoothold(const FootstepPlanRequest& r, const ReachConfig& reach,
                                            const CheckPass& pass,
                                            const ReachProgressCallback& progress,
                                            FootstepTransition& out) const;
  /// The check's fields of `out` (check, verdict, reason, d_H) from `check`; `checked`: the
  /// reachability check ran.
  static void recordCheck(FootstepCheckResult check, bool checked, FootstepTransition& out);
  /// The OCP of a pass ended as asked: not asked for, or strict and converged.
  static bool hasStrictTrajectory(const FootstepPlanRequest& r, const FootstepTransition& step);
  /// The passes planned and their summed times so far (plan()).
  struct PassTotals {
    int passes = 1;
    double check_time_s = 0.0, ocp_time_s = 0.0;
    /// The totals so far of a plan whose first part was `step`.
    static PassTotals of(const FootstepTransition& step) {
      return {step.check_passes, step.check_time_s, step.ocp_time_s};
    }
    /// Adds a pass's (or a candidate's) passes and times.
    void add(const FootstepTransition& step) {
      passes += step.check_passes;
      check_time_s += step.check_time_s;
      ocp_time_s += step.ocp_time_s;
    }
    /// The step returned carries the sums.
    void stampOn(FootstepTransition& step) const {
      step.check_passes = passes;
      step.check_time_s = check_time_s;
      step.ocp_time_s = ocp_time_s;
    }
  };
  /// A batch of candidate footholds for the swing of `t`: its stance sole held where it is, the
  /// IK started from x_0's posture with the touchdown's pelvis; no candidate yet.
  static FootholdCandidates candidateBatch(const ContactTransition& t);
  /// The kinematic check of `batch`'s candidates: through setCandidateCheck()'s function when
  /// set (the workers), else in this process (`stop_at_first_decisive`: as
  /// checkFootholdCandidates()).
  std::vector<CandidateOutcome> checkCandidates(const FootholdCandidates& batch,
                                                bool stop_at_first_decisive) const;
  /// planNearestReachable()'s retreat (see kNearestReachable):
  /// NearestFootholdConfig::retreat_checks points of the segment from the target (not certified) to
  /// the swing sole's position at x_0, by bisection; the certified one nearest the target (its
  /// strict trajectory), or none. From a kinematically infeasible target the bisection starts at
  /// the first of retreat_kinematic_points points that passes the kinematic check (and ends there
  /// when it is certified). `totals` and `checked` count every plan it made.
  std::optional<FootstepTransition> planRetreat(const FootstepPlanRequest& r,
                                                const FootstepPlanRequest& at,
                                                const FootstepTransition& target,
                                                const FootstepPlanProgress& progress,
                                                PassTotals& totals, int& checked) const;
  /// A retry of the quick pass's strict OCP (`pass`: the wide hull retry or the hull pass)
  /// when it applies; the step when it ended it, the sums of `totals` carried (updated with
  /// this pass's).
  std::optional<FootstepTransition> retryQuickOcp(
      const FootstepPlanRequest& r, const ReachConfig& reach, const ScheduledPass& pass,
      const CheckPass& quick_pass, const FootstepTransition& quick,
      std::vector<ReachableSlice>& quick_slices, const FootstepPlanProgress& progress,
      PassTotals& totals) const;
  /// The hull pass (ReachConfig::hull_pass): the quick pass's check and seed, its OCP solved
  /// again in the hulls of a forward set alone drawn with `hull_pass` (budgets.hull over the
  /// full budget), propagated up to the quick witness's junction.
  FootstepTransition solveInFullHulls(const FootstepPlanRequest& r, const ReachConfig& reach,
                                      const CheckPass& hull_pass, const FootstepTransition& quick,
                                      const FootstepPlanProgress& progress) const;
  /// The wide hull retry (ReachConfig::quick_retry_constraint_margin): the quick pass's check
  /// and seed, its strict OCP solved again in its own slices `quick_slices` grown by
  /// `extra_margin` [m]; no sample is drawn.
  FootstepTransition solveInGrownHulls(const FootstepPlanRequest& r,
                                       const FootstepTransition& quick,
                                       std::vector<ReachableSlice> quick_slices,
                                       double extra_margin,
                                       const FootstepPlanProgress& progress) const;
  /// Steps 4-5 of out.transition into out.trajectory and out.foothold, the stance sole held at
  /// `held`, the swing sole in `set_constraint`; the OCP request solved into `solved_ocp` when
  /// given (left as it is when no OCP is solved).
  void solveTransition(const FootstepPlanRequest& r, const Eigen::Isometry3d& held,
                       std::vector<ReachableSlice> set_constraint,
                       const OcpProgressCallback& progress, FootstepTransition& out,
                       RelaxedFallback relaxed_fallback = RelaxedFallback::kAsRequested,
                       std::optional<TransitionRequest>* solved_ocp = nullptr) const;
  /// The end of solveTransition() after the OCP: out.foothold and its source from
  /// out.trajectory (else `fallback_foothold`), the OCP's reason appended, the certificate.
  void finishTransition(const FootstepPlanRequest& r, const Eigen::Vector3d& fallback_foothold,
                        FootstepTransition& out) const;
  /// The verdict of a checked, kinematically feasible step from its witness and its OCP.
  void certify(FootstepTransition& out) const;

  std::shared_ptr<const RobotModel> model_;
  ContactConfig contact_;
  FootstepPlannerConfig config_;
  std::shared_ptr<const KinematicFeasibility> kinematics_;
  FootstepReachability footsteps_;
  NearestFeasibleFoothold nearest_;
  CandidateCheck candidate_check_;
  FootstepCheck footstep_check_;
  TransitionOcp ocp_;
};

}  // namespace reach_trajopt
