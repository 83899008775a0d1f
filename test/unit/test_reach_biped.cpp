// The reachability check on the shipped biped, single support (left stance) -> double support:
// a normal TVR footstep is reachable; a 1.5 m lateral footstep and a footstep just beyond the
// leg's reach are not (kinematic stage), nor is a kinematically feasible foothold too far
// from where the swing sole can go in the window (dynamic stage; the adaptive budget gives up
// after the quick budget there, and the full budget alone agrees). Every forward and backward
// sample, and the witness path, is re-checked here independently of the library: the held
// sole on its foothold within 1e-4 m, joint limits, and the recorded (u, lambda) satisfying
// eq. (1) and the contact wrench cone to 1e-6. 1 and 2 threads give identical results.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <iostream>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/contact/contact_wrench_cone.h"
#include "reach_trajopt/planner/tvr_planner.h"
#include "reach_trajopt/reach/footstep_reachability.h"
#include "reach_trajopt/testing/reference_cases.h"
#include "reach_trajopt/testing/swing_state.h"
#include "thrown_message.h"

using namespace reach_trajopt;

namespace {

std::shared_ptr<const RobotModel> biped() { return shippedBipedModel(REACH_TRAJOPT_SOURCE_DIR); }

/// Sample counts small enough for a unit test (the paper's 1e4 is in bench/reach).
ReachConfig testConfig() {
  ReachConfig c;
  c.horizon = 0.06;
  c.window_start = 0.02;
  c.window_end = 0.04;
  c.budgets.full.initial_samples = 600;
  c.budgets.full.children_per_parent = 4;
  c.budgets.full.backward_children_per_parent = 12;
  c.budgets.full.max_boundary = 40;
  c.budgets.full.interior_samples = 12;
  c.angular_bins = 8;
  c.threads = 1;
  return c;
}

/// IK starting point with bent knees (the IK's own guess converges to stretched legs here).
Eigen::VectorXd bentKnees(const RobotModel& m, double x, double y) {
  return bipedPosture(m, Eigen::Vector3d(x, y, 1.1), 0.4);
}

struct Scenario {
  std::shared_ptr<ReachabilityAnalyzer> analyzer;
  std::shared_ptr<KinematicFeasibility> kinematics;
  ContactTransition request;
};

/// Left stance at (0, 0.1); the TVR target of the right sole from a CoM moving forward; x_0
/// has the right sole 3 cm short of the target and 2 cm up, moving so it would stop on the
/// target at t_f with constant deceleration.
Scenario normalStep(const ReachConfig& config) {
  Scenario s;
  const auto model = biped();
  const ContactConfig contact;
  s.analyzer = std::make_shared<ReachabilityAnalyzer>(model, contact, config);
  s.kinematics =
      std::make_shared<KinematicFeasibility>(model, KinematicFeasibilityConfig(), contact);
  TvrConfig tc;
  tc.kappa_x = -0.66;  // the step these cases were written for: the paper's bias (the shipped
                       // kappa_x, the struct default, is the authors' code value -0.16)
  const TvrPlanner planner(tc);
  TvrInput in;
  in.com.p = Eigen::Vector2d(0.05, 0.05);
  in.com.pd = Eigen::Vector2d(0.5, -0.1);
  in.p_des = Eigen::Vector2d(0.3, 0.0);
  in.stance = Eigen::Vector2d(0.0, 0.1);
  in.swing = Side::kRight;
  const TvrStep step = planner.plan(in);
  ContactTransition& r = s.request;
  r.stance = Side::kLeft;
  r.stance_contact.position << 0.0, 0.1, 0.0;
  r.target.position << step.alpha.x(), step.alpha.y(), 0.0;
  const Eigen::Vector3d p0 = r.target.position + Eigen::Vector3d(-0.03, 0.0, 0.02);
  const Eigen::Vector3d v0 = 2.0 * (r.target.position - p0) / config.horizon;
  const RobotState x0 =
      swingState(model, KinematicFeasibilityConfig(), contact, Side::kLeft, r.stance_contact, p0,
                 0.0, v0, bentKnees(*model, 0.5 * p0.x(), 0.5 * (0.1 + p0.y())));
  r.q0 = x0.q;
  r.qd0 = x0.qd;
  return s;
}

double angle(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  return Eigen::AngleAxisd(Eigen::Matrix3d(A * B.transpose())).angle();
}

/// Largest deviations found by the independent re-check.
struct Recheck {
  double contact = 0.0, dynamics = 0.0, cone = 0.0, torque = 0.0, limits = 0.0;
  long samples = 0;
  void print(const char* what) const {
    std::cout << what << ": " << samples << " samples; max |sole - foothold| " << contact
              << ", max |eq. (1) residual| " << dynamics << ", max cone violation " << cone
              << ", torque " << torque << ", limits " << limits << "\n";
  }
};

/// Re-checks state x (contacts, limits) and the step evaluated at (q_e, qd_e) with
/// acceleration qdd and the recorded (u, lambda).
void checkState(const RobotModel& m, const Eigen::Isometry3d& foothold, FrameId sole,
                const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Recheck& out) {
  Workspace ws(m);
  m.update(ws, q, qd);
  const Eigen::Isometry3d T = m.framePose(ws, sole);
  out.contact = std::max({out.contact, (T.translation() - foothold.translation()).norm(),
                          angle(T.linear(), foothold.linear())});
  const Eigen::VectorXd lo = m.positionLowerLimits(), hi = m.positionUpperLimits(),
                        vmax = m.velocityLimits();
  for (int i = 0; i < m.nq(); ++i)
    out.limits = std::max({out.limits, q[i] - hi[i], lo[i] - q[i], std::abs(qd[i]) - vmax[i]});
}

void checkStep(const RobotModel& m, FrameId sole, const Eigen::VectorXd& q_e,
               const Eigen::VectorXd& qd_e, const Eigen::VectorXd& qdd, const Eigen::VectorXd& u,
               const Eigen::VectorXd& lambda, Recheck& out) {
  Workspace ws(m);
  m.update(ws, q_e, qd_e);
  Eigen::MatrixXd M(m.nq(), m.nq());
  Eigen::VectorXd b(m.nq());
  m.massMatrix(ws, M);
  m.bias(ws, b);
  Matrix6Xd J(6, m.nq());
  m.frameJacobian(ws, sole, J);
  const Eigen::VectorXd res =
      M * qdd + b - m.selectionMatrix().transpose() * u - J.transpose() * lambda;
  out.dynamics = std::max(out.dynamics, res.cwiseAbs().maxCoeff());
  const ContactWrenchCone cone(ContactConfig{});
  const ContactWrenchCone::Matrix C = cone.worldMatrix(m.framePose(ws, sole).linear());
  out.cone = std::max(out.cone, -(C * lambda).minCoeff());
  out.torque = std::max(out.torque, (u.cwiseAbs() - m.effortLimits()).maxCoeff());
}

/// Every sample of both sets: its own state, and the step that produced it.
void recheckAll(const ReachabilityAnalyzer& an, const ReachResult& r, const ContactTransition& req,
                Recheck& fwd, Recheck& bwd) {
  const RobotModel& m = an.model();
  const FrameId sole = m.frameId("l_sole");
  const Eigen::Isometry3d foothold = req.stance_contact.pose();
  for (bool forward : {true, false}) {
    const auto& slices = forward ? r.forward : r.backward;
    Recheck& out = forward ? fwd : bwd;
    for (int j = 1; j < static_cast<int>(slices.size()); ++j) {
      for (int i = 0; i < slices[j].size(); ++i) {
        const int p = slices[j].parent[i];
        const Eigen::VectorXd q = an.sampleConfiguration(r, forward, j, i);
        const Eigen::VectorXd qd = slices[j].qd.col(i);
        const Eigen::VectorXd qp = an.sampleConfiguration(r, forward, j - 1, p);
        const Eigen::VectorXd qdp = slices[j - 1].qd.col(p);
        // The integrator: forward q = q_p + dt qd (semi-implicit), backward q = q_p - dt qd_p.
        const Eigen::VectorXd q_expect =
            forward ? Eigen::VectorXd(qp + r.dt * qd) : Eigen::VectorXd(qp - r.dt * qdp);
        ASSERT_LT((q - q_expect).cwiseAbs().maxCoeff(), 1e-12);
        checkState(m, foothold, sole, q, qd, out);
        if (forward)
          checkStep(m, sole, qp, qdp, (qd - qdp) / r.dt, slices[j].u.col(i),
                    slices[j].lambda.col(i), out);
        else
          checkStep(m, sole, q, qd, (qdp - qd) / r.dt, slices[j].u.col(i), slices[j].lambda.col(i),
                    out);
        ++out.samples;
      }
    }
  }
}

void expectClean(const Recheck& c) {
  EXPECT_LE(c.contact, 1e-4);
  EXPECT_LE(c.dynamics, 1e-6);
  EXPECT_LE(c.cone, 1e-6);
  EXPECT_LE(c.torque, 1e-6);
  EXPECT_LE(c.limits, 1e-9);
  EXPECT_GT(c.samples, 0);
}

}  // namespace

