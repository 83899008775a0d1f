#pragma once
/// \file walking_experiment.h
/// The stepping loop of the paper's Sec. IV on the Bullet simulation: DS -> SS-L -> DS -> SS-R
/// -> ... At the start of every single support the TVR planner (eq. 11) proposes the next
/// contact from the simulated CoM state (predicted to touchdown with the LIPM, eq. 9-10); the
/// swing sole is taken there and the whole-body controller tracks the LIPM CoM reference about
/// the stance sole. What happens to the proposed foothold is the run's WalkingPolicy
/// (walking_policy.h): heuristic bounds, a check `WalkConfig::check_horizon` before the nominal
/// touchdown from the measured state, what a failed check does, and whether the swing is
/// interpolated or the OCP's trajectory tracked to touchdown with its feed-forward.
/// A run ends after the requested number of steps, or at a fall (pelvis below a height, a link
/// other than the feet touching the ground, or the legs colliding), with a per-step record.

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/contact/contact_mode.h"
#include "reach_trajopt/control/whole_body_controller.h"
#include "reach_trajopt/model/robot_config.h"
#include "reach_trajopt/planner/tvr_planner.h"
#include "reach_trajopt/planner/tvr_proposal.h"
#include "reach_trajopt/sim/bullet_world.h"
#include "reach_trajopt/sim/sim_config.h"
#include "reach_trajopt/step/footstep_transition_planner.h"
#include "reach_trajopt/step/step_verdict.h"
#include "reach_trajopt/walk/walking_policy.h"

