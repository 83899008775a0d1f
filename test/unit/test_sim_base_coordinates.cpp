// Checks of the simulator edge (base_coordinates.h): quaternion <-> ZYX Euler round trips,
// the Euler-rate matrix against finite differences of rotations, and the acceleration maps
// against finite differences of the velocity maps along a trajectory.
#include <gtest/gtest.h>

#include <random>

#include "reach_trajopt/sim/base_coordinates.h"

using namespace reach_trajopt;

namespace {

// Rotation vector of R (log map), for finite differences of orientations.
Eigen::Vector3d rotationLog(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

Vector6d randomVector6(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> U(-scale, scale);
  Vector6d v;
  for (int i = 0; i < 6; ++i) v[i] = U(rng);
  return v;
}

Eigen::Isometry3d randomPose(std::mt19937& rng) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(U(rng), U(rng), U(rng), U(rng)).normalized().toRotationMatrix();
  T.translation() = 0.3 * Eigen::Vector3d(U(rng), U(rng), U(rng));
  return T;
}

// A smooth virtual-coordinate trajectory q_b(t) with analytic derivatives.
struct Trajectory {
  Vector6d a, b, w;
  Vector6d q(double t) const { return a + (b.array() * (w.array() * t).sin()).matrix(); }
  Vector6d qd(double t) const { return (b.array() * w.array() * (w.array() * t).cos()).matrix(); }
  Vector6d qdd(double t) const {
    return (-b.array() * w.array().square() * (w.array() * t).sin()).matrix();
  }
};

}  // namespace

TEST(SimBaseCoordinates, EulerRoundTripAwayFromGimbalLock) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  std::uniform_real_distribution<double> pitch(-1.5, 1.5);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d ypr(angle(rng), pitch(rng), angle(rng));
    const Eigen::Matrix3d R = rotationFromEuler(ypr);
    // Through a quaternion, as the simulator stores it.
    const Eigen::Quaterniond q(R);
    const Eigen::Vector3d back = eulerFromRotation(q.toRotationMatrix());
    EXPECT_LT((back - ypr).cwiseAbs().maxCoeff(), 1e-9) << ypr.transpose();
    EXPECT_LT((rotationFromEuler(back) - R).norm(), 1e-12);
  }
}

TEST(SimBaseCoordinates, RotationMatchesZyxProduct) {
  const Eigen::Vector3d ypr(0.3, -0.4, 1.1);
  const double cy = std::cos(ypr[0]), sy = std::sin(ypr[0]);
  const double cp = std::cos(ypr[1]), sp = std::sin(ypr[1]);
  const double cr = std::cos(ypr[2]), sr = std::sin(ypr[2]);
  Eigen::Matrix3d Rz, Ry, Rx;
  Rz << cy, -sy, 0, sy, cy, 0, 0, 0, 1;
  Ry << cp, 0, sp, 0, 1, 0, -sp, 0, cp;
  Rx << 1, 0, 0, 0, cr, -sr, 0, sr, cr;
  EXPECT_LT((rotationFromEuler(ypr) - Rz * Ry * Rx).norm(), 1e-15);
}

