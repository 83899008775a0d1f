/// \file walking_experiment.cpp
/// The stepping loop: phases, the TVR call at lift-off, the LIPM CoM reference, touchdown by
/// measured contact, fall detection.

#include "reach_trajopt/walk/walking_experiment.h"

#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "reach_trajopt/common/config_fields.h"
#include "reach_trajopt/common/stopwatch.h"
#include "reach_trajopt/control/com_reference.h"
#include "reach_trajopt/control/swing_trajectory.h"
#include "reach_trajopt/control/transition_tracking.h"
#include "reach_trajopt/planner/double_support_velocity.h"
#include "reach_trajopt/planner/step_timing.h"
#include "reach_trajopt/sim/bullet_world.h"
#include "reach_trajopt/walk/standing_pose.h"

namespace reach_trajopt {

// ---- WalkConfig -------------------------------------------------------------------------------

void WalkConfig::validate() const {
  fields().checkRanges(*this);
  if (!(check_horizon < single_support_duration))
    throw ConfigError("WalkConfig: check_horizon must be shorter than single_support_duration");
  if (!(max_double_support_duration >= double_support_duration))
    throw ConfigError("WalkConfig: max_double_support_duration must be >= double_support_duration");
  if (!(max_single_support_duration >= min_single_support_duration))
    throw ConfigError(
        "WalkConfig: max_single_support_duration must be >= min_single_support_duration");
  requireFinite("WalkConfig: initial_com_velocity", initial_com_velocity);
  requireFinite("WalkConfig: midswing_push", midswing_push);
  policy.validate();
}

namespace {

using C = WalkConfig;

/// WalkConfig::fields(): the step's timing and the lift-off.
void addTimingFields(ConfigFields<C>& t) {
  t.add("steps", &C::steps, "", Range::nonNegative(), "footsteps to walk (touchdowns)")
      .add("single_support_duration", &C::single_support_duration, "s", Range::positive(),
           "nominal swing time")
      .add("double_support_duration", &C::double_support_duration, "s", Range::positive(),
           "weight transfer between steps")
      .choice("step_timing", &C::step_timing,
              {{"fixed", WalkConfig::StepTiming::kFixed},
               {"tvr_bounds", WalkConfig::StepTiming::kTvrBounds}},
              "swing duration: fixed (single_support_duration) or tvr_bounds (chosen at "
              "lift-off in [min_, max_single_support_duration] so that the TVR step fits "
              "the foot offset bounds; planner/step_timing.h)")
      .add("min_single_support_duration", &C::min_single_support_duration, "s", Range::positive(),
           "step_timing tvr_bounds: shortest swing (policies with a check: at least "
           "check_horizon + one tick)")
      .add("max_single_support_duration", &C::max_single_support_duration, "s", Range::positive(),
           "step_timing tvr_bounds: longest swing, >= min_single_support_duration")
      .choice("lift_off", &C::lift_off,
              {{"timed", WalkConfig::LiftOff::kTimed},
               {"capture_point", WalkConfig::LiftOff::kCapturePoint}},
              "when a double support ends: timed (double_support_duration) or "
              "capture_point (the double support steers the capture point to the periodic "
              "gait's lift-off point and lifts off there, or at once when it leaves the "
              "soles; between double_support_duration and max_double_support_duration)")
      .add("max_double_support_duration", &C::max_double_support_duration, "s", Range::positive(),
           "lift_off capture_point: longest double support, >= double_support_duration")
      .add("lift_off_capture_tolerance", &C::lift_off_capture_tolerance, "m", Range::positive(),
           "lift_off capture_point: the capture point this close to its lift-off point "
           "lets the swing sole lift off")
      .add("lift_off_capture_gain", &C::lift_off_capture_gain, "1/s", Range::positive(),
           "lift_off capture_point: the rate at which the double support steers the "
           "capture point")
      .add("lift_off_capture_feedback", &C::lift_off_capture_feedback, "",
           "lift_off capture_point: steer the measured capture point (the CoM reference "
           "restarts from the measured CoM state each tick) instead of the reference's own")
      .add("lift_off_exit_margin", &C::lift_off_exit_margin, "m", Range::nonNegative(),
           "lift_off capture_point: the capture point beyond the soles' box shrunk by this "
           "margin has left the soles (lift-off at once); 0: their edges")
      .add("lift_off_unloaded_force", &C::lift_off_unloaded_force, "N", Range::nonNegative(),
           "lift_off capture_point: after double_support_duration the sole in turn also lifts "
           "off once its measured normal force is below this (unloaded) and the capture point "
           "is within lift_off_unloaded_capture_tolerance of its lift-off point; 0: off")
      .add("lift_off_unloaded_capture_tolerance", &C::lift_off_unloaded_capture_tolerance, "m",
           Range::positive(),
           "lift_off_unloaded_force: the capture point this close to its lift-off point lets "
           "an unloaded sole lift off")
      .add("stepping_com_xy_weight", &C::stepping_com_xy_weight, "", Range::nonNegative(),
           "weight of the controller's horizontal CoM task while stepping (after the settle "
           "phase); 0: wbc.w_com_xy, the standing robot's")
      .add("ocp_swing_com_xy_weight", &C::ocp_swing_com_xy_weight, "", Range::nonNegative(),
           "the same while the swing tracks an OCP trajectory (swing=ocp); 0: wbc.w_com_xy");
}

/// WalkConfig::fields(): the swing, touchdown and standing posture before the walk.
void addSwingFields(ConfigFields<C>& t) {
  t.add("settle_duration", &C::settle_duration, "s", Range::nonNegative(),
        "initial standing before the first lift-off")
      .add("swing_height", &C::swing_height, "m", Range::nonNegative(),
           "swing apex above the ground")
      .add("touchdown_depth", &C::touchdown_depth, "m", Range::nonNegative(),
           "nominal swing end below the ground (touchdown by contact)")
      .add("ocp_touchdown_blend", &C::ocp_touchdown_blend, "s", Range::nonNegative(),
           "a swing tracking an OCP trajectory: its sole sinks to touchdown_depth below the "
           "trajectory's landing over this last part of it (0: lands on the OCP's sole)")
      .add("touchdown_force", &C::touchdown_force, "N", Range::positive(),
           "sole normal force that counts as touchdown")
      .add("late_touchdown", &C::late_touchdown, "s", Range::nonNegative(),
           "time past the nominal swing end before a fall is declared");
}

/// WalkConfig::fields(): the planning, the pushes, the end of a run.
void addExperimentFields(ConfigFields<C>& t) {
  t.add("check_horizon", &C::check_horizon, "s", Range::positive(),
        "policies with a check: the check and the OCP start this long before the nominal "
        "touchdown (replaces reach.horizon), < single_support_duration")
      .add("replan_fraction", &C::replan_fraction, "", Range::between(0.0, 1.0),
           "eq. (11) re-evaluated from the measured CoM during this fraction of the swing")
      .add("replan_tolerance", &C::replan_tolerance, "m", Range::nonNegative(),
           "after the swing's first plan, the step is planned again (eq. 11, the policy's check "
           "and OCP over the time left) when eq. (11)'s foothold from the measured CoM has "
           "moved this far from the one planned (a push); 0: never")
      .add("max_replans", &C::max_replans, "", Range::atLeast(0),
           "replan_tolerance: at most this many new plans per swing")
      .add("min_replan_horizon", &C::min_replan_horizon, "s", Range::positive(),
           "replan_tolerance: no new plan when less time is left to the nominal touchdown")
      .choice("plan_latency", &C::plan_latency,
              {{"pause", WalkConfig::PlanLatency::kPause},
               {"measured", WalkConfig::PlanLatency::kMeasured},
               {"fixed", WalkConfig::PlanLatency::kFixed}},
              "when a step's plan takes effect: pause (the simulation waits), measured (after "
              "its wall time in sim time), fixed (after fixed_plan_latency)")
      .add("fixed_plan_latency", &C::fixed_plan_latency, "s", Range::nonNegative(),
           "plan_latency fixed: the plan takes effect this long after its check starts")
      .add("plan_deadline_margin", &C::plan_deadline_margin, "s", Range::nonNegative(),
           "plan_latency measured: the planner's deadline is the nominal touchdown less this "
           "(its answer still takes effect before the foot lands)")
      .add("knee_bend", &C::knee_bend, "rad", Range::nonNegative(), "standing posture")
      .add("forward_speed", &C::forward_speed, "m/s", Range{},
           "desired CoM speed along x (drives p_des of eq. 11)")
      .add("initial_com_velocity", &C::initial_com_velocity, "m/s", "push at t = 0, feet still")
      .add("midswing_push", &C::midswing_push, "m/s",
           "push while walking: a change of the base's horizontal velocity at half swing of "
           "step midswing_push_step (a standing run: 1 s into its settle phase)")
      .add("midswing_push_step", &C::midswing_push_step, "", Range::atLeast(1),
           "the step midswing_push is applied in")
      .choice("first_swing", &C::first_swing,
              {{"capture_point", WalkConfig::FirstSwing::kFromCapturePoint},
               {"left", WalkConfig::FirstSwing::kLeft},
               {"right", WalkConfig::FirstSwing::kRight}},
              "the sole that swings first (right: SS-L comes first; capture_point: the side "
              "the capture point lies toward at lift-off)")
      .add("fall_pelvis_height", &C::fall_pelvis_height, "m", Range::positive(),
           "pelvis origin below this height = fall")
      .add("seed", &C::seed, "",
           "seed of every random draw of the run (replaces reach.seed in the walk)")
      .add("max_sim_time", &C::max_sim_time, "s", Range::between(1e-3, 3600.0),
           "hard stop (at most an hour of simulated time)");
}

}  // namespace

const ConfigFields<WalkConfig>& WalkConfig::fields() {
  static const ConfigFields<C> f = [] {
    ConfigFields<C> t("WalkConfig", "walk", "include/reach_trajopt/walk/walking_experiment.h",
                      "The walking experiment of Sec. IV. Step period T = "
                      "single_support_duration + double_support_duration (0.26 s < 2 t_s, as "
                      "the step map (12) needs).");
    t.custom(
        "policy", "string",
        [](const YamlSection& s, const std::string& k, C& c) {
          std::string spec;
          s.read(k, spec);
          try {
            c.policy = WalkingPolicy::parse(spec);
          } catch (const ReachError& e) {
            throw ConfigError(s.where(k) + ": " + e.what());
          }
        },
        [](const C& c) { return c.policy.name; }, "",
        "<preset>[,part=value...]: baseline (Sec. IV-A), unbounded, kinematic, proposed "
        "(Sec. IV-B); parts bounds, check, on_fail, swing (walk/walking_policy.h); it "
        "sets TvrConfig::heuristic_bounds");
    addTimingFields(t);
    addSwingFields(t);
    addExperimentFields(t);
    t.removed("mode",
              "walk.mode was replaced by walk.policy (a preset: baseline, "
              "unbounded, kinematic, proposed)");
    return t;
  }();
  return f;
}

WalkConfig WalkConfig::fromYaml(const YamlSection& s) { return fields().read(s); }

void WalkConfig::setPlanLatency(const std::string& value, const std::string& key) {
  if (value == "pause") {
    plan_latency = PlanLatency::kPause;
    return;
  }
  if (value == "measured") {
    plan_latency = PlanLatency::kMeasured;
    return;
  }
  constexpr double kMaxFixedLatency = 10.0;  // [s]
  char* end = nullptr;
  const double seconds = std::strtod(value.c_str(), &end);
  if (value.empty() || end != value.c_str() + value.size() || !(seconds >= 0.0) ||
      seconds > kMaxFixedLatency)
    throw ConfigError(key + ": expected pause, measured or a latency in [0, 10] s, got '" + value +
                      "'");
  plan_latency = PlanLatency::kFixed;
  fixed_plan_latency = seconds;
}

std::string WalkConfig::planLatencyName() const {
  switch (plan_latency) {
    case PlanLatency::kPause:
      return "pause";
    case PlanLatency::kMeasured:
      return "measured";
    case PlanLatency::kFixed:
      break;
  }
  std::ostringstream os;
  os << fixed_plan_latency;
  return os.str();
}

std::string WalkResult::summaryLine() const {
  std::ostringstream os;
  os.precision(4);
  os << "WALK mode=" << policy.name << " steps=" << steps << " fell=" << (fell ? "yes" : "no")
     << " sim_s=" << sim_time << " wall_s=" << wall_time
     << " max_touchdown_err_m=" << max_touchdown_error << " qp_failures=" << qp_failures
     << " end=" << end_reason;
  int replans = 0;
  for (const StepRecord& r : records) replans += r.replans;
  os << " replans=" << replans;
  if (policy.checksFoothold()) {
    int infeasible = 0, failed = 0, late = 0, nearest_feasible = 0, nearest_reachable = 0,
        relaxed = 0, clipped = 0;
    for (const StepRecord& r : records) {
      infeasible += r.verdict == StepVerdict::kKinematicallyInfeasible;
      failed += r.failed_check_action.has_value();
      late += r.plan_late;
      nearest_feasible += r.foothold_source == FootholdSource::kNearestFeasible;
      nearest_reachable += r.foothold_source == FootholdSource::kNearestReachable;
      relaxed += r.foothold_source == FootholdSource::kRelaxed;
      clipped += r.foothold_source == FootholdSource::kClippedToBounds;
    }
    os << " kinematically_infeasible=" << infeasible << " failed_checks=" << failed
       << " late_plans=" << late << " from_nearest_feasible=" << nearest_feasible
       << " from_nearest_reachable=" << nearest_reachable << " from_relaxed=" << relaxed
       << " from_clipped_to_bounds=" << clipped;
  }
  if (policy.check == WalkingPolicy::FootholdCheck::kReachability) {
    // The verdicts: every "reachable" rests on a certified witness; its OCP was strict.
    int reachable = 0, bridge = 0, local_solve = 0, reachable_converged = 0, unreachable = 0;
    for (const StepRecord& r : records) {
      reachable += r.verdict == StepVerdict::kReachable;
      bridge += r.certificate == Certificate::kBridge;
      local_solve += r.certificate == Certificate::kLocalSolve;
      reachable_converged +=
          r.verdict == StepVerdict::kReachable && r.ocp_status == OcpStatus::kConverged;
      unreachable += r.verdict == StepVerdict::kUnreachable;
    }
    os << " reachable=" << reachable << " bridge_certified=" << bridge
       << " local_solve_certified=" << local_solve
       << " reachable_ocp_converged=" << reachable_converged
       << " not_shown_reachable=" << unreachable;
  }
  os << " " << policy.definition();
  return os.str();
}

// ---- The loop ---------------------------------------------------------------------------------

struct WalkingExperiment::Impl {
  std::unique_ptr<FootstepTransitionPlanner> footsteps;  ///< policies with a check
  FootstepPlanFunction plan_footstep;  ///< who plans the checked steps (empty: footsteps)
  TvrProposalFunction propose;         ///< who proposes the contacts (empty: the loop)
  WalkConfig walk;
  TvrConfig tvr_config;
  ContactConfig contact;
  WbcConfig wbc_config;
  SimConfig sim_config;
  RobotConfig robot;
};

WalkingExperiment::WalkingExperiment(const RobotConfig& robot, const WalkConfig& walk,
                                     const TvrConfig& tvr, const ContactConfig& contact,
                                     const WbcConfig& wbc, const SimConfig& sim,
                                     const FootstepPlannerConfig* proposed)
    : impl_(std::make_unique<Impl>()) {
  robot.validate();
  model_ = robot.loadModel();
  walk.validate();
  tvr.validate();
  contact.validate();
  wbc.validate();
  sim.validate();
  const FootstepPlannerConfig defaults;
  const FootstepPlannerConfig& c = proposed ? *proposed : defaults;
  if (walk.policy.checksFoothold()) {
    ReachConfig reach = c.reach;
    reach.horizon = walk.check_horizon;
    reach.seed = walk.seed;  // the run's seed reaches the sampler (its only random draws)
    reach.validate();
    FootstepPlannerConfig planner = c;
    planner.reach = reach;
    impl_->footsteps = std::make_unique<FootstepTransitionPlanner>(model_, contact, planner);
  }
  impl_->walk = walk;
  impl_->tvr_config = tvr;
  impl_->contact = contact;
  impl_->wbc_config = wbc;
  // The pelvis is named once, in KinematicFeasibilityConfig.
  impl_->wbc_config.pelvis_frame = c.kinematics.pelvis_frame;
  impl_->sim_config = sim;
  // The robot's sole frames are named once, in ContactConfig.
  impl_->sim_config.left_sole_frame = contact.left_sole_frame;
  impl_->sim_config.right_sole_frame = contact.right_sole_frame;
  if (robot.sim_sole_boxes)
    impl_->sim_config.sole_box_size = Eigen::Vector3d(
        2.0 * contact.half_length, 2.0 * contact.half_width, robot.sim_sole_box_height);
  impl_->robot = robot;
}

WalkingExperiment::~WalkingExperiment() = default;

void WalkingExperiment::setFootstepPlanner(FootstepPlanFunction plan) {
  impl_->plan_footstep = std::move(plan);
}

void WalkingExperiment::setTvrProposer(TvrProposalFunction propose) {
  impl_->propose = std::move(propose);
}

const FootstepTransitionPlanner* WalkingExperiment::footstepPlanner() const {
  return impl_->footsteps.get();
}

namespace {

Eigen::Vector2d xy(const Eigen::Vector3d& v) { return v.head<2>(); }

/// How far inside the sole's edges the double support's pivot stays [m].
constexpr double kSupportMargin = 0.02;

}  // namespace

/// One run of the stepping loop: the phase machine DS (settle) -> SS -> DS -> SS ... over the
/// named parts (TVR step planning, the footstep check, the CoM reference, the swing source,
/// touchdown and fall detection). Lives for one run().
struct WalkingExperiment::Loop {
  enum class Phase { kSettle, kSingle, kDouble };