namespace reach_trajopt {

class YamlSection;
template <typename Config>
class ConfigFields;

/// Parameters of a walking run. Durations [s], lengths [m], speeds [m/s].
struct WalkConfig {
  /// What happens to each TVR footstep (a preset name in the YAML, optionally with parts:
  /// "kinematic,swing=interpolation"); its check uses check_horizon.
  WalkingPolicy policy = WalkingPolicy::preset("baseline");
  int steps = 20;                         ///< footsteps to walk (touchdowns)
  double single_support_duration = 0.22;  ///< nominal swing time
  double double_support_duration = 0.04;  ///< weight transfer between steps
  /// When a double support ends. kTimed: after double_support_duration (the CoM reference the
  /// LIPM about a pivot moving from the old stance sole to the new one). kCapturePoint: the
  /// double support steers the capture point (control/com_reference.h) to where the periodic
  /// LIPM gait in place has it at lift-off (tanh(omega T_ss / 2) of the way from the soles'
  /// midpoint to the next stance sole), its pivot kept on the soles, and the swing sole lifts
  /// off once the measured capture point is within lift_off_capture_tolerance of it, after at
  /// least double_support_duration (none before the first step) and at most
  /// max_double_support_duration; a capture point that leaves the soles' box lifts off at once,
  /// with the sole on the side it leaves toward when it leaves sideways (only a step can catch
  /// it), the next sole in turn when it leaves forward or backward. As standing, the
  /// double support absorbs what the soles can; the first step starts from such a double
  /// support (gait initiation).
  enum class LiftOff { kTimed, kCapturePoint };
  LiftOff lift_off = LiftOff::kCapturePoint;
  double max_double_support_duration = 1.0;  ///< [s]
  double lift_off_capture_tolerance = 0.02;  ///< [m]
  double lift_off_capture_gain = 10.0;       ///< [1/s]
  /// lift_off kCapturePoint: the capture point steered is the measured one (the CoM reference
  /// restarts from the measured CoM state each tick: DCM feedback, the pivot from the measured
  /// capture point), not the reference's own LIPM started at touchdown (which the robot, loosely
  /// tracking it, left behind).
  bool lift_off_capture_feedback = true;
  /// lift_off kCapturePoint: the capture point counts as having left the soles (lift-off at
  /// once) when it is beyond their box shrunk by this margin [m]; 0: the sole edges, where the
  /// soles can no longer hold it.
  double lift_off_exit_margin = 0.0;
  /// lift_off kCapturePoint: after double_support_duration, the sole in turn also lifts off
  /// once its measured normal force is below this [N] (the double support has emptied it: a
  /// contact event, as touchdown_force is at the other end of the swing) while the capture
  /// point is within lift_off_unloaded_capture_tolerance of its lift-off point; 0: off. A sole
  /// emptied while the capture point stalls short of lift_off_capture_tolerance otherwise stays
  /// a held contact that carries nothing, and can leave the ground under the QP.
  double lift_off_unloaded_force = 30.0;
  double lift_off_unloaded_capture_tolerance = 0.05;  ///< [m]
  /// Weight of the whole-body controller's horizontal CoM task while stepping (every phase
  /// after the settle phase); 0: WbcConfig::w_com_xy (the standing robot's). Large enough that
  /// the QP realizes the reference's pivot instead of trading it for the posture.
  double stepping_com_xy_weight = 50.0;
  /// The same while the swing tracks an OCP trajectory (swing ocp): its joint feed-forward
  /// carries the CoM motion the OCP planned; 50 made the proposed preset's demo walk collide
  /// its legs at step 5, 10 did not and kept the kinematic preset's envelope. 0:
  /// WbcConfig::w_com_xy.
  double ocp_swing_com_xy_weight = 10.0;
  /// How long each swing lasts. kFixed: single_support_duration. kTvrBounds: chosen at lift-off
  /// in [min_single_support_duration, max_single_support_duration] so that the TVR step fits
  /// the foot offset bounds (planner/step_timing.h; Khadiv et al. 2016); the nominal duration
  /// when it fits there. Policies with a check swing at least check_horizon + one tick.
  enum class StepTiming { kFixed, kTvrBounds };
  StepTiming step_timing = StepTiming::kFixed;
  double min_single_support_duration = 0.15;  ///< shortest adapted swing [s]
  double max_single_support_duration = 0.35;  ///< longest adapted swing [s]
  double settle_duration = 0.2;               ///< initial standing before the first lift-off
  double swing_height = 0.07;                 ///< swing apex above the ground
  double replan_fraction = 0.0;               ///< eq. (11) is re-evaluated from the measured CoM
                                              ///< state during this fraction of the swing
  /// Replanning on a disturbance (a push during the swing, as the authors' planner replans at
  /// half swing): after the swing's first plan (the check's, for policies with one; the end of
  /// replan_fraction otherwise) eq. (11) is re-evaluated from the measured CoM state every
  /// tick, and when its foothold has moved more than replan_tolerance [m] from the one
  /// planned, the step is planned again: eq. (11), then the policy's check and OCP over the
  /// time left to the nominal touchdown (their horizon), at most max_replans times per swing
  /// and not when less than min_replan_horizon [s] is left. 0: never.
  double replan_tolerance = 0.0;
  int max_replans = 1;
  double min_replan_horizon = 0.06;
  double touchdown_depth = 0.01;  ///< nominal swing end below the ground (touchdown by contact)
  /// A swing tracking an OCP trajectory: its sole's reference sinks to touchdown_depth below
  /// the trajectory's landing over this last part of it [s] (minimum jerk; 0: it aims at the
  /// OCP's landing and, with the tracking lag, touches down late).
  double ocp_touchdown_blend = 0.05;
  double touchdown_force = 30.0;  ///< sole normal force that counts as touchdown [N]
  double late_touchdown = 0.15;   ///< time past the nominal swing end before a fall is declared
  double check_horizon = 0.2;     ///< policies with a check: the check and the OCP start this long
                                  ///< before the nominal touchdown (their t_f - t_0; it
                                  ///< replaces ReachConfig::horizon) [s]
  /// When a footstep's plan (check + OCP) takes effect. kPause: at once, the simulation waiting
  /// for it (the reference: a run is the same on any machine). kMeasured: the simulation goes
  /// on for the plan's measured wall time first (what this machine would give a robot);
  /// kFixed: for fixed_plan_latency (reproducible). Until the plan takes effect the swing
  /// follows the one it has; a plan that would take effect after the nominal touchdown, or
  /// after the swing sole touched down, is dropped (StepRecord::plan_late).
  enum class PlanLatency { kPause, kMeasured, kFixed };
  PlanLatency plan_latency = PlanLatency::kPause;
  double fixed_plan_latency = 0.1;  ///< kFixed's latency [s], >= 0
  /// kMeasured: the plan's deadline (FootstepPlanRequest::deadline) is the nominal touchdown
  /// less this [s]: the planner stops its passes and its anytime OCP there, and what it
  /// returns still takes effect before the foot lands. The sole lands by contact before the
  /// nominal end of its swing (it aims touchdown_depth below the ground), 20 to 40 ms on the
  /// biped's pushed walk; a deadline at the nominal touchdown made 18 of its 18 plans late.
  double plan_deadline_margin = 0.04;
  double knee_bend = 0.6;      ///< standing posture [rad]
  double forward_speed = 0.0;  ///< desired CoM speed along x (drives p_des of eq. 11)
  Eigen::Vector2d initial_com_velocity = Eigen::Vector2d::Zero();  ///< push at t = 0, feet still
  /// A push while walking: this change of the base's (and so every link's and the CoM's)
  /// horizontal velocity [m/s] at half swing of step midswing_push_step (BulletWorld::pushBase);
  /// a standing run (steps 0) gets it 1 s into its settle phase (at half of a shorter one).
  Eigen::Vector2d midswing_push = Eigen::Vector2d::Zero();
  int midswing_push_step = 4;  ///< the step pushed at half swing, >= 1
  /// Which sole swings first. kFromCapturePoint: the one on the side the instantaneous capture
  /// point (CoM + CoM velocity / omega, eq. 9) lies toward, laterally from the soles' midpoint,
  /// at the end of the settle phase (a push to the left steps with the left leg: the stance
  /// leg is not crossed); within 1 cm of the midpoint, the right sole (as kRight).
  enum class FirstSwing { kFromCapturePoint, kLeft, kRight };
  FirstSwing first_swing = FirstSwing::kFromCapturePoint;
  double fall_pelvis_height = 0.6;  ///< pelvis origin below this height = fall [m]
  /// Seed of every random draw of the run: the reachability check's sampler (replaces
  /// reach.seed; the simulation, the controller and the other policies draw nothing).
  unsigned seed = 1;
  double max_sim_time = 60.0;  ///< hard stop [s] (at most 3600)

