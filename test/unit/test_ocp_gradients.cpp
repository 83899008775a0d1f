// Every derivative the transition OCP hands to SLSQP, checked against central finite
// differences: the per-sample signals of the reduced single-support dynamics (eq. 1 + 5) with
// respect to (q_a, qd_a, qdd_a, lambda_2), and the NLP's cost, equality and inequality
// Jacobians with respect to its variables, for the strict and the relaxed problem. Also checks
// that the reduced coordinates hold the stance contact and eq. (1) exactly (full model).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "reach_trajopt/contact/contact_constraint.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/ocp/stance_reduced_dynamics.h"
#include "reach_trajopt/ocp/transition_nlp.h"
#include "reach_trajopt/planner/kinematic_feasibility.h"
#include "reach_trajopt/testing/matrix_error.h"
#include "reach_trajopt/testing/reference_cases.h"

using namespace reach_trajopt;

namespace {

std::shared_ptr<const RobotModel> biped() { return shippedBipedModel(REACH_TRAJOPT_SOURCE_DIR); }

/// The reduced dynamics of `r`'s step: the left sole held at its pose, the right one moving
/// to its target.
StanceReducedDynamics stepDynamics(const TransitionRequest& r) {
  const auto m = biped();
  return StanceReducedDynamics(m, m->frameId("l_sole"), r.heldPose(), m->frameId("r_sole"),
                               r.targetPose(), 0.0);
}

/// SS-L, right sole stepping to (0.25, -0.1); x_0 from the IK stance with the right leg folded.
TransitionRequest request() {
  const auto m = biped();
  TransitionRequest r = ocpStepCase(m, 0.25, 0.25, 0.2);
  StanceReducedDynamics d = stepDynamics(r);
  StanceReducedDynamics::Scratch s(d);
  const Eigen::VectorXd qa = r.q0.tail(m->nu());
  // A moving start: joint velocities, base velocity from the stance contact (J_s qd = 0).
  Eigen::VectorXd input = Eigen::VectorXd::Zero(d.inputCount());
  input.head(m->nu()) = qa;
  input.segment(m->nu(), m->nu()) = 0.3 * Eigen::VectorXd::LinSpaced(m->nu(), -1.0, 1.0);
  Eigen::VectorXd sig(d.signalCount());
  d.evaluate(s, input, sig);
  r.qd0 = s.qd;
  return r;
}

/// Central differences of f: R^n -> R^m at x, step h (relative to max(1, |x_i|)).
template <typename F>
Eigen::MatrixXd centralJacobian(F f, const Eigen::VectorXd& x, int m, double h) {
  Eigen::MatrixXd J(m, x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const double hi = h * std::max(1.0, std::abs(x[i]));
    Eigen::VectorXd a = x, b = x;
    a[i] += hi;
    b[i] -= hi;
    J.col(i) = (f(a) - f(b)) / (2.0 * hi);
  }
  return J;
}

using reach_trajopt::testing::rowRelativeError;

}  // namespace