  Loop(const WalkingExperiment::Impl& impl, std::shared_ptr<const RobotModel> model,
       const std::function<void(const WalkTick&)>& on_tick,
       const std::function<void(const StepRecord&)>& on_step,
       const std::function<void(const StepRecord&, const FootstepTransition&)>& on_check);
  WalkResult run();

 private:
  /// A footstep's plan waiting for its latency to pass (WalkConfig::plan_latency).
  struct PendingPlan {
    bool active = false;
    double ask_time = 0.0;  ///< sim time of the check's start: the trajectory's t = 0 [s]
    double apply_at = 0.0;  ///< sim time it takes effect [s]
    Eigen::Vector2d foothold = Eigen::Vector2d::Zero();
    bool track_ocp = false;
    TransitionResult trajectory;
  };
  static TvrConfig plannerConfig(const TvrConfig& tvr, const WalkConfig& wc, double com_height);
  void measure();
  /// Phase transitions; false when the run ends here.
  bool updatePhase(double t);
  bool singleSupport(double t);
  /// WalkConfig::FirstSwing::kFromCapturePoint's choice from the measured CoM state.
  Side firstSwingSide() const;
  void beginSingleSupport(double t);
  /// The sole that lifts off now (WalkConfig::lift_off), `time_in_double` [s] into the double
  /// support; none while the double support goes on.
  std::optional<Side> liftOff(double time_in_double) const;
  /// lift_off capture_point: where the capture point should be at lift-off [m].
  Eigen::Vector2d liftOffCapturePoint() const;
  /// The box around both soles the double support's pivot stays in [m].
  void supportBox(Eigen::Vector2d& box_min, Eigen::Vector2d& box_max) const;
  Eigen::Vector2d soleXy(Side side) const;
  /// The simulator reports `side`'s sole in contact with a normal force above `force_n` [N]
  /// (the contact events: a touchdown, a sole the double support has not emptied).
  bool soleCarries(Side side, double force_n) const;
  /// The measured instantaneous capture point, CoM + CoM velocity / omega (eq. 9) [m].
  Eigen::Vector2d capturePoint() const;
  /// Applies WalkConfig::midswing_push (once per run) and measures the pushed state.
  void pushOnce();
  /// The swing's duration by WalkConfig::step_timing, from the measured CoM state at lift-off.
  double swingDuration(double t) const;
  void planStep(double t, double time_in_swing);
  /// The policy's check and OCP from the measured state; `replanning`: a new plan during the
  /// swing, over the time left to the nominal touchdown (their horizon). Returns false when a
  /// replan's plan is not taken (it has no OCP trajectory while the swing tracks one, or the
  /// check threw): the swing keeps the plan it has.
  bool checkStep(double t, double time_in_swing, bool replanning = false);
  /// WalkConfig::replan_tolerance: eq. (11)'s foothold from the measured CoM state has moved
  /// from the one planned (`time_in_swing` [s] into the swing).
  bool disturbed(double t, double time_in_swing) const;
  /// Plans the step again `time_in_swing` [s] into the swing (eq. 11, then the policy's check).
  void replan(double t, double time_in_swing);
  /// The check's plan as the policy takes it: the foothold, and the OCP's trajectory to track
  /// or not (on_fail); records a failed check's action.
  PendingPlan decidePlan(const FootstepTransition& step, double t);
  /// The last resort of every policy with a check, when it has no plan to follow (its fallback
  /// found nothing, or the check threw): the TVR step clipped to the heuristic bounds (whatever
  /// the policy's `bounds`), reached by interpolation; records it as the foothold's source.
  PendingPlan clippedToBoundsPlan(double t);
  /// A plan that arrives after the nominal touchdown is dropped: the step goes on to where its
  /// swing goes (swingTarget()), and its record says so.
  void dropLatePlan();
  /// The plan's latency in sim time by WalkConfig::plan_latency [s] (`wall_s`: its wall time).
  double planLatency(double wall_s) const;
  /// The plan in effect from sim time `t` [s]: the step aims at its foothold (the record's
  /// `planned`), the swing tracks the OCP's trajectory or goes to the foothold.
  void applyPlan(PendingPlan& plan, double t);
  /// A pending plan whose time has come takes effect (each single-support tick).
  void applyPendingPlan(double t);
  FootstepPlanRequest footstepRequest(double time_in_swing, bool replanning) const;
  void recordCheck(const FootstepTransition& step);
  void touchdown(double t);
  void references(double t);
  /// False when the robot fell.
  bool controlAndStep(double t);
  /// Ends the run as a fall; the step in progress (single support) joins the records.
  void fall(const std::string& reason);
  Eigen::Vector3d target3() const {
    return Eigen::Vector3d(current_.planned.x(), current_.planned.y(), ground_z_);
  }
  /// The TVR step clipped to the heuristic bounds: every policy's last resort.
  Eigen::Vector2d clippedToBounds() const {
    return planner_.boundedContact(current_.planned_tvr, current_.stance, 0.0, swing_);
  }
  /// Where the swing goes until its plan takes effect. Paying for the plan's latency, a
  /// checked policy's swing goes to its last resort (the TVR step clipped to the heuristic
  /// bounds), not to an unchecked TVR step that can be out of the leg's reach: the plan arrives
  /// late in the swing (0.16 s of 0.22 s in the demo walk), too late to bring a sole back from
  /// there (after half-swing pushes of 0.6 m/s, "no touchdown" at the next step). Pausing,
  /// the plan takes effect when it is asked for: the proposal.
  Eigen::Vector3d swingTarget() const {
    if (wc_.plan_latency == WalkConfig::PlanLatency::kPause || !impl_.footsteps) return target3();
    const Eigen::Vector2d last_resort = clippedToBounds();
    return Eigen::Vector3d(last_resort.x(), last_resort.y(), ground_z_);
  }