// Every forward and backward sample, and the bridged witness, re-checked here. The verdict
// itself is tested against the OCP and exact sets elsewhere (test_footstep_verdict,
// test_reach_double_integrator): this short case (horizon of testConfig, x_f at rest) is not
// certified by the bridge (its swing sole cannot stop in time with the joints' gap closed).
TEST(ReachBiped, NormalTvrFootstepEverySampleAndTheWitnessCheckOut) {
  const Scenario s = normalStep(testConfig());
  std::cout << "TVR target " << s.request.target.position.transpose() << "\n";
  const FootstepReachability fr(s.analyzer, s.kinematics);
  const FootstepCheckResult res = fr.check(s.request);
  std::cout << res.reason << "\n";
  ASSERT_TRUE(res.kinematically_feasible) << res.reason;
  const ReachResult& r = res.reach;
  EXPECT_EQ(res.reachable, r.witness.certified);
  std::cout << "forward " << r.counts.forward_samples << " samples (" << r.counts.forward_qps
            << " QPs), backward " << r.counts.backward_samples << " samples ("
            << r.counts.backward_qps << " QPs), total " << r.timings.total << " s\n";
  Recheck fwd, bwd;
  recheckAll(*s.analyzer, r, s.request, fwd, bwd);
  fwd.print("forward");
  bwd.print("backward");
  expectClean(fwd);
  expectClean(bwd);
  // The witness path: x_0 ... a, then the bridge; no jump; each state and step re-checked the
  // same way.
  const WitnessPath& w = r.witness;
  ASSERT_TRUE(w.valid);
  EXPECT_EQ(w.junction, -1);
  ASSERT_GE(w.bridge_start, 1);
  const RobotModel& m = s.analyzer->model();
  EXPECT_EQ(w.q.col(0), s.request.q0);
  EXPECT_NEAR(w.time.front(), 0.0, 1e-12);
  if (w.certified) {
    EXPECT_LE((w.q.col(w.q.cols() - 1) - res.kinematics.q_f).cwiseAbs().maxCoeff(),
              testConfig().terminal_position_tolerance);
    EXPECT_NEAR(w.time.back(), testConfig().horizon, 1e-12);
  }
  Recheck wc;
  const FrameId sole = m.frameId("l_sole");
  for (int k = 0; k < w.q.cols(); ++k) {
    checkState(m, s.request.stance_contact.pose(), sole, w.q.col(k), w.qd.col(k), wc);
    if (k + 1 < w.q.cols() && k != w.junction) {
      checkStep(m, sole, w.q.col(k), w.qd.col(k), (w.qd.col(k + 1) - w.qd.col(k)) / r.dt,
                w.u.col(k), w.lambda.col(k), wc);
      EXPECT_LT((w.q.col(k + 1) - w.q.col(k) - r.dt * w.qd.col(k + 1)).cwiseAbs().maxCoeff(),
                1e-12);
    }
  }
  wc.print("witness");
  EXPECT_LE(wc.contact, 1e-4);
  EXPECT_LE(wc.dynamics, 1e-6);
  EXPECT_LE(wc.cone, 1e-6);
  EXPECT_LE(wc.torque, 1e-6);
  EXPECT_LE(wc.limits, 1e-9);
  EXPECT_LE(w.violation.dynamics, 1e-6);  // the library's own account agrees
  std::cout << "witness bridged from t = " << w.time[w.bridge_start] << " s (pair gap "
            << w.position_gap << " / " << w.velocity_gap << "), x(t_f) - x_f "
            << w.terminal_position_gap << " / " << w.terminal_velocity_gap << "\n";
}