TEST(SimBaseCoordinates, UnwrapsYawAndRollTowardReference) {
  const Eigen::Vector3d ypr(3.1, 0.2, -3.1);
  const Eigen::Vector3d next(3.1 + 0.1, 0.2, -3.1 - 0.1);  // crossed +-pi
  const Eigen::Vector3d plain = eulerFromRotation(rotationFromEuler(next));
  EXPECT_LT(plain[0], 0.0);  // wrapped to (-pi, pi]
  const Eigen::Vector3d unwrapped = eulerFromRotation(rotationFromEuler(next), ypr);
  EXPECT_LT((unwrapped - next).cwiseAbs().maxCoeff(), 1e-12);
  // Several turns away.
  const Eigen::Vector3d far(0.5 + 4 * M_PI, -0.3, 0.2 - 2 * M_PI);
  EXPECT_LT((eulerFromRotation(rotationFromEuler(far), far) - far).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(SimBaseCoordinates, RateMatrixMatchesFiniteDifferenceOfRotation) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> U(-1.3, 1.3);
  const double h = 1e-6;
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d ypr(U(rng), U(rng), U(rng));
    const Eigen::Vector3d rate(U(rng), U(rng), U(rng));
    // omega_world from R(t+h) R(t-h)^T (central difference of the orientation).
    const Eigen::Matrix3d Rp = rotationFromEuler(ypr + h * rate);
    const Eigen::Matrix3d Rm = rotationFromEuler(ypr - h * rate);
    const Eigen::Vector3d omega_fd = rotationLog(Rp * Rm.transpose()) / (2 * h);
    const Eigen::Vector3d omega = eulerRateMatrix(ypr) * rate;
    EXPECT_LT((omega - omega_fd).norm(), 1e-7 * (1 + omega.norm()));
    // And back.
    EXPECT_LT((eulerRatesFromAngularVelocity(ypr, omega) - rate).norm(), 1e-12 * (1 + rate.norm()));
    // Edot against a finite difference of E along the motion.
    const Eigen::Matrix3d Edot_fd =
        (eulerRateMatrix(ypr + h * rate) - eulerRateMatrix(ypr - h * rate)) / (2 * h);
    EXPECT_LT((eulerRateMatrixDot(ypr, rate) - Edot_fd).norm(), 1e-7);
  }
}

TEST(SimBaseCoordinates, GimbalLockThrows) {
  const Eigen::Vector3d ypr(0.2, M_PI / 2, 0.1);
  EXPECT_THROW(eulerRatesFromAngularVelocity(ypr, Eigen::Vector3d(1, 0, 0)), ReachError);
}

TEST(SimBaseCoordinates, VirtualStateRoundTripAndFiniteDifferences) {
  std::mt19937 rng(3);
  const double h = 1e-6;
  for (int i = 0; i < 100; ++i) {
    const BaseCoordinates coords(randomPose(rng));
    Trajectory traj{randomVector6(rng, 1.0), randomVector6(rng, 0.4), randomVector6(rng, 3.0)};
    const double t = 0.37;
    const Vector6d q = traj.q(t), qd = traj.qd(t), qdd = traj.qdd(t);

    const BaseBodyState body = coords.fromVirtual(q, qd);
    Vector6d q_back, qd_back;
    coords.toVirtual(body, q.tail<3>(), q_back, qd_back);
    EXPECT_LT((q_back - q).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((qd_back - qd).cwiseAbs().maxCoeff(), 1e-12);

    // The body's velocities are the time derivatives of its pose along the trajectory.
    const BaseBodyState bp = coords.fromVirtual(traj.q(t + h), traj.qd(t + h));
    const BaseBodyState bm = coords.fromVirtual(traj.q(t - h), traj.qd(t - h));
    const Eigen::Vector3d v_fd = (bp.position - bm.position) / (2 * h);
    const Eigen::Matrix3d Rp = bp.orientation.toRotationMatrix();
    const Eigen::Matrix3d Rm = bm.orientation.toRotationMatrix();
    const Eigen::Vector3d w_fd = rotationLog(Rp * Rm.transpose()) / (2 * h);
    EXPECT_LT((body.linear_velocity - v_fd).norm(), 1e-7);
    EXPECT_LT((body.angular_velocity - w_fd).norm(), 1e-7);

    // The acceleration maps: analytic against the finite difference of the velocities, and
    // each other's inverse.
    const BaseBodyAcceleration acc = coords.accelerationFromVirtual(q, qd, qdd);
    EXPECT_LT((acc.linear - (bp.linear_velocity - bm.linear_velocity) / (2 * h)).norm(), 1e-6);
    EXPECT_LT((acc.angular - (bp.angular_velocity - bm.angular_velocity) / (2 * h)).norm(), 1e-6);
    EXPECT_LT((coords.accelerationToVirtual(q, qd, acc) - qdd).cwiseAbs().maxCoeff(), 1e-11);
  }
}

TEST(SimBaseCoordinates, RejectsNonFinite) {
  const BaseCoordinates coords;
  Vector6d q = Vector6d::Zero(), qd = Vector6d::Zero();
  q[3] = std::nan("");
  EXPECT_THROW(coords.fromVirtual(q, qd), ReachError);
  BaseBodyState body;
  body.angular_velocity.x() = INFINITY;
  Vector6d a, b;
  EXPECT_THROW(coords.toVirtual(body, a, b), ReachError);
}