  const WalkingExperiment::Impl& impl_;
  const WalkConfig& wc_;
  std::shared_ptr<const RobotModel> model_;
  const RobotModel& m_;
  const std::function<void(const WalkTick&)>& on_tick_;
  const std::function<void(const StepRecord&)>& on_step_;
  const std::function<void(const StepRecord&, const FootstepTransition&)>& on_check_;
  FrameId sole_[2];
  FrameId pelvis_;
  Workspace ws_, ws_traj_;
  Matrix6Xd J_traj_;  ///< swing sole Jacobian of the tracked trajectory (scratch)
  Eigen::VectorXd q0_;
  std::unique_ptr<BulletWorld> world_;
  double dt_ = 0.0;
  Eigen::Vector3d com0_;
  TvrPlanner planner_;
  LipmComReference com_ref_;
  WholeBodyController wbc_;
  Eigen::Matrix3Xd Jc_;

  Phase phase_ = Phase::kSettle;
  double phase_start_ = 0.0;
  Side swing_;
  ContactMode mode_ = ContactMode::doubleSupport();
  Eigen::Vector2d feet_mid_ = Eigen::Vector2d::Zero();
  double ground_z_ = 0.0;
  std::unique_ptr<SwingTrajectory> swing_traj_;
  bool pushed_ = false;          ///< WalkConfig::midswing_push was applied
  bool initiating_ = false;      ///< the double support before the first lift-off
  double swing_duration_ = 0.0;  ///< this swing's duration (WalkConfig::step_timing) [s]
  StepRecord current_;
  bool checked_ = false;      ///< this swing's footstep check has run
  TransitionResult tracked_;  ///< the OCP trajectory tracked (empty when none)
  double tracked_start_ = 0.0;
  PendingPlan pending_;
  WbcReference ref_;
  WalkResult result_;
  // The measured state of the current tick.
  Eigen::Vector3d com_ = Eigen::Vector3d::Zero(), vcom_ = Eigen::Vector3d::Zero();
};

WalkingExperiment::Loop::Loop(
    const WalkingExperiment::Impl& impl, std::shared_ptr<const RobotModel> model,
    const std::function<void(const WalkTick&)>& on_tick,
    const std::function<void(const StepRecord&)>& on_step,
    const std::function<void(const StepRecord&, const FootstepTransition&)>& on_check)
    : impl_(impl),
      wc_(impl.walk),
      model_(model),
      m_(*model),
      on_tick_(on_tick),
      on_step_(on_step),
      on_check_(on_check),
      sole_{m_.frameId(impl.contact.left_sole_frame), m_.frameId(impl.contact.right_sole_frame)},
      pelvis_(m_.frameId(impl.wbc_config.pelvis_frame)),
      ws_(m_),
      ws_traj_(m_),
      J_traj_(6, m_.nq()),
      q0_(standingConfiguration(m_, wc_.knee_bend, impl.contact.left_sole_frame, impl.robot)),
      com0_([&] {
        m_.update(ws_, q0_, Eigen::VectorXd::Zero(m_.nq()));
        return m_.centerOfMass(ws_);
      }()),
      planner_(plannerConfig(impl.tvr_config, wc_, com0_.z())),
      com_ref_(planner_.lipm(), com0_),
      wbc_(model_, impl.contact, impl.wbc_config, q0_),
      Jc_(3, m_.nq()),
      swing_(wc_.first_swing == WalkConfig::FirstSwing::kLeft ? Side::kLeft : Side::kRight) {
  const Eigen::VectorXd qd0 =
      doubleSupportBaseVelocity(m_, q0_, sole_[0], sole_[1], wc_.initial_com_velocity);
  world_ = BulletWorld::fromUrdfFile(impl.robot.urdfPath(), m_, impl.sim_config);
  world_->reset(q0_, qd0);
  dt_ = world_->timeStep();
  result_.policy = wc_.policy;
  ref_.posture = q0_;
}

TvrConfig WalkingExperiment::Loop::plannerConfig(const TvrConfig& tvr, const WalkConfig& wc,
                                                 double com_height) {
  TvrConfig c = tvr;
  c.com_height = com_height;  // the LIPM height is the robot's standing CoM height
  c.heuristic_bounds = wc.policy.heuristic_bounds;
  return c;
}

WalkResult WalkingExperiment::Loop::run() {
  const auto wall_start = SteadyClock::now();
  const int max_ticks = static_cast<int>(std::ceil(wc_.max_sim_time / dt_));
  result_.end_reason = "time limit";
  for (int tick = 0; tick < max_ticks; ++tick) {
    const double t = tick * dt_;
    measure();
    if (!updatePhase(t)) break;
    references(t);
    if (!controlAndStep(t)) break;
  }
  result_.wall_time = secondsSince(wall_start);
  return result_;
}

void WalkingExperiment::Loop::measure() {
  m_.update(ws_, world_->q(), world_->qd());
  com_ = m_.centerOfMass(ws_);
  m_.centerOfMassJacobian(ws_, Jc_);
  vcom_ = Jc_ * world_->qd();
}

bool WalkingExperiment::Loop::updatePhase(double t) {
  if (phase_ == Phase::kSettle && wc_.steps == 0 && t >= std::min(1.0, 0.5 * wc_.settle_duration))
    pushOnce();
  if (phase_ == Phase::kSettle && t >= wc_.settle_duration) {
    if (result_.steps >= wc_.steps) {
      result_.end_reason = "completed";
      return false;
    }
    feet_mid_ = 0.5 * (soleXy(Side::kLeft) + soleXy(Side::kRight));
    if (wc_.first_swing == WalkConfig::FirstSwing::kFromCapturePoint) swing_ = firstSwingSide();
    if (wc_.lift_off == WalkConfig::LiftOff::kTimed) {
      beginSingleSupport(t);
    } else {  // gait initiation: the pivot under the swing sole shifts the weight to the stance
      phase_ = Phase::kDouble;
      phase_start_ = t;
      initiating_ = true;
      com_ref_.startDoubleSupport(LipmState{xy(com_), xy(vcom_)}, soleXy(swing_), soleXy(swing_));
    }
  } else if (phase_ == Phase::kSingle) {
    return singleSupport(t);
  } else if (phase_ == Phase::kDouble) {
    const std::optional<Side> lifting = liftOff(t - phase_start_);
    if (!lifting) return true;
    if (result_.steps >= wc_.steps) {
      result_.end_reason = "completed";
      return false;
    }
    swing_ = *lifting;
    initiating_ = false;
    beginSingleSupport(t);
  }
  return true;
}

std::optional<Side> WalkingExperiment::Loop::liftOff(double time_in_double) const {
  // The sole in turn: the one that did not just land (at gait initiation, the one chosen).
  const Side in_turn = initiating_ ? swing_ : opposite(swing_);
  if (wc_.lift_off == WalkConfig::LiftOff::kTimed) {
    if (time_in_double >= wc_.double_support_duration) return in_turn;
    return std::nullopt;
  }
  if (!initiating_ && time_in_double < wc_.double_support_duration) return std::nullopt;
  if (time_in_double >= wc_.max_double_support_duration) return in_turn;
  const Eigen::Vector2d capture = capturePoint();
  Eigen::Vector2d box_min, box_max;
  supportBox(box_min, box_max);
  // The soles' box up to their edges, shrunk by lift_off_exit_margin.
  const Eigen::Vector2d exit_margin =
      Eigen::Vector2d::Constant(kSupportMargin - wc_.lift_off_exit_margin);
  box_min -= exit_margin;
  box_max += exit_margin;
  if ((capture.array() < box_min.array()).any() || (capture.array() > box_max.array()).any()) {
    // Only a step can catch it: with the sole on the side it leaves toward.
    const Side toward = capture.y() > 0.5 * (soleXy(Side::kLeft).y() + soleXy(Side::kRight).y())
                            ? Side::kLeft
                            : Side::kRight;
    // Leaving forward or backward, after a touchdown: the sole in turn (the one that just
    // landed carries the weight it took over and cannot lift at once).
    const bool sideways = capture.y() < box_min.y() || capture.y() > box_max.y();
    return sideways || initiating_ ? toward : in_turn;
  }
  const Eigen::Vector2d target = liftOffCapturePoint();
  const double dx = std::isfinite(target.x()) ? capture.x() - target.x() : 0.0;
  const double gap = std::hypot(dx, capture.y() - target.y());
  if (gap <= wc_.lift_off_capture_tolerance) return in_turn;
  // A sole the double support has emptied (a contact event) lifts off with the capture point
  // near enough: held on, it carries nothing and can leave the ground under the QP.
  if (!initiating_ && wc_.lift_off_unloaded_force > 0.0 &&
      gap <= wc_.lift_off_unloaded_capture_tolerance) {
    if (!soleCarries(in_turn, wc_.lift_off_unloaded_force)) return in_turn;
  }
  return std::nullopt;
}

Eigen::Vector2d WalkingExperiment::Loop::liftOffCapturePoint() const {
  // The next swing is the sole that is not the next stance: after a touchdown, the old stance.
  const Side next_swing = initiating_ ? swing_ : opposite(swing_);
  const Eigen::Vector2d stance = soleXy(opposite(next_swing)),
                        mid = 0.5 * (stance + soleXy(next_swing));
  // The periodic LIPM gait: lift-off with the capture point tanh(omega T / 2) of the way from
  // the midpoint to the stance sole (heading 0).
  const double omega = planner_.lipm().omega();
  const double fraction = std::tanh(0.5 * omega * wc_.single_support_duration);
  // Walking in place, both axes; walking at a speed, the lateral one (the sagittal capture
  // point is held: the walk's speed is the TVR steps').
  const Eigen::Vector2d target = mid + fraction * (stance - mid);
  return Eigen::Vector2d(
      wc_.forward_speed == 0.0 ? target.x() : std::numeric_limits<double>::quiet_NaN(), target.y());
}

void WalkingExperiment::Loop::supportBox(Eigen::Vector2d& box_min, Eigen::Vector2d& box_max) const {
  const Eigen::Vector2d half(impl_.contact.half_length - kSupportMargin,
                             impl_.contact.half_width - kSupportMargin);
  box_min = soleXy(Side::kLeft).cwiseMin(soleXy(Side::kRight)) - half;
  box_max = soleXy(Side::kLeft).cwiseMax(soleXy(Side::kRight)) + half;
}

void WalkingExperiment::Loop::pushOnce() {
  if (pushed_ || wc_.midswing_push.isZero(0.0)) return;
  pushed_ = true;
  world_->pushBase(Eigen::Vector3d(wc_.midswing_push.x(), wc_.midswing_push.y(), 0.0));
  measure();
}

Eigen::Vector2d WalkingExperiment::Loop::soleXy(Side side) const {
  return xy(m_.framePose(ws_, sole_[static_cast<int>(side)]).translation());
}

bool WalkingExperiment::Loop::soleCarries(Side side, double force_n) const {
  const SoleContact& sole = world_->soleContacts()[static_cast<int>(side)];
  return sole.in_contact && sole.wrench[2] > force_n;
}

Side WalkingExperiment::Loop::firstSwingSide() const {
  // The capture point's lateral offset from the soles' midpoint, in the stance heading (the
  // walk starts facing +x).
  const double offset = capturePoint().y() - feet_mid_.y();
  return offset > 0.01 ? Side::kLeft : Side::kRight;
}

Eigen::Vector2d WalkingExperiment::Loop::capturePoint() const {
  return xy(com_) + xy(vcom_) / planner_.lipm().omega();
}

bool WalkingExperiment::Loop::singleSupport(double t) {
  const double ts = t - phase_start_;
  if (ts < wc_.replan_fraction * swing_duration_) {
    planStep(t, ts);
    swing_traj_->retarget(swingTarget(), ts);
  }
  if (impl_.footsteps && !checked_ && ts >= swing_duration_ - impl_.footsteps->horizon())
    checkStep(t, ts);
  applyPendingPlan(t);
  if (current_.index == wc_.midswing_push_step && ts >= 0.5 * swing_duration_) pushOnce();
  if (disturbed(t, ts)) replan(t, ts);
  if (ts > 0.5 * swing_duration_ && soleCarries(swing_, wc_.touchdown_force)) {
    touchdown(t);
  } else if (ts > swing_duration_ + wc_.late_touchdown) {
    fall("no touchdown of the swing sole");
    return false;
  }
  return true;
}

void WalkingExperiment::Loop::beginSingleSupport(double t) {
  phase_ = Phase::kSingle;
  phase_start_ = t;
  mode_ = ContactMode::singleSupport(opposite(swing_));
  const Side stance = opposite(swing_);
  const Eigen::Vector3d stance_pos =
      m_.framePose(ws_, sole_[static_cast<int>(stance)]).translation();
  const Eigen::Vector3d swing_pos =
      m_.framePose(ws_, sole_[static_cast<int>(swing_)]).translation();
  current_ = StepRecord();
  current_.index = result_.steps + 1;
  current_.swing = swing_;
  current_.stance = xy(stance_pos);
  ground_z_ = stance_pos.z();
  swing_duration_ = swingDuration(t);
  current_.swing_duration = swing_duration_;
  planStep(t, 0.0);
  swing_traj_ = std::make_unique<SwingTrajectory>(swing_pos, swingTarget(), swing_duration_,
                                                  wc_.swing_height, wc_.touchdown_depth);
  com_ref_.startSingleSupport(current_.com_at_plan, current_.stance);
  checked_ = false;
  tracked_ = TransitionResult();
  pending_ = PendingPlan();
}

bool WalkingExperiment::Loop::disturbed(double t, double ts) const {
  if (wc_.replan_tolerance <= 0.0 || current_.replans >= wc_.max_replans) return false;
  // After the swing's first plan: the check's, or the end of the replan_fraction window.
  if (impl_.footsteps ? !checked_ : ts < wc_.replan_fraction * swing_duration_) return false;
  const double remaining = swing_duration_ - ts;
  if (remaining < wc_.min_replan_horizon) return false;
  // The in-process eq. (11), whoever proposes the steps (it is the same planner): a tick's
  // closed form, not a request per tick.
  const TvrStep now =
      planner_.planFromMeasured(LipmState{xy(com_), xy(vcom_)}, current_.stance, current_.swing, t,
                                remaining, com0_.x(), wc_.forward_speed, feet_mid_.y());
  return (now.alpha_tvr - current_.planned_tvr).norm() > wc_.replan_tolerance;
}

void WalkingExperiment::Loop::replan(double t, double ts) {
  ++current_.replans;
  if (!impl_.footsteps) {
    planStep(t, ts);
    swing_traj_->retarget(target3(), ts);
    return;
  }
  const StepRecord before = current_;
  planStep(t, ts);
  // Paying for its latency, the swing goes where it goes before a step's first plan (now from
  // the new proposal) until the checked plan arrives, and the plan it waited for, computed
  // before the disturbance, is superseded: kept, it would take the swing back there.
  const bool interim =
      wc_.plan_latency != WalkConfig::PlanLatency::kPause && tracked_.time.size() == 0;
  if (interim) {
    pending_ = PendingPlan();
    swing_traj_->retarget(swingTarget(), ts);
  }
  // A swing that tracks an OCP trajectory keeps it when the new plan has none to track (its
  // check or OCP failed: the interpolated swing cannot start from the tracked sole's state),
  // and any swing keeps its plan when the check threw.
  if (!checkStep(t, ts, true)) {
    const std::string why = current_.reason;
    current_ = before;
    current_.reason += "; replanned " + std::to_string(ts) + " s into the swing, not taken: " + why;
    if (interim) swing_traj_->retarget(swingTarget(), ts);
  }
}

double WalkingExperiment::Loop::swingDuration(double t) const {
  if (wc_.step_timing == WalkConfig::StepTiming::kFixed) return wc_.single_support_duration;
  StepTimingRange range;
  range.nominal = wc_.single_support_duration;
  range.min = std::min(wc_.single_support_duration, wc_.min_single_support_duration);
  // A checked step's check and OCP start check_horizon before touchdown, after lift-off.
  if (impl_.footsteps) range.min = std::max(range.min, impl_.footsteps->horizon() + dt_);
  range.min = std::min(range.min, range.nominal);
  range.max = std::max(wc_.single_support_duration, wc_.max_single_support_duration);
  const Eigen::Vector2d stance = soleXy(opposite(swing_));
  return adaptStepTiming(planner_, LipmState{xy(com_), xy(vcom_)}, stance, swing_, t, com0_.x(),
                         wc_.forward_speed, feet_mid_.y(), range)
      .swing_duration;
}

// Eq. (11) from the measured CoM state predicted to the nominal touchdown (LIPM about the
// stance sole). Called at lift-off and again during the first part of the swing, so that the
// footstep follows the measured state rather than a single prediction.
void WalkingExperiment::Loop::planStep(double t, double time_in_swing) {
  current_.com_at_plan.p = xy(com_);
  current_.com_at_plan.pd = xy(vcom_);
  current_.plan_time = t;
  const double remaining = std::max(0.0, swing_duration_ - time_in_swing);
  TvrProposal proposal;
  if (impl_.propose) {
    TvrProposalRequest request;
    request.measured = current_.com_at_plan;
    request.stance = current_.stance;
    request.swing = current_.swing;
    request.time = t;
    request.remaining = remaining;
    request.x_start = com0_.x();
    request.forward_speed = wc_.forward_speed;
    request.y_mid = feet_mid_.y();
    request.com_height = planner_.config().com_height;
    request.heuristic_bounds = planner_.config().heuristic_bounds;
    proposal = impl_.propose(request);
  } else {
    proposal.step = planner_.planFromMeasured(current_.com_at_plan, current_.stance, current_.swing,
                                              t, remaining, com0_.x(), wc_.forward_speed,
                                              feet_mid_.y(), &proposal.input);
  }
  current_.com_predicted = proposal.input.com;
  current_.planned_tvr = proposal.step.alpha_tvr;
  current_.planned = proposal.step.alpha;
  current_.offset_clipped = proposal.step.offset_clipped;
}

// The policy's footstep check (in process or through setFootstepPlanner's function); the
// simulation waits (in sim time) for it and the OCP.
bool WalkingExperiment::Loop::checkStep(double t, double ts, bool replanning) {
  checked_ = true;
  try {
    const auto wall_start = SteadyClock::now();
    FootstepPlanRequest request = footstepRequest(ts, replanning);
    // Paying for the plan's wall time, the planner knows its deadline: the nominal touchdown,
    // as far away in wall time as it is in sim time (a later plan would be dropped), less the
    // margin its answer needs to take effect before then.
    if (wc_.plan_latency == WalkConfig::PlanLatency::kMeasured)
      request.deadline = secondsAfter(
          wall_start, std::max(0.0, phase_start_ + swing_duration_ - t - wc_.plan_deadline_margin));
    const FootstepTransition step =
        impl_.plan_footstep ? impl_.plan_footstep(request) : impl_.footsteps->plan(request);
    const double wall_s = secondsSince(wall_start);
    recordCheck(step);
    PendingPlan plan = decidePlan(step, t);
    if (replanning && !plan.track_ocp && tracked_.time.size() > 0) return false;
    const double latency = planLatency(wall_s);
    current_.plan_latency_s = latency;
    if (latency <= 0.0) {  // the simulation waited for the plan
      applyPlan(plan, t);
      if (on_check_) on_check_(current_, step);
      return true;
    }
    if (on_check_) on_check_(current_, step);
    // A plan that pays its latency gives its foothold, not its trajectory: the OCP starts from
    // the state at the check's start, which the robot leaves while it follows the swing it has.
    // Tracked from where it would be by then, its joint feed-forward pulls the whole body to
    // another state: the pushed demo walk fell within 12 steps with 0.05 s of fixed latency (88
    // failed controller QPs; blending the references into the trajectory over 0.05-0.1 s did
    // not help), and walks its 20 steps, no failed QP, when the swing goes to the foothold.
    plan.track_ocp = false;
    plan.trajectory = TransitionResult();
    plan.apply_at = t + latency;
    // Its deadline is the nominal touchdown: a later plan is dropped.
    if (plan.apply_at > phase_start_ + swing_duration_) {
      dropLatePlan();
      return true;
    }
    plan.active = true;
    pending_ = std::move(plan);
    return true;
  } catch (const ReachError& e) {
    // The measured state is outside what the check accepts (e.g. a hip joint beyond its
    // velocity limit after a push at half swing): no plan of the policy's. Unchecked, the TVR
    // step of an unbounded policy can be a metre away (0.6 m/s to the left at half swing: 1.06 m
    // outward, "no touchdown"); the step takes the last resort of a fallback that found nothing.
    current_.verdict = StepVerdict::kCheckError;
    current_.reason = e.what();
    if (replanning) return false;  // a replan that threw changes nothing
    PendingPlan plan = clippedToBoundsPlan(t);
    applyPlan(plan, t);
    return true;
  }
}

WalkingExperiment::Loop::PendingPlan WalkingExperiment::Loop::clippedToBoundsPlan(double t) {
  PendingPlan plan;
  plan.ask_time = t;
  plan.foothold = clippedToBounds();
  plan.track_ocp = false;
  current_.foothold_source = FootholdSource::kClippedToBounds;
  return plan;
}

void WalkingExperiment::Loop::dropLatePlan() {
  current_.plan_late = true;
  pending_ = PendingPlan();
  current_.planned = xy(swingTarget());
  current_.foothold_source = current_.planned == current_.planned_tvr
                                 ? FootholdSource::kTarget
                                 : FootholdSource::kClippedToBounds;
}

WalkingExperiment::Loop::PendingPlan WalkingExperiment::Loop::decidePlan(
    const FootstepTransition& step, double t) {
  const WalkingPolicy& policy = wc_.policy;
  // A ring point (nearest_reachable) stands in for a target that failed the check.
  const bool failed =
      step.target_verdict.has_value() || !step.kinematically_feasible ||
      (policy.check == WalkingPolicy::FootholdCheck::kReachability && !step.reachable);
  current_.foothold_source = step.foothold_source;
  PendingPlan plan;
  plan.ask_time = t;
  plan.foothold = xy(step.foothold);
  plan.track_ocp = policy.swing == WalkingPolicy::SwingSource::kOcp && step.usable();
  if (failed) {
    current_.failed_check_action = policy.on_failed_check;
    if (policy.clipsFailedStep(step)) plan = clippedToBoundsPlan(t);
  }
  if (plan.track_ocp) plan.trajectory = step.trajectory;
  return plan;
}

double WalkingExperiment::Loop::planLatency(double wall_s) const {
  switch (wc_.plan_latency) {
    case WalkConfig::PlanLatency::kPause:
      return 0.0;
    case WalkConfig::PlanLatency::kMeasured:
      return wall_s;
    case WalkConfig::PlanLatency::kFixed:
      return wc_.fixed_plan_latency;
  }
  return 0.0;
}

void WalkingExperiment::Loop::applyPlan(PendingPlan& plan, double t) {
  current_.planned = plan.foothold;
  if (plan.track_ocp) {
    tracked_ = std::move(plan.trajectory);
    tracked_start_ = plan.ask_time;
  } else {
    swing_traj_->retarget(Eigen::Vector3d(plan.foothold.x(), plan.foothold.y(), ground_z_),
                          t - phase_start_);
  }
}

void WalkingExperiment::Loop::applyPendingPlan(double t) {
  if (!pending_.active || t < pending_.apply_at) return;
  applyPlan(pending_, t);
  pending_ = PendingPlan();
}

// The check's request from the measured state, with the policy's parts.
FootstepPlanRequest WalkingExperiment::Loop::footstepRequest(double ts, bool replanning) const {
  const WalkingPolicy& policy = wc_.policy;
  const Side stance = opposite(swing_);
  FootstepPlanRequest request;
  request.stance = stance;
  request.stance_contact =
      FlatContact::fromPose(m_.framePose(ws_, sole_[static_cast<int>(stance)]));
  request.target = {target3(), request.stance_contact.yaw};  // the stance sole's heading
  request.q0 = world_->q();
  request.qd0 = world_->qd();
  // The CoM velocity at touchdown: the LIPM about the stance sole from the measured CoM
  // state, over the time left to the nominal touchdown.
  request.touchdown_com = planner_.lipm().propagate(LipmState{xy(com_), xy(vcom_)}, current_.stance,
                                                    std::max(0.0, swing_duration_ - ts));
  if (replanning) {  // the sets and the OCP over the time left to the nominal touchdown
    ReachConfig reach = impl_.footsteps->config().reach;
    reach.horizon = std::max(0.0, swing_duration_ - ts);
    request.reach = reach;
  }
  request.check_reachability = policy.check == WalkingPolicy::FootholdCheck::kReachability;
  request.solve_ocp = policy.solvesOcp();
  switch (policy.on_failed_check) {
    case WalkingPolicy::OnFailedCheck::kRelaxedOcp:
      request.on_infeasible = InfeasibleFootholdPolicy::kRelaxTowardTarget;
      request.ocp_policy = OcpPolicy::kByVerdict;  // strict (the local solve), then relaxed
      break;
    case WalkingPolicy::OnFailedCheck::kNearestFeasible:
      // The ring search for an infeasible foothold; an unreachable one (or a strict OCP that
      // failed) gets the relaxed OCP's closest reachable foothold.
      request.on_infeasible = InfeasibleFootholdPolicy::kNearestFeasible;
      request.ocp_policy = OcpPolicy::kByVerdict;
      break;
    case WalkingPolicy::OnFailedCheck::kNearestReachable:
      // Any foothold not shown reachable: the nearest certified ring point; none: as
      // kNearestFeasible (without a reachability check: kNearestFeasible itself).
      request.on_infeasible = InfeasibleFootholdPolicy::kNearestReachable;
      request.ocp_policy = OcpPolicy::kByVerdict;
      break;
    case WalkingPolicy::OnFailedCheck::kClipToBounds:
      request.on_infeasible = InfeasibleFootholdPolicy::kNoFallback;
      request.ocp_policy = OcpPolicy::kStrict;
      break;
  }
  return request;
}

void WalkingExperiment::Loop::recordCheck(const FootstepTransition& step) {
  // The proposed foothold's verdict; the certificate below is the foothold's landed on.
  current_.verdict = step.target_verdict.value_or(step.verdict);
  current_.hausdorff_distance = step.hausdorff_distance;
  current_.certificate = step.certificate;
  const WitnessPath& w = step.check.reach.witness;
  if (w.valid) {
    current_.witness_violation = w.violation.max();
    current_.junction_position_gap = w.position_gap;
    current_.junction_velocity_gap = w.velocity_gap;
    current_.terminal_position_gap = w.terminal_position_gap;
    current_.terminal_velocity_gap = w.terminal_velocity_gap;
  }
  current_.check_time_s = step.check_time_s;
  current_.ocp_time_s = step.ocp_time_s;
  current_.check_passes = step.check_passes;
  current_.ocp_status =
      wc_.policy.solvesOcp() ? std::optional<OcpStatus>(step.trajectory.status) : std::nullopt;
  current_.reason = step.reason;
}

void WalkingExperiment::Loop::touchdown(double t) {
  if (pending_.active) dropLatePlan();  // the sole landed before the plan arrived
  current_.touched_down = true;
  current_.touchdown_time = t;
  current_.executed = m_.framePose(ws_, sole_[static_cast<int>(swing_)]).translation();
  current_.touchdown_error = (xy(current_.executed) - current_.planned).norm();
  result_.max_touchdown_error = std::max(result_.max_touchdown_error, current_.touchdown_error);
  result_.records.push_back(current_);
  ++result_.steps;
  if (on_step_) on_step_(current_);
  phase_ = Phase::kDouble;
  phase_start_ = t;
  mode_ = ContactMode::doubleSupport();
  com_ref_.startDoubleSupport(LipmState{xy(com_), xy(vcom_)}, current_.stance,
                              xy(current_.executed));
}

void WalkingExperiment::Loop::references(double t) {
  if (phase_ == Phase::kSettle) {
    com_ref_.hold(ref_);
  } else if (phase_ == Phase::kDouble && wc_.lift_off == WalkConfig::LiftOff::kCapturePoint) {
    Eigen::Vector2d box_min, box_max;
    supportBox(box_min, box_max);
    // DCM feedback: the reference restarts from the measured CoM state, so the pivot follows
    // from the measured capture point.
    if (wc_.lift_off_capture_feedback) com_ref_.restart(LipmState{xy(com_), xy(vcom_)});
    com_ref_.steerCapturePoint(dt_, liftOffCapturePoint(), wc_.lift_off_capture_gain, box_min,
                               box_max, ref_);
  } else {
    const double transfer = phase_ == Phase::kDouble
                                ? std::min(1.0, (t - phase_start_) / wc_.double_support_duration)
                                : 1.0;
    com_ref_.advance(dt_, transfer, ref_);
  }
  // Stepping, the horizontal CoM task is stiffer than standing's (WalkConfig); less so while
  // the swing tracks an OCP trajectory, whose joint feed-forward carries the CoM motion it
  // planned.
  const bool tracking_ocp = phase_ == Phase::kSingle && tracked_.time.size() > 0;
  const double w = tracking_ocp ? wc_.ocp_swing_com_xy_weight : wc_.stepping_com_xy_weight;
  ref_.w_com_xy = phase_ != Phase::kSettle && w > 0.0 ? w : -1.0;
  ref_.q_ff.resize(0);
  ref_.qd_ff.resize(0);
  ref_.qdd_ff.resize(0);
  if (phase_ != Phase::kSingle) return;
  if (tracked_.time.size() > 0) {  // the OCP's swing sole, its joints as feed-forward
    trackTransition(m_, ws_traj_, J_traj_, sole_[static_cast<int>(swing_)], tracked_,
                    t - tracked_start_, TouchdownAim{wc_.touchdown_depth, wc_.ocp_touchdown_blend},
                    ref_);
  } else {
    const SwingSample sw = swing_traj_->sample(t - phase_start_);
    ref_.swing_position = sw.position;
    ref_.swing_velocity = sw.velocity;
    ref_.swing_acceleration = sw.acceleration;
    ref_.swing_rotation.setIdentity();
  }
}

bool WalkingExperiment::Loop::controlAndStep(double t) {
  const Eigen::VectorXd& q = world_->q();
  const Eigen::VectorXd& qd = world_->qd();
  const WbcOutput& out = wbc_.compute(q, qd, mode_, ref_);
  if (out.status != qp::QpStatus::kOptimal) ++result_.qp_failures;
  if (on_tick_) {
    WalkTick info;
    info.time = t;
    info.mode = mode_;
    info.q = &q;
    info.qd = &qd;
    info.com = com_;
    info.com_velocity = vcom_;
    info.com_reference = ref_.com_position;
    info.wbc = &out;
    info.soles = &world_->soleContacts();
    on_tick_(info);
  }
  world_->step(out.u);
  result_.sim_time = world_->time();
  // Fall detection, on the state measured at the start of the tick.
  const double pelvis_z = m_.framePose(ws_, pelvis_).translation().z();
  if (pelvis_z < wc_.fall_pelvis_height) {
    fall("pelvis below " + std::to_string(wc_.fall_pelvis_height) + " m");
    return false;
  }
  if (!world_->nonFootContacts().empty()) {
    fall("link '" + world_->nonFootContacts().front() + "' touched the ground");
    return false;
  }
  if (!world_->legContacts().empty()) {  // a robot's legs would have hit each other
    fall("legs collided (" + world_->legContacts().front() + ")");
    return false;
  }
  return true;
}

void WalkingExperiment::Loop::fall(const std::string& reason) {
  result_.fell = true;
  result_.end_reason = reason;
  if (phase_ == Phase::kSingle) result_.records.push_back(current_);  // the step it fell in
}

WalkResult WalkingExperiment::run(
    const std::function<void(const WalkTick&)>& on_tick,
    const std::function<void(const StepRecord&)>& on_step,
    const std::function<void(const StepRecord&, const FootstepTransition&)>& on_check) {
  Loop loop(*impl_, model_, on_tick, on_step, on_check);
  return loop.run();
}

}  // namespace reach_trajopt
