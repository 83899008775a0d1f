// Contact modes and sequences, the contact wrench cone (eq. 7-8) on cases with known answers,
// the orientation error of eq. (5) and its Jacobian against finite differences, config/YAML.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/contact/contact_constraint.h"
#include "reach_trajopt/contact/contact_mode.h"
#include "reach_trajopt/contact/contact_sequence.h"
#include "reach_trajopt/contact/contact_wrench_cone.h"
#include "reach_trajopt/testing/reference_cases.h"

using namespace reach_trajopt;

namespace {
const double kNaN = std::numeric_limits<double>::quiet_NaN();

ContactWrenchCone::Wrench cornerWrench(const Eigen::Matrix<double, 4, 3>& f, double X, double Y) {
  ContactWrenchCone::Wrench w = ContactWrenchCone::Wrench::Zero();
  const double sx[4] = {1, 1, -1, -1}, sy[4] = {1, -1, 1, -1};
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d c(sx[k] * X, sy[k] * Y, 0.0);
    const Eigen::Vector3d fk = f.row(k).transpose();
    w.head<3>() += fk;
    w.tail<3>() += c.cross(fk);
  }
  return w;
}

Eigen::Matrix3d rpy(double r, double p, double y) {
  return (Eigen::AngleAxisd(y, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(p, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(r, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}
}  // namespace

TEST(ContactMode, NamesAndStance) {
  EXPECT_EQ(ContactMode::doubleSupport().name(), "DS");
  EXPECT_EQ(ContactMode::singleSupport(Side::kLeft).name(), "SS-L");
  EXPECT_EQ(ContactMode::singleSupport(Side::kRight).name(), "SS-R");
  EXPECT_EQ(ContactMode::singleSupport(Side::kLeft).swing(), Side::kRight);
  EXPECT_TRUE(ContactMode::singleSupport(Side::kRight).inContact(Side::kRight));
  EXPECT_FALSE(ContactMode::singleSupport(Side::kRight).inContact(Side::kLeft));
  EXPECT_EQ(ContactMode::fromName("SS-R"), ContactMode::singleSupport(Side::kRight));
  EXPECT_THROW(ContactMode::fromName("SS-X"), ReachError);
  EXPECT_THROW(ContactMode::doubleSupport().stance(), ReachError);
}

TEST(ContactSequence, WalkingPatternAndTiming) {
  const auto seq = ContactSequence::walking(3, Side::kLeft, 0.28, 0.05);
  ASSERT_EQ(seq.size(), 7);
  const char* expected[] = {"DS", "SS-L", "DS", "SS-R", "DS", "SS-L", "DS"};
  for (int i = 0; i < 7; ++i) EXPECT_EQ(seq.phase(i).mode.name(), expected[i]);
  EXPECT_NEAR(seq.totalDuration(), 4 * 0.05 + 3 * 0.28, 1e-15);
  EXPECT_NEAR(seq.startTime(3), 0.05 + 0.28 + 0.05, 1e-15);
  EXPECT_EQ(seq.phaseIndexAt(0.0), 0);
  EXPECT_EQ(seq.phaseIndexAt(0.05), 1);  // a phase owns its start instant
  EXPECT_EQ(seq.phaseIndexAt(0.2), 1);
  EXPECT_EQ(seq.phaseIndexAt(seq.totalDuration()), 6);
  EXPECT_EQ(seq.modeAt(0.4).name(), "SS-R");
  EXPECT_THROW(seq.phaseIndexAt(-1e-9), ReachError);
  EXPECT_THROW(seq.phaseIndexAt(kNaN), ReachError);
  EXPECT_THROW(seq.phase(7), ReachError);
}

TEST(ContactSequence, RejectsInvalidSequences) {
  const auto ssl = ContactMode::singleSupport(Side::kLeft);
  const auto ssr = ContactMode::singleSupport(Side::kRight);
  EXPECT_THROW(ContactSequence({{ssl, 0.3}, {ssr, 0.3}}), ReachError);  // needs a flight
  EXPECT_THROW(ContactSequence({{ssl, 0.3}, {ssl, 0.3}}), ReachError);  // not a switch
  EXPECT_THROW(ContactSequence({{ContactMode{false, false}, 0.3}}), ReachError);
  EXPECT_THROW(ContactSequence({{ssl, 0.0}}), ReachError);
  EXPECT_THROW(ContactSequence({{ssl, kNaN}}), ReachError);
  EXPECT_THROW(ContactSequence::walking(2, Side::kLeft, -0.1, 0.05), ReachError);
  EXPECT_NO_THROW(ContactSequence({{ssl, 0.3}, {ContactMode::doubleSupport(), 0.1}, {ssr, 0.3}}));
}

TEST(ContactWrenchCone, RejectsBadParameters) {
  EXPECT_THROW(ContactWrenchCone(0.0, 0.135, 0.08), ReachError);
  EXPECT_THROW(ContactWrenchCone(-0.7, 0.135, 0.08), ReachError);
  EXPECT_THROW(ContactWrenchCone(0.7, 0.0, 0.08), ReachError);
  EXPECT_THROW(ContactWrenchCone(0.7, 0.135, 0.0), ReachError);
  EXPECT_THROW(ContactWrenchCone(kNaN, 0.135, 0.08), ReachError);
  // Finite but so large that the cone's entries would overflow to inf and NaN.
  EXPECT_THROW(ContactWrenchCone(1e308, 0.135, 0.08), ReachError);
  EXPECT_THROW(ContactWrenchCone(0.7, 1e308, 0.08), ReachError);
  EXPECT_THROW(ContactWrenchCone(0.7, 0.135, 1e308), ReachError);
  ContactConfig c;
  c.mu = 0.0;
  EXPECT_THROW(c.validate(), ReachError);
  EXPECT_THROW(ContactWrenchCone{c}, ReachError);
}

TEST(ContactWrenchCone, KnownWrenches) {
  const double mu = 0.7, X = 0.135, Y = 0.08, fz = 600.0;
  const ContactWrenchCone cone(mu, X, Y);
  using W = ContactWrenchCone::Wrench;
  EXPECT_TRUE(cone.contains(W(0, 0, fz, 0, 0, 0)));   // pure weight
  EXPECT_FALSE(cone.contains(W(0, 0, -1, 0, 0, 0)));  // pulling
  EXPECT_TRUE(cone.contains(W(mu * fz * 0.99, 0, fz, 0, 0, 0)));
  EXPECT_FALSE(cone.contains(W(mu * fz * 1.01, 0, fz, 0, 0, 0)));  // slipping
  EXPECT_TRUE(cone.contains(W(0, 0, fz, Y * fz * 0.99, 0, 0)));    // CoP near the edge
  EXPECT_FALSE(cone.contains(W(0, 0, fz, Y * fz * 1.01, 0, 0)));   // CoP off the sole
  EXPECT_FALSE(cone.contains(W(0, 0, fz, 0, -X * fz * 1.01, 0)));
  // Pure yaw torque: |tz| <= mu (X + Y) fz exactly.
  EXPECT_TRUE(cone.contains(W(0, 0, fz, 0, 0, mu * (X + Y) * fz * 0.999)));
  EXPECT_FALSE(cone.contains(W(0, 0, fz, 0, 0, -mu * (X + Y) * fz * 1.001)));
  EXPECT_NEAR(cone.margin(W(0, 0, fz, 0, 0, 0)), Y * fz, 1e-12);  // smallest slack: CoP rows
}

TEST(ContactWrenchCone, CornerForceWrenchesPass) {
  const double mu = 0.7, X = 0.135, Y = 0.08;
  const ContactWrenchCone cone(mu, X, Y);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0), fz(0.0, 300.0);
  for (int n = 0; n < 5000; ++n) {
    Eigen::Matrix<double, 4, 3> f;
    for (int k = 0; k < 4; ++k) {
      const double z = fz(rng);
      double a = u(rng), b = u(rng);
      if (n % 3 == 0) a = a > 0 ? 1.0 : -1.0;  // on the pyramid edge
      f.row(k) << a * mu * z, b * mu * z, z;
    }
    const auto w = cornerWrench(f, X, Y);
    EXPECT_GE(cone.margin(w), -1e-10 * w.cwiseAbs().maxCoeff()) << w.transpose();
  }
}

TEST(ContactWrenchCone, WorldMatrixIsRotatedSoleMatrix) {
  const ContactWrenchCone cone(0.7, 0.135, 0.08);
  const Eigen::Matrix3d R = rpy(0.2, -0.1, 1.3);
  const auto Cw = cone.worldMatrix(R);
  ContactWrenchCone::Wrench w_sole;
  w_sole << 30, -20, 500, 4, -6, 2;
  ContactWrenchCone::Wrench w_world;
  w_world << R * w_sole.head<3>(), R * w_sole.tail<3>();
  EXPECT_LT((Cw * w_world - cone.soleMatrix() * w_sole).norm(), 1e-10);
  EXPECT_TRUE(cone.worldMatrix(Eigen::Matrix3d::Identity()).isApprox(cone.soleMatrix()));
}

TEST(ContactConstraint, OrientationErrorAndInverseLeftJacobian) {
  Eigen::Isometry3d planned = Eigen::Isometry3d::Identity();
  planned.linear() = rpy(0.1, 0.2, -0.4);
  planned.translation() << 0.3, 0.1, 0.0;
  EXPECT_LT(ContactConstraint::error(planned, planned).norm(), 1e-15);
  // A known error: rotate the sole by 0.3 rad about world z and shift it 1 cm.
  Eigen::Isometry3d pose = planned;
  pose.linear() =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix() * planned.linear();
  pose.translation() += Eigen::Vector3d(0.01, 0, 0);
  Vector6d expected;
  expected << 0.01, 0, 0, 0, 0, 0.3;
  EXPECT_LT((ContactConstraint::error(pose, planned) - expected).norm(), 1e-12);

  // de/dt = Jl^-1(e) omega: central differences of e along R(t) = exp(t [omega]) R.
  const Eigen::Vector3d omega(0.3, -0.7, 0.5);
  for (const double angle : {1e-6, 0.2, 1.0, 2.5}) {
    Eigen::Isometry3d p0 = planned;
    p0.linear() =
        Eigen::AngleAxisd(angle, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix() *
        planned.linear();
    const Vector6d e0 = ContactConstraint::error(p0, planned);
    const double h = 1e-6;
    Eigen::Isometry3d pp = p0, pm = p0;
    pp.linear() = Eigen::AngleAxisd(h * omega.norm(), omega.normalized()) * p0.linear();
    pm.linear() = Eigen::AngleAxisd(-h * omega.norm(), omega.normalized()) * p0.linear();
    const Eigen::Vector3d fd =
        (ContactConstraint::error(pp, planned) - ContactConstraint::error(pm, planned)).tail<3>() /
        (2 * h);
    const Eigen::Vector3d an = ContactConstraint::inverseLeftJacobian(e0.tail<3>()) * omega;
    EXPECT_LT((fd - an).norm(), 1e-7) << "angle " << angle;
  }
}

TEST(ContactConstraint, RejectsBadPlannedPose) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.translation().x() = kNaN;
  EXPECT_THROW(ContactConstraint(0, p), ReachError);
  Eigen::Isometry3d s = Eigen::Isometry3d::Identity();
  s.linear() *= 2.0;
  EXPECT_THROW(ContactConstraint(0, s), ReachError);
  EXPECT_THROW(ContactConstraint(-1, Eigen::Isometry3d::Identity()), ReachError);
}

TEST(ContactConfig, YamlReadAndErrors) {
  const auto ok = YamlSection::loadString("contact: {mu: 0.5, half_length: 0.1}", "t.yaml");
  const auto c = ContactConfig::fromYaml(ok.section("contact"));
  EXPECT_EQ(c.mu, 0.5);
  EXPECT_EQ(c.half_length, 0.1);
  EXPECT_EQ(c.half_width, 0.08);  // default kept
  EXPECT_EQ(c.left_sole_frame, "l_sole");
  const auto expectError = [](const std::string& yaml, const std::string& fragment) {
    try {
      ContactConfig::fromYaml(YamlSection::loadString(yaml, "t.yaml").section("contact"));
      ADD_FAILURE() << "no error for " << yaml;
    } catch (const ReachError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expectError("contact: {mu: 0}", "mu must be in (0, 1000]");
  expectError("contact: {mu: -1}", "mu must be in (0, 1000]");
  expectError("contact: {mu: 1.0e300}", "mu must be in (0, 1000]");
  expectError("contact: {half_width: 0.0}", "half_width must be in (0, 10]");
  expectError("contact: {mu: abc}", "t.yaml: contact.mu: expected a number");
  expectError("contact: {muu: 0.5}", "contact.muu: unknown key");
  expectError("other: {}", "contact: missing section");
  EXPECT_THROW(YamlSection::loadFile("/nonexistent/x.yaml"), ReachError);
  EXPECT_THROW(YamlSection::loadString("a: [1, 2", "bad.yaml"), ReachError);
}

TEST(ContactConfig, ShippedYamlLoads) {
  const auto file =
      YamlSection::loadFile(std::string(REACH_TRAJOPT_SOURCE_DIR) + "/config/biped.yaml");
  const auto c = ContactConfig::fromYaml(file.section("contact"));
  EXPECT_EQ(c.half_length, 0.135);
  EXPECT_EQ(c.half_width, 0.08);
  EXPECT_EQ(c.left_sole_frame, "l_sole");
  EXPECT_EQ(c.right_sole_frame, "r_sole");
}

// ---- eq. (5) on the shipped biped: J_phi and the drift against central differences ----------
namespace {
std::shared_ptr<const RobotModel> biped() { return shippedBipedModel(REACH_TRAJOPT_SOURCE_DIR); }
}  // namespace

TEST(ContactConstraint, JacobianAndDriftMatchFiniteDifferences) {
  const RobotModel& m = *biped();
  const int n = m.nq();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd q = m.neutralConfiguration(), qd(n), qdd(n);
  for (int i = 0; i < n; ++i) {
    q[i] += 0.2 * u(rng);
    qd[i] = u(rng);
    qdd[i] = u(rng);
  }
  Workspace ws(m);
  m.update(ws, q, qd);
  const FrameId sole = m.frameId("l_sole");
  // A planned pose away from the current one (phi != 0) for J_phi; at it (phi = 0) for drift.
  Eigen::Isometry3d off = m.framePose(ws, sole);
  off.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, -1, 2).normalized()) * off.linear();
  off.translation() += Eigen::Vector3d(0.05, -0.02, 0.01);
  const ContactConstraint c_off(m, "l_sole", off);
  const ContactConstraint c_at(sole, m.framePose(ws, sole));
  ContactConstraintTerms t(n);
  c_off.evaluate(m, ws, t);
  EXPECT_GT(t.phi.norm(), 0.1);
  const double h = 1e-6;
  Workspace wp(m), wm(m);
  // J_phi qd = d/dt phi(q + t qd).
  m.update(wp, q + h * qd, qd);
  m.update(wm, q - h * qd, qd);
  const Vector6d fd_phidot = (c_off.phi(m, wp) - c_off.phi(m, wm)) / (2 * h);
  EXPECT_LT((fd_phidot - t.phidot).norm(), 1e-6 * (1 + t.phidot.norm()));
  EXPECT_LT((t.J_phi * qd - t.phidot).norm(), 1e-12 * (1 + t.phidot.norm()));
  // phiddot = d/dt phidot along (q + t qd + t^2/2 qdd, qd + t qdd), exact at phi = 0.
  ContactConstraintTerms t0(n), tp(n), tm(n);
  c_at.evaluate(m, ws, t0);
  EXPECT_LT(t0.phi.norm(), 1e-12);
  m.update(wp, q + h * qd + 0.5 * h * h * qdd, qd + h * qdd);
  m.update(wm, q - h * qd + 0.5 * h * h * qdd, qd - h * qdd);
  c_at.evaluate(m, wp, tp);
  c_at.evaluate(m, wm, tm);
  const Vector6d fd_phiddot = (tp.phidot - tm.phidot) / (2 * h);
  EXPECT_LT((fd_phiddot - t0.phiddot(qdd)).norm(), 1e-5 * (1 + fd_phiddot.norm()))
      << fd_phiddot.transpose() << "\n"
      << t0.phiddot(qdd).transpose();
  EXPECT_THROW(ContactConstraint(m, "no_such_frame", off), ReachError);
}
