/// \file walking_experiment.cpp
/// The stepping loop: phases, the TVR call at lift-off, the LIPM CoM reference, touchdown by
/// measured contact, fall detection.

#include "reach_trajopt/walk/walking_experiment.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <Eigen/LU>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/sim/bullet_world.h"
#include "reach_trajopt/walk/standing_pose.h"
#include "reach_trajopt/walk/swing_trajectory.h"

namespace reach_trajopt {

// ---- WalkConfig -------------------------------------------------------------------------------

WalkConfig::Mode WalkConfig::parseMode(const std::string& name) {
  if (name == "baseline") return Mode::kBaseline;
  if (name == "proposed") return Mode::kProposed;
  throw ReachError("walk mode must be 'baseline' or 'proposed', got '" + name + "'");
}

const char* WalkConfig::modeName(Mode mode) {
  return mode == Mode::kBaseline ? "baseline" : "proposed";
}

void WalkConfig::validate() const {
  auto positive = [](const char* name, double v) {
    if (!(v > 0.0) || !std::isfinite(v))
      throw ReachError(std::string("WalkConfig: ") + name + " must be > 0, got " +
                       std::to_string(v));
  };
  auto nonNegative = [](const char* name, double v) {
    if (!(v >= 0.0) || !std::isfinite(v))
      throw ReachError(std::string("WalkConfig: ") + name + " must be >= 0, got " +
                       std::to_string(v));
  };
  if (steps < 0) throw ReachError("WalkConfig: steps must be >= 0");
  positive("single_support_duration", single_support_duration);
  positive("double_support_duration", double_support_duration);
  nonNegative("settle_duration", settle_duration);
  nonNegative("swing_height", swing_height);
  nonNegative("touchdown_depth", touchdown_depth);
  positive("touchdown_force", touchdown_force);
  nonNegative("late_touchdown", late_touchdown);
  positive("check_horizon", check_horizon);
  if (!(check_horizon < single_support_duration))
    throw ReachError("WalkConfig: check_horizon must be shorter than single_support_duration");
  if (!(replan_fraction >= 0.0 && replan_fraction <= 1.0))
    throw ReachError("WalkConfig: replan_fraction must be in [0, 1]");
  nonNegative("knee_bend", knee_bend);
  positive("fall_pelvis_height", fall_pelvis_height);
  positive("max_sim_time", max_sim_time);
  if (!std::isfinite(forward_speed)) throw ReachError("WalkConfig: forward_speed is not finite");
  requireFinite("WalkConfig: initial_com_velocity", initial_com_velocity);
}

WalkConfig WalkConfig::fromYaml(const YamlSection& s) {
  s.requireOnlyKeys({"mode", "steps", "single_support_duration", "double_support_duration",
                     "settle_duration", "swing_height", "touchdown_depth", "touchdown_force",
                     "late_touchdown", "check_horizon", "replan_fraction", "knee_bend", "forward_speed", "initial_com_velocity",
                     "first_swing", "fall_pelvis_height", "seed", "max_sim_time"});
  WalkConfig c;
  std::string mode = modeName(c.mode), first = c.first_swing == Side::kLeft ? "left" : "right";
  s.read("mode", mode);
  c.mode = parseMode(mode);
  s.read("steps", c.steps);
  s.read("single_support_duration", c.single_support_duration);
  s.read("double_support_duration", c.double_support_duration);
  s.read("settle_duration", c.settle_duration);
  s.read("swing_height", c.swing_height);
  s.read("touchdown_depth", c.touchdown_depth);
  s.read("touchdown_force", c.touchdown_force);
  s.read("late_touchdown", c.late_touchdown);
  s.read("check_horizon", c.check_horizon);
  s.read("replan_fraction", c.replan_fraction);
  s.read("knee_bend", c.knee_bend);
  s.read("forward_speed", c.forward_speed);
  Eigen::VectorXd v = c.initial_com_velocity;
  s.read("initial_com_velocity", v);
  c.initial_com_velocity = v;
  s.read("first_swing", first);
  if (first != "left" && first != "right")
    throw ReachError(s.where("first_swing") + ": expected 'left' or 'right', got '" + first + "'");
  c.first_swing = first == "left" ? Side::kLeft : Side::kRight;
  s.read("fall_pelvis_height", c.fall_pelvis_height);
  int seed = static_cast<int>(c.seed);
  s.read("seed", seed);
  c.seed = static_cast<unsigned>(seed);
  s.read("max_sim_time", c.max_sim_time);
  return validatedIn(s, c);
}

ProposedStepConfig ProposedStepConfig::fromYaml(const YamlSection& root) {
  ProposedStepConfig c;
  if (root.has("kinematic_feasibility"))
    c.kinematics = KinematicFeasibilityConfig::fromYaml(root.section("kinematic_feasibility"));
  if (root.has("reach")) c.reach = ReachConfig::fromYaml(root.section("reach"));
  if (root.has("ocp")) c.ocp = TransitionOcpConfig::fromYaml(root.section("ocp"));
  return c;
}

std::string WalkResult::summaryLine() const {
  std::ostringstream os;
  os.precision(4);
  os << "WALK mode=" << WalkConfig::modeName(mode) << " steps=" << steps
     << " fell=" << (fell ? "yes" : "no") << " sim_s=" << sim_time << " wall_s=" << wall_time
     << " max_touchdown_err_m=" << max_touchdown_error << " qp_failures=" << qp_failures
     << " end=" << end_reason;
  return os.str();
}

// ---- The loop ---------------------------------------------------------------------------------

struct WalkingExperiment::Impl {
  std::unique_ptr<ProposedStepPlanner> proposed;
  WalkConfig walk;
  TvrConfig tvr_config;
  ContactConfig contact;
  WbcConfig wbc_config;
  SimConfig sim_config;
  std::string urdf;
};

WalkingExperiment::WalkingExperiment(const std::string& urdf_path, const WalkConfig& walk,
                                     const TvrConfig& tvr, const ContactConfig& contact,
                                     const WbcConfig& wbc, const SimConfig& sim,
                                     const ProposedStepConfig* proposed)
    : model_(RobotModel::fromUrdfFile(urdf_path)), impl_(std::make_unique<Impl>()) {
  walk.validate();
  tvr.validate();
  contact.validate();
  wbc.validate();
  sim.validate();
  if (walk.mode == WalkConfig::Mode::kProposed) {
    const ProposedStepConfig defaults;
    const ProposedStepConfig& c = proposed ? *proposed : defaults;
    ReachConfig reach = c.reach;
    reach.horizon = walk.check_horizon;
    reach.validate();
    impl_->proposed =
        std::make_unique<ProposedStepPlanner>(model_, contact, c.kinematics, reach, c.ocp);
  }
  impl_->walk = walk;
  impl_->tvr_config = tvr;
  impl_->contact = contact;
  impl_->wbc_config = wbc;
  impl_->sim_config = sim;
  impl_->urdf = urdf_path;
}

WalkingExperiment::~WalkingExperiment() = default;

namespace {

Eigen::Vector2d xy(const Eigen::Vector3d& v) { return v.head<2>(); }

/// Joint velocities that give the base a horizontal velocity while both soles stay still.
Eigen::VectorXd pushVelocity(const RobotModel& model, Workspace& ws, const Eigen::VectorXd& q,
                             const Eigen::Vector2d& v, FrameId left, FrameId right) {
  const int n = model.nq();
  Eigen::VectorXd qd = Eigen::VectorXd::Zero(n);
  if (v.squaredNorm() == 0.0) return qd;
  model.update(ws, q, qd);
  Matrix6Xd J(6, n);
  for (FrameId f : {left, right}) {
    model.frameJacobian(ws, f, J);
    // Leg columns: the joints whose column is non-zero for this sole (besides the base).
    std::vector<int> cols;
    for (int j = 6; j < n; ++j)
      if (J.col(j).norm() > 0.0) cols.push_back(j);
    Eigen::MatrixXd Jl(6, cols.size());
    for (size_t k = 0; k < cols.size(); ++k) Jl.col(k) = J.col(cols[k]);
    Eigen::VectorXd base = Eigen::VectorXd::Zero(6);
    base.head<2>() = v;
    const Eigen::VectorXd ql =
        Jl.completeOrthogonalDecomposition().solve(-J.leftCols(6) * base);
    for (size_t k = 0; k < cols.size(); ++k) qd[cols[k]] = ql[k];
  }
  qd.head<2>() = v;
  return qd;
}

}  // namespace

WalkResult WalkingExperiment::run(const std::function<void(const WalkTick&)>& on_tick,
                                  const std::function<void(const StepRecord&)>& on_step,
                                  const std::function<void(const StepRecord&, const ProposedStep&)>& on_check) {
  const auto wall_start = std::chrono::steady_clock::now();
  const WalkConfig& wc = impl_->walk;
  const RobotModel& m = *model_;
  const FrameId sole[2] = {m.frameId(impl_->contact.left_sole_frame),
                           m.frameId(impl_->contact.right_sole_frame)};
  const FrameId pelvis = m.frameId(m.linkNames().front());
  Workspace ws(m);

  const Eigen::VectorXd q0 = standingConfiguration(m, wc.knee_bend, impl_->contact.left_sole_frame);
  const Eigen::VectorXd qd0 =
      pushVelocity(m, ws, q0, wc.initial_com_velocity, sole[0], sole[1]);
  auto world = BulletWorld::fromUrdfFile(impl_->urdf, m, impl_->sim_config);
  world->reset(q0, qd0);
  const double dt = world->timeStep();

  m.update(ws, q0, Eigen::VectorXd::Zero(m.nq()));
  const Eigen::Vector3d com0 = m.centerOfMass(ws);
  TvrConfig tvr_config = impl_->tvr_config;
  tvr_config.com_height = com0.z();  // the LIPM height is the robot's standing CoM height
  tvr_config.heuristic_bounds = wc.mode == WalkConfig::Mode::kBaseline;
  const TvrPlanner planner(tvr_config);
  const Lipm& lipm = planner.lipm();
  WholeBodyController wbc(model_, impl_->contact, impl_->wbc_config, q0);

  enum class Phase { kSettle, kSingle, kDouble };
  Phase phase = Phase::kSettle;
  double phase_start = 0.0;
  Side swing = wc.first_swing;
  ContactMode mode = ContactMode::doubleSupport();
  // LIPM CoM reference (horizontal) and the pivot it rotates about.
  LipmState com_ref;
  Eigen::Vector2d pivot_from = Eigen::Vector2d::Zero(), pivot_to = Eigen::Vector2d::Zero();
  Eigen::Vector2d feet_mid = Eigen::Vector2d::Zero();
  std::unique_ptr<SwingTrajectory> swing_traj;
  StepRecord current;
  // Proposed mode: the OCP trajectory being tracked (empty when none) and when it started.
  bool checked = false;
  TransitionResult tracked;
  double tracked_start = 0.0;
  Workspace ws_traj(m);
  Matrix6Xd J_traj(6, m.nq());

  WalkResult result;
  result.mode = wc.mode;
  WbcReference ref;
  ref.posture = q0;
  Eigen::Matrix3Xd Jc(3, m.nq());

  // Eq. (11) from the measured CoM state predicted to the nominal touchdown (LIPM about the
  // stance sole). Called at lift-off and again during the first part of the swing, so that
  // the footstep follows the measured state rather than a single prediction.
  auto planStep = [&](double t, const Eigen::Vector3d& com, const Eigen::Vector3d& vcom,
                      double time_in_swing) {
    current.com_at_plan.p = xy(com);
    current.com_at_plan.pd = xy(vcom);
    current.plan_time = t;
    const double remaining = std::max(0.0, wc.single_support_duration - time_in_swing);
    current.com_predicted = lipm.propagate(current.com_at_plan, current.stance, remaining);
    TvrInput in;
    in.com = current.com_predicted;
    in.p_des = Eigen::Vector2d(com0.x() + wc.forward_speed * (t + remaining), feet_mid.y());
    in.stance = current.stance;
    in.stance_yaw = 0.0;
    in.swing = current.swing;
    const TvrStep step = planner.plan(in);
    current.planned_tvr = step.alpha_tvr;
    current.planned = step.alpha;
    current.offset_clipped = step.offset_clipped;
  };
  double ground_z = 0.0;
  auto target3 = [&]() {
    return Eigen::Vector3d(current.planned.x(), current.planned.y(), ground_z);
  };

  auto beginSingleSupport = [&](double t, const Eigen::Vector3d& com, const Eigen::Vector3d& vcom) {
    phase = Phase::kSingle;
    phase_start = t;
    mode = ContactMode::singleSupport(opposite(swing));
    const Side stance = opposite(swing);
    const Eigen::Vector3d stance_pos = m.framePose(ws, sole[static_cast<int>(stance)]).translation();
    const Eigen::Vector3d swing_pos = m.framePose(ws, sole[static_cast<int>(swing)]).translation();
    current = StepRecord();
    current.index = result.steps + 1;
    current.swing = swing;
    current.stance = xy(stance_pos);
    ground_z = stance_pos.z();
    planStep(t, com, vcom, 0.0);
    swing_traj = std::make_unique<SwingTrajectory>(swing_pos, target3(), wc.single_support_duration,
                                                   wc.swing_height, wc.touchdown_depth);
    com_ref = current.com_at_plan;
    pivot_from = pivot_to = current.stance;
    checked = false;
    tracked = TransitionResult();
  };

  const int max_ticks = static_cast<int>(std::ceil(wc.max_sim_time / dt));
  result.end_reason = "time limit";
  for (int tick = 0; tick < max_ticks; ++tick) {
    const double t = tick * dt;
    const Eigen::VectorXd& q = world->q();
    const Eigen::VectorXd& qd = world->qd();
    m.update(ws, q, qd);
    const Eigen::Vector3d com = m.centerOfMass(ws);
    m.centerOfMassJacobian(ws, Jc);
    const Eigen::Vector3d vcom = Jc * qd;

    // ---- Phase transitions ----
    if (phase == Phase::kSettle && t >= wc.settle_duration) {
      if (result.steps >= wc.steps) {
        result.end_reason = "completed";
        break;
      }
      feet_mid = 0.5 * (xy(m.framePose(ws, sole[0]).translation()) +
                        xy(m.framePose(ws, sole[1]).translation()));
      beginSingleSupport(t, com, vcom);
    } else if (phase == Phase::kSingle) {
      const double ts = t - phase_start;
      if (ts < wc.replan_fraction * wc.single_support_duration) {
        planStep(t, com, vcom, ts);
        swing_traj->retarget(target3());
      }
      if (impl_->proposed && !checked &&
          ts >= wc.single_support_duration - impl_->proposed->horizon()) {
        // The simulation waits (in sim time) for the check and the OCP.
        checked = true;
        const Side stance = opposite(swing);
        try {
          // The CoM velocity at touchdown: the LIPM about the stance sole from the measured
          // CoM state, over the time left to the nominal touchdown.
          const LipmState at_touchdown = lipm.propagate(
              LipmState{xy(com), xy(vcom)}, current.stance,
              std::max(0.0, wc.single_support_duration - ts));
          const ProposedStep step = impl_->proposed->plan(
              stance, m.framePose(ws, sole[static_cast<int>(stance)]), target3(), q, qd,
              at_touchdown);
          current.verdict = step.verdict;
          current.hausdorff_distance = step.hausdorff_distance;
          current.check_time_s = step.check_time_s;
          current.ocp_time_s = step.ocp_time_s;
          current.ocp_status = ocpStatusName(step.trajectory.status);
          current.reason = step.reason;
          current.planned = xy(step.foothold);
          if (on_check) on_check(current, step);
          if (step.usable()) {
            tracked = step.trajectory;
            tracked_start = t;
          } else {
            swing_traj->retarget(
                Eigen::Vector3d(step.foothold.x(), step.foothold.y(), ground_z));
          }
        } catch (const ReachError& e) {
          // The measured state is outside what the check accepts (e.g. a joint beyond its
          // velocity limit while the robot is already falling): the step goes on unchecked.
          current.verdict = "check_error";
          current.reason = e.what();
        }
        m.update(ws, q, qd);  // plan() used its own workspace; keep ours current
      }
      const SoleContact& sc = world->soleContacts()[static_cast<int>(swing)];
      if (ts > 0.5 * wc.single_support_duration && sc.in_contact &&
          sc.wrench[2] > wc.touchdown_force) {
        current.touched_down = true;
        current.touchdown_time = t;
        current.executed = m.framePose(ws, sole[static_cast<int>(swing)]).translation();
        current.touchdown_error = (xy(current.executed) - current.planned).norm();
        result.max_touchdown_error = std::max(result.max_touchdown_error, current.touchdown_error);
        result.records.push_back(current);
        ++result.steps;
        if (on_step) on_step(current);
        phase = Phase::kDouble;
        phase_start = t;
        mode = ContactMode::doubleSupport();
        com_ref.p = xy(com);
        com_ref.pd = xy(vcom);
        pivot_from = current.stance;
        pivot_to = xy(current.executed);
      } else if (ts > wc.single_support_duration + wc.late_touchdown) {
        result.fell = true;
        result.end_reason = "no touchdown of the swing sole";
        result.records.push_back(current);
        break;
      }
    } else if (phase == Phase::kDouble && t - phase_start >= wc.double_support_duration) {
      if (result.steps >= wc.steps) {
        result.end_reason = "completed";
        break;
      }
      swing = opposite(swing);
      beginSingleSupport(t, com, vcom);
    }

    // ---- References ----
    if (phase != Phase::kSettle) {
      double s = 1.0;
      if (phase == Phase::kDouble)
        s = std::min(1.0, (t - phase_start) / wc.double_support_duration);
      const Eigen::Vector2d pivot = (1.0 - s) * pivot_from + s * pivot_to;
      const Eigen::Vector2d acc = lipm.acceleration(com_ref.p, pivot);
      ref.com_acceleration = Eigen::Vector3d(acc.x(), acc.y(), 0.0);
      com_ref.p += dt * com_ref.pd + 0.5 * dt * dt * acc;
      com_ref.pd += dt * acc;
    } else {
      ref.com_acceleration.setZero();
      com_ref.p = xy(com0);
      com_ref.pd.setZero();
    }
    ref.com_position = Eigen::Vector3d(com_ref.p.x(), com_ref.p.y(), com0.z());
    ref.com_velocity = Eigen::Vector3d(com_ref.pd.x(), com_ref.pd.y(), 0.0);
    ref.q_ff.resize(0);
    ref.qd_ff.resize(0);
    ref.qdd_ff.resize(0);
    if (phase == Phase::kSingle && tracked.time.size() > 0) {
      // Track the OCP trajectory: swing sole from its configurations, joints as feed-forward.
      const int last = static_cast<int>(tracked.time.size()) - 1;
      const double tt = t - tracked_start;
      const int k = std::min(last, static_cast<int>(std::lround(tt / tracked.dt)));
      m.update(ws_traj, tracked.q.col(k), tracked.qd.col(k));
      const FrameId id = sole[static_cast<int>(swing)];
      m.frameJacobian(ws_traj, id, J_traj);
      const Eigen::Isometry3d T = m.framePose(ws_traj, id);
      ref.swing_position = T.translation();
      ref.swing_rotation = T.linear();
      ref.swing_velocity = (J_traj * tracked.qd.col(k)).head<3>();
      ref.swing_acceleration =
          (J_traj * tracked.qdd.col(k) + m.frameJdotQd(ws_traj, id)).head<3>();
      if (tt > tracked.time[last]) {
        // Past the horizon without touchdown: keep descending slowly.
        ref.swing_position.z() -= 0.2 * (tt - tracked.time[last]);
        ref.swing_velocity = Eigen::Vector3d(0, 0, -0.2);
        ref.swing_acceleration.setZero();
      } else {
        ref.q_ff = tracked.q.col(k);
        ref.qd_ff = tracked.qd.col(k);
        ref.qdd_ff = tracked.qdd.col(k);
      }
    } else if (phase == Phase::kSingle) {
      const SwingSample sw = swing_traj->sample(t - phase_start);
      ref.swing_position = sw.position;
      ref.swing_velocity = sw.velocity;
      ref.swing_acceleration = sw.acceleration;
      ref.swing_rotation.setIdentity();
    }

    const WbcOutput& out = wbc.compute(q, qd, mode, ref);
    if (out.status != qp::QpStatus::kOptimal) ++result.qp_failures;
    if (on_tick) {
      WalkTick info;
      info.time = t;
      info.mode = mode;
      info.q = &q;
      info.qd = &qd;
      info.com = com;
      info.com_velocity = vcom;
      info.com_reference = ref.com_position;
      info.wbc = &out;
      info.soles = &world->soleContacts();
      on_tick(info);
    }
    world->step(out.u);
    result.sim_time = world->time();

    // ---- Fall detection ----
    const double pelvis_z = m.framePose(ws, pelvis).translation().z();
    if (pelvis_z < wc.fall_pelvis_height) {
      result.fell = true;
      result.end_reason = "pelvis below " + std::to_string(wc.fall_pelvis_height) + " m";
      break;
    }
    if (!world->nonFootContacts().empty()) {
      result.fell = true;
      result.end_reason = "link '" + world->nonFootContacts().front() + "' touched the ground";
      break;
    }
  }
  result.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace reach_trajopt