TEST(ReachBiped, LateralFootstepOf1_5mIsUnreachable) {
  Scenario s = normalStep(testConfig());
  s.request.target.position << 0.0, 0.1 - 1.5, 0.0;
  const FootstepCheckResult res = FootstepReachability(s.analyzer, s.kinematics).check(s.request);
  std::cout << res.reason << "\n";
  EXPECT_FALSE(res.reachable);
  EXPECT_FALSE(res.kinematically_feasible);
  EXPECT_NE(res.reason.find("unreachable"), std::string::npos);
}

TEST(ReachBiped, FootstepJustBeyondTheLegsReachIsUnreachable) {
  Scenario s = normalStep(testConfig());
  const RobotModel& m = s.analyzer->model();
  // The leg's forward reach along the target's line, by bisection on the kinematic check.
  FlatContact t = s.request.target;
  double lo = t.position.x(), hi = lo + 1.5;
  for (int k = 0; k < 30; ++k) {
    const double mid = 0.5 * (lo + hi);
    t.position.x() = mid;
    const bool ok =
        s.kinematics->check(Side::kLeft, s.request.stance_contact, t, bentKnees(m, 0.5 * mid, 0.0))
            .feasible;
    (ok ? lo : hi) = mid;
  }
  std::cout << "forward reach of the right sole: x = " << lo << " m\n";
  s.request.target.position.x() = hi + 0.02;  // 2 cm beyond
  const FootstepCheckResult res = FootstepReachability(s.analyzer, s.kinematics).check(s.request);
  std::cout << res.reason << "\n";
  EXPECT_FALSE(res.reachable);
  // Within kinematic reach but 0.25 m beyond where the swing sole can get in the window: the
  // dynamic check says no.
  Scenario d = normalStep(testConfig());
  d.request.target.position.x() += 0.25;
  const FootstepCheckResult dyn = FootstepReachability(d.analyzer, d.kinematics).check(d.request);
  std::cout << dyn.reason << "\n";
  ASSERT_TRUE(dyn.kinematically_feasible) << dyn.reason;
  EXPECT_FALSE(dyn.reachable);
  EXPECT_GT(dyn.reach.witness.output_gap, 0.05);
  // The adaptive budget (reach.quick_pass) gave up after the quick budget, its closest attempt
  // far beyond give_up_gap; the full budget alone does not find a path either.
  EXPECT_TRUE(dyn.reach.gave_up) << dyn.reason;
  EXPECT_EQ(dyn.reach.budgets, 1);
  ReachConfig full_alone = testConfig();
  full_alone.quick_pass = false;
  const FootstepCheckResult full =
      FootstepReachability(d.analyzer, d.kinematics).check(d.request, full_alone);
  EXPECT_EQ(full.reach.budgets, 1);
  EXPECT_FALSE(full.reach.gave_up);
  EXPECT_FALSE(full.reachable) << full.reason;
  EXPECT_GT(full.reach.counts.forward_qps + full.reach.counts.backward_qps,
            dyn.reach.counts.forward_qps + dyn.reach.counts.backward_qps);
}

