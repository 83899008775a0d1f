// The double support's capture-point steering (control/com_reference.h) closed around a
// simulated robot: a linear inverted pendulum whose realized pivot (centre of pressure) is off
// the commanded one by a constant bias, as a whole-body controller's is. The oracle is the
// pendulum's closed form, not the reference's code: with the reference restarted from the
// measured state each tick (DCM feedback) the measured capture point obeys
// xi' = -gain (xi - target) - omega bias, so it settles exponentially at
// target - omega bias / gain; without it the measured capture point runs away from the
// reference's at the rate omega. With the pivot held at the soles' edge the capture point
// moves away from it as exp(omega t).

#include <gtest/gtest.h>

#include <cmath>

#include "reach_trajopt/control/com_reference.h"

using namespace reach_trajopt;

namespace {

constexpr double kHeight = 1.0, kGravity = 9.81, kDt = 0.001;

/// The pendulum over dt about the pivot r, in closed form (eq. 9 integrated).
LipmState pendulum(const LipmState& x, const Eigen::Vector2d& r, double dt) {
  const double w = std::sqrt(kGravity / kHeight);
  LipmState out;
  out.p = r + (x.p - r) * std::cosh(w * dt) + x.pd / w * std::sinh(w * dt);
  out.pd = (x.p - r) * w * std::sinh(w * dt) + x.pd * std::cosh(w * dt);
  return out;
}

Eigen::Vector2d capture(const LipmState& x) { return x.p + x.pd / std::sqrt(kGravity / kHeight); }

/// The robot steered for `duration` [s]; returns its final state.
LipmState steer(LipmState robot, const Eigen::Vector2d& target, double gain,
                const Eigen::Vector2d& bias, bool feedback, double duration,
                const Eigen::Vector2d& box_min, const Eigen::Vector2d& box_max) {
  const Lipm lipm(kHeight, kGravity);
  const double w2 = kGravity / kHeight;
  LipmComReference reference(lipm, Eigen::Vector3d(0.0, 0.0, kHeight));
  reference.startDoubleSupport(robot, robot.p, robot.p);
  WbcReference ref;
  const int ticks = static_cast<int>(std::lround(duration / kDt));
  for (int k = 0; k < ticks; ++k) {
    if (feedback) reference.restart(robot);
    reference.steerCapturePoint(kDt, target, gain, box_min, box_max, ref);
    // The pivot the reference asks for, from its acceleration a = omega^2 (p_ref - r), on the
    // reference's position before its tick; the robot realizes it off by `bias`.
    const Eigen::Vector2d p_before = ref.com_position.head<2>() - kDt * ref.com_velocity.head<2>() +
                                     0.5 * kDt * kDt * ref.com_acceleration.head<2>();
    const Eigen::Vector2d pivot = p_before - ref.com_acceleration.head<2>() / w2;
    robot = pendulum(robot, pivot + bias, kDt);
  }
  return robot;
}

}  // namespace

TEST(ComReference, TheMeasuredCapturePointSettlesWhereTheClosedFormSaysWithFeedback) {
  const double omega = std::sqrt(kGravity / kHeight), gain = 10.0, t = 0.6;
  const Eigen::Vector2d target(0.03, -0.02), bias(0.01, -0.005);
  const Eigen::Vector2d box_min(-1.0, -1.0), box_max(1.0, 1.0);
  LipmState start;
  start.p = Eigen::Vector2d(0.0, 0.05);
  start.pd = Eigen::Vector2d(0.1, 0.3);
  const Eigen::Vector2d xi0 = capture(start);
  const Eigen::Vector2d settle = target - omega * bias / gain;
  const Eigen::Vector2d expected = settle + (xi0 - settle) * std::exp(-gain * t);
  const LipmState fb = steer(start, target, gain, bias, true, t, box_min, box_max);
  EXPECT_LT((capture(fb) - expected).norm(), 2e-3)
      << "measured " << capture(fb).transpose() << ", closed form " << expected.transpose();
  // Without feedback the robot's capture point leaves the reference's at the rate omega: by
  // t its distance from the settling point is many times the feedback's.
  const LipmState open = steer(start, target, gain, bias, false, t, box_min, box_max);
  EXPECT_GT((capture(open) - settle).norm(), 10.0 * (capture(fb) - settle).norm() + 0.02)
      << "open loop " << capture(open).transpose();
}

TEST(ComReference, ACapturePointBeyondTheSolesMovesAwayAsThePendulumAtTheEdge) {
  // The soles' box ends at y = 0.1; the capture point starts 1 cm beyond it: the pivot held at
  // the edge cannot bring it back, xi - edge grows as exp(omega t) (no bias).
  const double omega = std::sqrt(kGravity / kHeight), t = 0.3;
  const Eigen::Vector2d box_min(-0.1, -0.1), box_max(0.1, 0.1);
  LipmState start;
  start.p = Eigen::Vector2d(0.0, 0.05);
  start.pd = Eigen::Vector2d(0.0, 0.06 * omega);  // xi = (0, 0.11)
  const LipmState end = steer(start, Eigen::Vector2d(0.0, -0.03), 10.0, Eigen::Vector2d::Zero(),
                              true, t, box_min, box_max);
  EXPECT_NEAR(capture(end).y(), 0.1 + 0.01 * std::exp(omega * t), 1e-3);
  EXPECT_NEAR(capture(end).x(), 0.0, 1e-9) << "the sagittal capture point is at its target";
}