TEST(StanceReducedDynamics, HoldsStanceContactAndEquationOne) {
  const auto m = biped();
  const TransitionRequest r = request();
  StanceReducedDynamics d = stepDynamics(r);
  StanceReducedDynamics::Scratch s(d);
  const int nu = m->nu(), nq = m->nq();
  Eigen::VectorXd input = Eigen::VectorXd::Zero(d.inputCount());
  input.head(nu) = r.q0.tail(nu);
  input.segment(nu, nu) = r.qd0.tail(nu);
  input.segment(2 * nu, nu) = Eigen::VectorXd::LinSpaced(nu, -2.0, 3.0);
  input.tail<6>() << 10, -20, 300, 5, -4, 1;
  Eigen::VectorXd sig(d.signalCount());
  d.evaluate(s, input, sig);
  // Reconstructed x_0 equals the request's (built the same way) and keeps the sole in place.
  EXPECT_LT((s.q - r.q0).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((s.qd - r.qd0).cwiseAbs().maxCoeff(), 1e-12);
  Workspace ws(*m);
  m->update(ws, s.q, s.qd);
  const ContactConstraint stance(*m, "l_sole", r.heldPose());
  ContactConstraintTerms t(nq);
  stance.evaluate(*m, ws, t);
  EXPECT_LT(t.phi.cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(t.phidot.cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(t.phiddot(s.qdd).cwiseAbs().maxCoeff(), 1e-10);
  // Eq. (1) with the full model: M qdd + b = S^T u + J_s^T lambda_s + J_2^T lambda_2.
  Eigen::MatrixXd M(nq, nq);
  Eigen::VectorXd b(nq);
  Matrix6Xd Js(6, nq), J2(6, nq);
  m->massMatrix(ws, M);
  m->bias(ws, b);
  m->frameJacobian(ws, m->frameId("l_sole"), Js);
  m->frameJacobian(ws, m->frameId("r_sole"), J2);
  Eigen::VectorXd res = M * s.qdd + b - Js.transpose() * sig.segment<6>(d.lambdaOffset()) -
                        J2.transpose() * input.tail<6>();
  res.tail(nu) -= sig.segment(d.uOffset(), nu);
  EXPECT_LT(res.cwiseAbs().maxCoeff(), 1e-9 * std::max(1.0, b.cwiseAbs().maxCoeff()));
}

TEST(StanceReducedDynamics, SignalJacobianMatchesCentralDifferences) {
  const auto m = biped();
  const TransitionRequest r = request();
  StanceReducedDynamics d = stepDynamics(r);
  StanceReducedDynamics::Scratch s(d);
  const int nu = m->nu();
  Eigen::VectorXd input = Eigen::VectorXd::Zero(d.inputCount());
  input.head(nu) = r.q0.tail(nu);
  input.segment(nu, nu) = r.qd0.tail(nu) + 0.5 * Eigen::VectorXd::Ones(nu);
  input.segment(2 * nu, nu) = Eigen::VectorXd::LinSpaced(nu, -2.0, 3.0);
  input.tail<6>() << 10, -20, 300, 5, -4, 1;
  auto f = [&](const Eigen::VectorXd& x) {
    Eigen::VectorXd sig(d.signalCount());
    d.evaluate(s, x, sig);
    return sig;
  };
  const Eigen::MatrixXd fd = centralJacobian(f, input, d.signalCount(), 1e-5);
  Eigen::VectorXd sig(d.signalCount());
  Eigen::MatrixXd J(d.signalCount(), d.inputCount());
  // Central differences in q_a (step 1e-5): truncation ~1e-10, so agreement to ~1e-8.
  d.evaluate(s, input, sig, J, 1e-5, true);
  EXPECT_LT(rowRelativeError(J.leftCols(nu), fd.leftCols(nu)), 1e-7);
  // qd_a (exact central differences), qdd_a and lambda_2 (analytic) are exact: only the
  // reference's truncation and roundoff remain.
  EXPECT_LT(rowRelativeError(J.rightCols(2 * nu + 6), fd.rightCols(2 * nu + 6)), 1e-7);
  // Forward differences in q_a (step 1e-6): error ~ h |f''| ~ 1e-6 relative.
  d.evaluate(s, input, sig, J, 1e-6, false);
  EXPECT_LT(rowRelativeError(J.leftCols(nu), fd.leftCols(nu)), 1e-4);
  EXPECT_LT(rowRelativeError(J.rightCols(2 * nu + 6), fd.rightCols(2 * nu + 6)), 1e-7);
}

class TransitionNlpGradient : public ::testing::TestWithParam<bool> {};

TEST_P(TransitionNlpGradient, MatchesCentralDifferences) {
  const bool relaxed = GetParam();
  const auto m = biped();
  TransitionRequest r = request();
  // A hull slice so its rows are part of the check.
  ReachableSlice slice;
  slice.time = 0.1;
  slice.A.resize(3, 2);
  slice.A << 1.0, 0.2, -0.5, 1.0, 0.1, -1.0;
  slice.b.resize(3);
  slice.b << 1.0, 0.5, 0.6;
  r.slices.push_back(slice);
  // The default scheme: the kinematic chain analytic (exact up to roundoff).
  TransitionOcpConfig cfg;
  ASSERT_EQ(cfg.chain_derivatives, ChainDerivatives::kAnalytic);
  TransitionNlp nlp(m, cfg, ContactConfig(), r, relaxed);
  ASSERT_EQ(nlp.variableCount(),
            relaxed ? 12 * (cfg.segments + 1) + 8 : 12 * (cfg.segments - 1) + 6);
  // A point away from the initial guess, with lambda_2 and eps non-zero.
  Eigen::VectorXd x = nlp.initialGuess();
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] += 0.02 * std::sin(1.7 * i + 0.3);
  NlpValues v;
  nlp.evaluate(x, true, v);
  ASSERT_EQ(v.equality.size(), nlp.equalityCount());
  ASSERT_EQ(v.inequality.size(), nlp.inequalityCount());
  auto all = [&](const Eigen::VectorXd& y) {
    NlpValues w;
    nlp.evaluate(y, false, w);
    Eigen::VectorXd out(1 + w.equality.size() + w.inequality.size());
    out << w.cost, w.equality, w.inequality;
    return out;
  };
  const int m_all = 1 + nlp.equalityCount() + nlp.inequalityCount();
  const Eigen::MatrixXd fd = centralJacobian(all, x, m_all, 1e-6);
  EXPECT_LT(rowRelativeError(v.cost_gradient.transpose(), fd.topRows(1)), 1e-6);
  EXPECT_LT(rowRelativeError(v.equality_jacobian, fd.middleRows(1, nlp.equalityCount())), 1e-6);
  EXPECT_LT(rowRelativeError(v.inequality_jacobian, fd.bottomRows(nlp.inequalityCount())), 1e-6);

  // chain_derivatives: finite_differences, central (step 1e-5) within the same bound, forward
  // (the default step) within its own, looser one.
  TransitionOcpConfig cfg_central;
  cfg_central.chain_derivatives = ChainDerivatives::kFiniteDifferences;
  cfg_central.central_differences = true;
  cfg_central.fd_step = 1e-5;
  TransitionNlp nlp_central(m, cfg_central, ContactConfig(), r, relaxed);
  NlpValues vc;
  nlp_central.evaluate(x, true, vc);
  EXPECT_LT(rowRelativeError(vc.cost_gradient.transpose(), fd.topRows(1)), 1e-6);
  EXPECT_LT(rowRelativeError(vc.equality_jacobian, fd.middleRows(1, nlp.equalityCount())), 1e-6);
  EXPECT_LT(rowRelativeError(vc.inequality_jacobian, fd.bottomRows(nlp.inequalityCount())), 1e-6);
  TransitionOcpConfig cfg_fwd;
  cfg_fwd.chain_derivatives = ChainDerivatives::kFiniteDifferences;
  TransitionNlp nlp_fwd(m, cfg_fwd, ContactConfig(), r, relaxed);
  NlpValues vf;
  nlp_fwd.evaluate(x, true, vf);
  EXPECT_LT(rowRelativeError(vf.cost_gradient.transpose(), fd.topRows(1)), 1e-4);
  EXPECT_LT(rowRelativeError(vf.equality_jacobian, fd.middleRows(1, nlp.equalityCount())), 1e-4);
  EXPECT_LT(rowRelativeError(vf.inequality_jacobian, fd.bottomRows(nlp.inequalityCount())), 1e-4);
}

INSTANTIATE_TEST_SUITE_P(StrictAndRelaxed, TransitionNlpGradient, ::testing::Values(false, true));

// The NLP's samples evaluated on 2 threads give the bits of 1 thread (TransitionOcpConfig::
// threads): each sample's dynamics on one thread, the rows assembled in sample order.
TEST(TransitionNlp, TwoThreadsGiveTheBitsOfOne) {
  const auto m = biped();
  const TransitionRequest r = request();
  for (const bool relaxed : {false, true}) {
    TransitionOcpConfig one, two;
    one.threads = 1;
    two.threads = 2;
    TransitionNlp nlp1(m, one, ContactConfig(), r, relaxed);
    TransitionNlp nlp2(m, two, ContactConfig(), r, relaxed);
    Eigen::VectorXd x = nlp1.initialGuess();
    for (Eigen::Index i = 0; i < x.size(); ++i) x[i] += 0.02 * std::sin(1.3 * i);
    for (const bool gradients : {false, true}) {
      NlpValues a, b;
      nlp1.evaluate(x, gradients, a);
      nlp2.evaluate(x, gradients, b);
      EXPECT_EQ(a.cost, b.cost);
      EXPECT_TRUE(a.equality == b.equality);
      EXPECT_TRUE(a.inequality == b.inequality);
      if (gradients) {
        EXPECT_TRUE(a.cost_gradient == b.cost_gradient);
        EXPECT_TRUE(a.equality_jacobian == b.equality_jacobian);
        EXPECT_TRUE(a.inequality_jacobian == b.inequality_jacobian);
      }
    }
  }
}

// Refinement (TransitionOcp): a time between two samples and a slice not yet enforced change
// the NLP (more samples, more rows); a time it samples already or a slice it enforces already
// do not, and the 1 ms re-check's answer then only restarts SLSQP.
TEST(TransitionNlp, AddSamplesSaysWhetherTheNlpChanged) {
  const auto m = biped();
  TransitionRequest r = request();
  ReachableSlice slice;
  slice.time = 0.1;
  slice.A = Eigen::MatrixXd::Identity(2, 2);
  slice.b = Eigen::Vector2d(1.0, 1.0);
  r.slices.push_back(slice);
  TransitionNlp nlp(m, TransitionOcpConfig(), ContactConfig(), r, false);
  const std::vector<double> times = nlp.sampleTimes();
  const int rows = nlp.inequalityCount();
  ASSERT_GE(times.size(), 3u);
  EXPECT_FALSE(nlp.addSamples({times[0], times[1]}, {}));
  EXPECT_EQ(nlp.sampleTimes(), times);
  EXPECT_EQ(nlp.inequalityCount(), rows);
  // The slice's time is on the grid: it is enforced from the start.
  EXPECT_FALSE(nlp.addSamples({}, {0}));
  EXPECT_EQ(nlp.inequalityCount(), rows);
  const double between = 0.5 * (times[0] + times[1]);
  EXPECT_TRUE(nlp.addSamples({between}, {}));
  EXPECT_EQ(nlp.sampleTimes().size(), times.size() + 1);
  EXPECT_GT(nlp.inequalityCount(), rows);
  EXPECT_FALSE(nlp.addSamples({between}, {}));
}