TEST(ReachBiped, OneAndTwoThreadsGiveIdenticalSetsAndVerdict) {
  ReachConfig c = testConfig();
  c.budgets.full.initial_samples = 300;
  c.horizon = 0.03;
  c.window_start = 0.01;
  c.window_end = 0.02;
  const Scenario s = normalStep(c);
  const FootstepReachability fr(s.analyzer, s.kinematics);
  c.threads = 1;
  const FootstepCheckResult a = fr.check(s.request, c);
  c.threads = 2;
  const FootstepCheckResult b = fr.check(s.request, c);
  ASSERT_EQ(a.reach.forward.size(), b.reach.forward.size());
  ASSERT_EQ(a.reach.backward.size(), b.reach.backward.size());
  for (int dir = 0; dir < 2; ++dir) {
    const auto& A = dir ? a.reach.backward : a.reach.forward;
    const auto& B = dir ? b.reach.backward : b.reach.forward;
    for (std::size_t j = 0; j < A.size(); ++j) {
      EXPECT_EQ(A[j].parent, B[j].parent);
      EXPECT_EQ(A[j].kept, B[j].kept);
      EXPECT_TRUE(A[j].qd == B[j].qd) << "slice " << j;
      EXPECT_TRUE(A[j].u == B[j].u);
      EXPECT_TRUE(A[j].lambda == B[j].lambda);
      EXPECT_TRUE(A[j].output == B[j].output);
    }
  }
  EXPECT_EQ(a.reachable, b.reachable);
  EXPECT_EQ(a.reason, b.reason);
  EXPECT_TRUE(a.reach.witness.q == b.reach.witness.q);
  EXPECT_EQ(b.reach.counts.threads, 2);
}

