// The LIPM capture limits (planner/capture_limits.h) against two independent answers:
//  - the figures of Koolen et al.'s formulas for the biped as the issue tracker quotes them
//    (h = 1 m, 0.42 m steps, 0.22 s swing, 0.135 m half sole: 0.42 / 1.08 / 1.75 m/s forward,
//    1.27 m/s with one outward 0.65 m step sideways), to their two digits;
//  - a numerical integration (RK4, 0.1 ms) of the pendulum x'' = omega^2 (x - p) under the
//    capture strategy (the CoP on the sole's edge, the step as far and as early as allowed),
//    with the largest capturable push found by bisection: it must agree with the closed form.

#include <gtest/gtest.h>

#include <cmath>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/planner/capture_limits.h"

using namespace reach_trajopt;

namespace {

/// Whether a push `v` [m/s] along one axis is captured with `steps` steps: the CoM starts
/// above the sole centre; each swing keeps the CoP at the sole's edge `d0` for T_s, then the
/// foot lands `l` further; at the end the capture point must lie within the last sole.
bool capturedByIntegration(double omega, double d0, double l, double T_s, int steps, double v) {
  const double dt = 1e-4;
  double x = 0.0, xd = v, foot = 0.0;
  auto rk4 = [&](double p, double duration) {
    const int n = static_cast<int>(std::round(duration / dt));
    for (int k = 0; k < n; ++k) {
      const double w2 = omega * omega;
      const double k1x = xd, k1v = w2 * (x - p);
      const double k2x = xd + 0.5 * dt * k1v, k2v = w2 * (x + 0.5 * dt * k1x - p);
      const double k3x = xd + 0.5 * dt * k2v, k3v = w2 * (x + 0.5 * dt * k2x - p);
      const double k4x = xd + dt * k3v, k4v = w2 * (x + dt * k3x - p);
      x += dt / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
      xd += dt / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    }
  };
  for (int s = 0; s < steps; ++s) {
    rk4(foot + d0, T_s);
    foot += l;
  }
  return x + xd / omega <= foot + d0;
}

double integratedLimit(double omega, double d0, double l, double T_s, int steps) {
  double lo = 0.0, hi = 10.0;
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    (capturedByIntegration(omega, d0, l, T_s, steps, mid) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace

TEST(CaptureLimits, TheBipedsFiguresAsQuoted) {
  const CaptureModel m;  // the biped of config/biped.yaml
  const CaptureLimits forward = captureLimits(m, 0.0);
  EXPECT_NEAR(forward.zero_step, 0.42, 0.005);
  EXPECT_NEAR(forward.one_step, 1.08, 0.005);
  EXPECT_NEAR(forward.n_step, 1.75, 0.005);
  const CaptureLimits left = captureLimits(m, M_PI / 2);
  EXPECT_NEAR(left.one_step, 1.27, 0.005);
  // Symmetric: right like left, backward like forward (equal bounds).
  EXPECT_NEAR(captureLimits(m, -M_PI / 2).one_step, left.one_step, 1e-12);
  EXPECT_NEAR(captureLimits(m, M_PI).n_step, forward.n_step, 1e-12);
}

TEST(CaptureLimits, AgreeWithTheIntegratedPendulum) {
  CaptureModel m;
  m.step_backward_max = 0.3;  // an asymmetric case too
  const double w = m.omega();
  struct Case {
    double theta, d0, l;
  } cases[] = {{0.0, m.sole_half_length, m.step_forward_max},
               {M_PI, m.sole_half_length, m.step_backward_max},
               {M_PI / 2, m.sole_half_width, m.step_lateral_max}};
  for (const Case& c : cases) {
    const CaptureLimits lim = captureLimits(m, c.theta);
    EXPECT_NEAR(lim.zero_step, integratedLimit(w, c.d0, c.l, m.min_swing_time, 0), 2e-3) << c.theta;
    EXPECT_NEAR(lim.one_step, integratedLimit(w, c.d0, c.l, m.min_swing_time, 1), 2e-3) << c.theta;
    // Many steps approach the N-step limit from below.
    const double ten = integratedLimit(w, c.d0, c.l, m.min_swing_time, 10);
    EXPECT_LE(ten, lim.n_step + 2e-3) << c.theta;
    EXPECT_NEAR(ten, lim.n_step, 0.01) << c.theta;
    EXPECT_LT(lim.zero_step, lim.one_step);
    EXPECT_LT(lim.one_step, lim.n_step);
  }
}

TEST(CaptureLimits, StandingOnBothSolesWidensOnlyTheSidewaysNoStepLimit) {
  CaptureModel m;
  const CaptureLimits one = captureLimits(m, M_PI / 2);
  m.stance_half_separation = 0.1;
  const CaptureLimits both = captureLimits(m, M_PI / 2);
  EXPECT_NEAR(both.zero_step - one.zero_step, m.omega() * 0.1, 1e-12);
  EXPECT_EQ(both.one_step, one.one_step);
  EXPECT_NEAR(captureLimits(m, 0.0).zero_step, m.omega() * m.sole_half_length, 1e-12);
}

TEST(CaptureLimits, ABadModelIsAnErrorNamingTheField) {
  CaptureModel m;
  m.com_height = 0.0;
  try {
    captureLimits(m, 0.0);
    FAIL();
  } catch (const RequestError& e) {
    EXPECT_NE(std::string(e.what()).find("com_height"), std::string::npos) << e.what();
  }
  m = CaptureModel();
  m.min_swing_time = std::nan("");
  EXPECT_THROW(captureLimits(m, 0.0), RequestError);
  EXPECT_THROW(captureLimits(CaptureModel(), std::nan("")), RequestError);
}