  /// \throws ConfigError naming the first bad field.
  void validate() const;
  /// plan_latency from its command-line / parameter form: "pause", "measured", or a latency
  /// in [0, 10] s (kFixed with that fixed_plan_latency). \throws ConfigError naming `key` and
  /// the value otherwise.
  void setPlanLatency(const std::string& value, const std::string& key);
  /// plan_latency in that form ("pause", "measured", the fixed latency in seconds).
  std::string planLatencyName() const;
  /// The YAML keys of section `walk:` (the member names), their units and meaning.
  static const ConfigFields<WalkConfig>& fields();
  /// Reads fields() from a YAML section, then validates.
  static WalkConfig fromYaml(const YamlSection& section);
};

/// One footstep of a run.
struct StepRecord {
  int index = 0;                ///< 1, 2, ...
  Side swing = Side::kRight;    ///< the sole that stepped
  double plan_time = 0.0;       ///< sim time of lift-off and planning [s]
  double touchdown_time = 0.0;  ///< sim time of touchdown [s] (0 if none)
  double swing_duration = 0.0;  ///< the swing's planned duration (WalkConfig::step_timing) [s]
  LipmState com_at_plan;        ///< measured CoM state at planning
  LipmState com_predicted;      ///< LIPM prediction at nominal touchdown (planner input)
  Eigen::Vector2d stance = Eigen::Vector2d::Zero();       ///< stance sole centre [m]
  Eigen::Vector2d planned_tvr = Eigen::Vector2d::Zero();  ///< eq. (11) without bounds [m]
  Eigen::Vector2d planned = Eigen::Vector2d::Zero();      ///< the contact aimed at [m]
  Eigen::Vector3d executed = Eigen::Vector3d::Zero();     ///< sole centre at touchdown [m]
  double touchdown_error = 0.0;                           ///< |executed_xy - planned| [m]
  bool offset_clipped = false;                            ///< heuristic bounds moved the TVR step
  bool touched_down = false;
  /// The check's verdict (policies with a check); kCheckError when the check threw.
  StepVerdict verdict = StepVerdict::kNotChecked;
  /// The check failed and the policy's on_fail part chose the foothold; none otherwise.
  std::optional<WalkingPolicy::OnFailedCheck> failed_check_action;
  /// Where `planned` came from (the TVR step, clipped, a ring point certified or not, the
  /// relaxed OCP's landing).
  FootholdSource foothold_source = FootholdSource::kTarget;
  double hausdorff_distance = -1.0;  ///< [m], -1 when not computed
  /// What certifies the foothold landed on (FootstepTransition::certificate): the target's
  /// reachable verdict, or a certified ring point's (foothold_source nearest_reachable).
  Certificate certificate = Certificate::kNone;
  /// The check's bridged witness (reachability check, kinematically feasible footholds): its
  /// largest violation along the path (reach/witness_path.h), the full-state gap of its
  /// junction pair before bridging and where it ended against x_f (|q|_inf [m, rad],
  /// |qd|_inf [m/s, rad/s]); -1 when there is no witness.
  double witness_violation = -1.0;
  double junction_position_gap = -1.0, junction_velocity_gap = -1.0;
  double terminal_position_gap = -1.0, terminal_velocity_gap = -1.0;
  double check_time_s = 0.0;  ///< reachability check wall time
  double ocp_time_s = 0.0;    ///< OCP wall time
  int check_passes =
      0;  ///< 0: no check; 1; 2: the quick pass certified nothing (see FootstepTransition)
  std::optional<OcpStatus> ocp_status;  ///< none: the policy solves no OCP
  /// Sim time from the check's start to when its plan took effect (WalkConfig::plan_latency;
  /// 0 in kPause) [s].
  double plan_latency_s = 0.0;
  /// The plan came after its deadline and was dropped: the swing went on as it was.
  bool plan_late = false;
  /// Times the step was planned again during the swing (WalkConfig::replan_tolerance); the
  /// fields above are the last plan's.
  int replans = 0;
  std::string reason;  ///< the check's and the OCP's explanations