// The backward prefilter (ReachConfig::backward_prefilter) only skips the dynamics of draws
// the exact test (19) rejects: with it, every backward slice is the one without it, bit for
// bit, and it rejects most of the draws (19) rejects. Two swing speeds: the linearization error
// grows with |qd| dt (backward_step.h).
TEST(ReachBiped, BackwardPrefilterKeepsExactlyTheChildrenOfTheExactTest) {
  for (const double horizon : {0.06, 0.03}) {
    ReachConfig c = testConfig();
    c.horizon = horizon;
    c.window_start = 0.01;
    c.window_end = 0.02;
    const Scenario s = normalStep(c);
    const FootstepReachability fr(s.analyzer, s.kinematics);
    c.backward_prefilter = false;
    const FootstepCheckResult exact = fr.check(s.request, c);
    c.backward_prefilter = true;
    const FootstepCheckResult fast = fr.check(s.request, c);
    ASSERT_TRUE(exact.kinematically_feasible);
    EXPECT_EQ(exact.reach.counts.backward_prefiltered, 0);
    const ReachCounts& n = fast.reach.counts;
    EXPECT_GT(n.backward_prefiltered, n.backward_rejected / 2) << "horizon " << horizon;
    EXPECT_LT(n.backward_qps, exact.reach.counts.backward_qps);
    EXPECT_EQ(n.backward_rejected, exact.reach.counts.backward_rejected);
    const auto& A = exact.reach.backward;
    const auto& B = fast.reach.backward;
    ASSERT_EQ(A.size(), B.size());
    for (std::size_t j = 0; j < A.size(); ++j) {
      EXPECT_EQ(A[j].parent, B[j].parent) << "horizon " << horizon << " slice " << j;
      EXPECT_EQ(A[j].kept, B[j].kept);
      EXPECT_TRUE(A[j].qd == B[j].qd);
      EXPECT_TRUE(A[j].u == B[j].u);
      EXPECT_TRUE(A[j].lambda == B[j].lambda);
      EXPECT_TRUE(A[j].output == B[j].output);
    }
    EXPECT_EQ(exact.reachable, fast.reachable);
    EXPECT_EQ(exact.reason, fast.reason);
  }
}

TEST(ReachBiped, StatesViolatingContactsAreErrors) {
  const Scenario s = normalStep(testConfig());
  const RobotModel& m = s.analyzer->model();
  ReachProblem p;
  p.mode = ContactMode::singleSupport(Side::kLeft);
  p.footholds[0] = s.request.stance_contact.pose();
  p.q0 = s.request.q0;
  p.qd0 = s.request.qd0;
  const auto kin =
      s.kinematics->check(Side::kLeft, s.request.stance_contact, s.request.target, s.request.q0);
  ASSERT_TRUE(kin.feasible);
  p.qf = kin.q_f;
  p.qdf = Eigen::VectorXd::Zero(m.nq());
  p.target = s.request.target.pose();
  // The ReachError the check of `problem` throws ("" and a failure when it throws none).
  auto checkError = [&](const ReachProblem& problem) {
    return test::thrownMessage<ReachError>([&] { s.analyzer->check(problem); });
  };
  ReachProblem bad = p;
  bad.q0[0] += 0.01;  // the base moves the stance sole off its foothold
  const std::string off_foothold = checkError(bad);
  EXPECT_NE(off_foothold.find("x_0 violates the contact"), std::string::npos) << off_foothold;
  bad = p;
  bad.target->translation().x() += 0.05;  // x_f does not touch down on the target
  const std::string off_target = checkError(bad);
  EXPECT_NE(off_target.find("x_f violates the contact"), std::string::npos) << off_target;
  bad = p;
  bad.footholds[0].reset();
  EXPECT_THROW(s.analyzer->check(bad), ReachError);
}

TEST(ReachBiped, TouchdownFasterThanTheJointsAllowIsUnreachableNotAnError) {
  // x_f derived from a predicted touchdown CoM velocity the joints cannot follow: the step is
  // unreachable, naming a joint whose velocity (oracle: the posture's own qd_f against the
  // URDF limits) exceeds its limit. The same x_f given with the request is a bad request.
  Scenario s = normalStep(testConfig());
  const RobotModel& m = s.analyzer->model();
  s.request.touchdown.com_velocity = Eigen::Vector2d(0.0, -8.0);
  const FootstepReachability fr(s.analyzer, s.kinematics);
  const FootstepCheckResult res = fr.check(s.request);
  ASSERT_TRUE(res.kinematically_feasible) << res.reason;
  EXPECT_FALSE(res.reachable);
  const Eigen::VectorXd over = res.qdf.cwiseAbs() - m.velocityLimits();
  Eigen::Index worst = 0;
  ASSERT_GT(over.maxCoeff(&worst), 0.0);
  EXPECT_NE(res.reason.find("exceeds the velocity limit of "), std::string::npos) << res.reason;
  bool names_a_violating_joint = false;
  for (int i = 0; i < m.nq(); ++i)
    if (over[i] > 0.0 &&
        res.reason.find("limit of " + m.joints()[i].name + " ") != std::string::npos)
      names_a_violating_joint = true;
  EXPECT_TRUE(names_a_violating_joint) << res.reason;
  ContactTransition given = s.request;
  given.qdf = res.qdf;
  EXPECT_THROW(fr.check(given), ReachError);
  // At the normal step's own touchdown velocity the rule refuses nothing.
  const Scenario normal = normalStep(testConfig());
  const FootstepCheckResult ok = fr.check(normal.request);
  EXPECT_EQ(ok.reason.find("exceeds the velocity limit"), std::string::npos) << ok.reason;
}