  /// The enum fields' names at the edges (CSV, messages, WALK lines).
  const char* verdictName() const { return stepVerdictName(verdict); }
  const char* certificateName() const { return reach_trajopt::certificateName(certificate); }
  /// "clip_to_bounds", "nearest_feasible", "relaxed_ocp", "nearest_reachable"; "" when the
  /// check did not fail.
  const char* failedCheckActionName() const {
    return failed_check_action ? WalkingPolicy::actionName(*failed_check_action) : "";
  }
  const char* footholdSourceName() const {
    return reach_trajopt::footholdSourceName(foothold_source);
  }
  /// "converged", "relaxed", "failed"; "none" when no OCP was solved.
  const char* ocpStatusName() const {
    return ocp_status ? reach_trajopt::ocpStatusName(*ocp_status) : "none";
  }
};

/// What the loop sees at one control tick (for recorders and the ROS layer).
struct WalkTick {
  double time = 0.0;  ///< sim time [s]
  ContactMode mode;
  const Eigen::VectorXd* q = nullptr;  ///< measured state (our coordinates)
  const Eigen::VectorXd* qd = nullptr;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Vector3d com_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d com_reference = Eigen::Vector3d::Zero();
  const WbcOutput* wbc = nullptr;
  const std::vector<SoleContact>* soles = nullptr;
};

/// Outcome of a run.
struct WalkResult {
  WalkingPolicy policy;
  int steps = 0;  ///< completed footsteps (touchdowns)
  bool fell = false;
  std::string end_reason;            ///< "completed", or why it fell / stopped
  double sim_time = 0.0;             ///< [s]
  double wall_time = 0.0;            ///< [s]
  int qp_failures = 0;               ///< controller ticks whose QP was not optimal
  double max_touchdown_error = 0.0;  ///< [m]
  std::vector<StepRecord> records;
  /// One line: WALK mode=<policy name> steps=<n> fell=<yes|no> ... ending with the policy's
  /// definition (the format of `make demo`).
  std::string summaryLine() const;
};

/// @brief The walking experiment of Sec. IV: Bullet world + whole-body controller + TVR.
class WalkingExperiment {
 public:
  /// \throws ReachError on invalid configs or a URDF the simulator cannot load.
  /// `proposed` configures the checks, the nearest foothold search and the OCP; used by
  /// policies with a check (defaults when null).
  /// The simulator reports the wrenches of `contact`'s sole frames (`sim`'s are replaced).
  /// `robot` gives the URDF, its locked joints and the leg joints of the standing pose.
  WalkingExperiment(const RobotConfig& robot, const WalkConfig& walk, const TvrConfig& tvr,
                    const ContactConfig& contact, const WbcConfig& wbc, const SimConfig& sim,
                    const FootstepPlannerConfig* proposed = nullptr);
  ~WalkingExperiment();

  /// Runs one walk from the standing pose. `on_tick` (optional) is called after every
  /// control tick, `on_step` after every touchdown, `on_check` (policies with a check) after
  /// every check + OCP with the step so far and the planner's full output.
  WalkResult run(
      const std::function<void(const WalkTick&)>& on_tick = {},
      const std::function<void(const StepRecord&)>& on_step = {},
      const std::function<void(const StepRecord&, const FootstepTransition&)>& on_check = {});

  /// Plans one checked footstep (the check, the OCP and their fallbacks) for the loop; it
  /// throws ReachError for a request it rejects (the step then goes on unchecked, verdict
  /// "check_error", to the TVR step clipped to the heuristic bounds, as with the in-process
  /// planner).
  using FootstepPlanFunction = std::function<FootstepTransition(const FootstepPlanRequest&)>;
  /// Who plans the checked footsteps of the next runs: `plan` (e.g. a ROS node, so the
  /// stepping loop runs through the graph), or the in-process FootstepTransitionPlanner when
  /// empty (the default). The simulation waits (in sim time) for it either way. It must plan
  /// as footstepPlanner() does (same configuration) for the walk to match the in-process one.
  void setFootstepPlanner(FootstepPlanFunction plan);
  /// Proposes the next contact of eq. (11) for the loop, at lift-off and during the swing's
  /// first part (WalkConfig::replan_fraction); it throws ReachError for a request it rejects,
  /// as the in-process planner does.
  using TvrProposalFunction = std::function<TvrProposal(const TvrProposalRequest&)>;
  /// Who proposes the contacts of the next runs: `propose` (e.g. a ROS node), or the loop's own
  /// TvrPlanner when empty (the default). The request carries the loop's LIPM height and
  /// bounds switch; `propose` must use the TvrConfig the experiment was built with (its gains
  /// and bounds) for the walk to match the in-process one (proposeFootstep() does).
  void setTvrProposer(TvrProposalFunction propose);
  /// The in-process planner of the policies with a check (its configuration: the walk's
  /// check_horizon and seed in reach); null for the policies without one.
  const FootstepTransitionPlanner* footstepPlanner() const;

  const RobotModel& model() const { return *model_; }
  std::shared_ptr<const RobotModel> modelPtr() const { return model_; }

 private:
  struct Impl;
  struct Loop;
  std::shared_ptr<const RobotModel> model_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace reach_trajopt
