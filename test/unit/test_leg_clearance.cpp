// The legs' clearance (model/leg_clearance.h) against independent oracles:
//  - the closest points of two segments against a dense grid search over (s, t);
//  - each capsule contains its primitive (the box's corners, the cylinder's rims, the sphere);
//  - the capsules' distance is a lower bound of the URDF shapes' exact distance, computed by
//    Bullet's GJK on the primitives themselves (box, cylinder, sphere), at random biped
//    configurations, and not a loose one (within the capsules' radii of it, and nearly exact
//    where the cylinders' sides are closest);
//  - the gradient in q against central differences;
//  - separatedBy(margin), decided link pair by link pair, answers closest().distance >= margin
//    (every capsule pair) at random configurations, margins either side of the distance, on
//    the biped and on a variant whose foot and thigh links carry several shapes;
//  - the legs are found from the sole frames (every shape of l_* below the left hip, none of
//    the pelvis or torso), and bad sole frames are refused with their name.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>

#include "reach_trajopt/model/leg_clearance.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/testing/exact_leg_distance.h"

using namespace reach_trajopt;

namespace {

const std::string kUrdf = std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf";

double gridDistance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                    const Eigen::Vector3d& q1) {
  const int n = 400;
  double best = HUGE_VAL;
  for (int i = 0; i <= n; ++i) {
    const Eigen::Vector3d p = p0 + (p1 - p0) * (double(i) / n);
    for (int j = 0; j <= n; ++j)
      best = std::min(best, (p - q0 - (q1 - q0) * (double(j) / n)).norm());
  }
  return best;
}

double pointToSegment(const Eigen::Vector3d& x, const Eigen::Vector3d& a,
                      const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double t =
      d.squaredNorm() > 0 ? std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  return (x - a - t * d).norm();
}

Eigen::VectorXd randomConfiguration(const RobotModel& m, std::mt19937& rng) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(m.nq());
  for (int i = 6; i < m.nq(); ++i) {
    std::uniform_real_distribution<double> u(m.joints()[i].q_min, m.joints()[i].q_max);
    q[i] = u(rng);
  }
  q[2] = 1.0;
  return q;
}

}  // namespace

TEST(LegClearance, SegmentClosestPointsMatchAGridSearch) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto rnd = [&] { return Eigen::Vector3d(u(rng), u(rng), u(rng)); };
  for (int k = 0; k < 40; ++k) {
    Eigen::Vector3d p0 = rnd(), p1 = rnd(), q0 = rnd(), q1 = rnd();
    if (k % 5 == 1) q1 = q0 + 0.7 * (p1 - p0);  // parallel
    if (k % 5 == 2) p1 = p0;                    // a point and a segment
    if (k % 5 == 3) q1 = q0;
    Eigen::Vector3d a, b;
    const double d = closestPointsOfSegments(p0, p1, q0, q1, a, b);
    const double grid = gridDistance(p0, p1, q0, q1);
    EXPECT_LE(d, grid + 1e-12) << "case " << k;
    EXPECT_NEAR(d, grid, 2e-4) << "case " << k;
    EXPECT_NEAR((a - b).norm(), d, 1e-12);
    EXPECT_LE(pointToSegment(a, p0, p1), 1e-12);  // the points lie on their segments
    EXPECT_LE(pointToSegment(b, q0, q1), 1e-12);
  }
}

TEST(LegClearance, CapsulesContainTheirPrimitives) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> size(0.02, 0.4), angle(-3.0, 3.0);
  for (int k = 0; k < 30; ++k) {
    CollisionShape s;
    s.type = static_cast<CollisionShape::Type>(k % 3);
    s.size = Eigen::Vector3d(size(rng), size(rng), size(rng));
    s.pose = Eigen::Translation3d(0.1, -0.2, 0.3) *
             Eigen::AngleAxisd(angle(rng), Eigen::Vector3d(1, 2, 3).normalized());
    std::vector<Eigen::Vector3d> points;  // in the shape's frame: a grid over its surface
    if (s.type == CollisionShape::Type::kBox) {
      const int g = 24;
      for (int a = 0; a <= g; ++a)
        for (int b = 0; b <= g; ++b)
          for (int f = 0; f < 6; ++f) {
            Eigen::Vector3d p;
            p[f / 2] = f % 2 ? 0.5 : -0.5;
            p[(f / 2 + 1) % 3] = a / double(g) - 0.5;
            p[(f / 2 + 2) % 3] = b / double(g) - 0.5;
            points.push_back(s.size.cwiseProduct(p));
          }
    } else {
      const double r = s.size.x();
      const double half = s.type == CollisionShape::Type::kCylinder ? s.size.y() / 2 : 0;
      for (int a = 0; a < 36; ++a)
        for (double z : {-half, half})
          points.push_back(Eigen::Vector3d(r * std::cos(a * 0.1745), r * std::sin(a * 0.1745), z));
    }
    const std::vector<LinkCapsule> caps = boundingCapsules(s);
    ASSERT_FALSE(caps.empty());
    double worst = -HUGE_VAL;  // largest distance of a surface point outside every capsule
    for (const Eigen::Vector3d& p : points) {
      double inside = HUGE_VAL;
      for (const LinkCapsule& c : caps)
        inside = std::min(inside, pointToSegment(s.pose * p, c.a, c.b) - c.radius);
      worst = std::max(worst, inside);
    }
    EXPECT_LE(worst, 1e-12) << "shape " << k;
    EXPECT_GE(worst, -1e-9) << "shape " << k << ": some extreme point touches the capsules";
  }
}

TEST(LegClearance, FindsTheLegsOfTheBiped) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  const LegClearance legs(*model, "l_sole", "r_sole");
  ASSERT_FALSE(legs.empty());
  for (Side side : {Side::kLeft, Side::kRight}) {
    const char prefix = side == Side::kLeft ? 'l' : 'r';
    ASSERT_EQ(legs.capsules(side).size(), 6u);  // thigh, shank, foot (4 across its width)
    for (const LinkCapsule& c : legs.capsules(side)) EXPECT_EQ(c.link[0], prefix) << c.link;
  }
  try {
    LegClearance(*model, "l_sole", "no_such_sole");
    FAIL() << "an unknown frame was accepted";
  } catch (const ReachError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_sole"), std::string::npos);
  }
  EXPECT_THROW(LegClearance(*model, "l_sole", "l_foot"), ReachError);  // one chain
}

TEST(LegClearance, IsATightLowerBoundOfTheShapesDistanceByGjk) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  const LegClearance legs(*model, "l_sole", "r_sole");
  const ExactLegDistance exact_distance(*model, "l_sole", "r_sole");
  ASSERT_EQ(exact_distance.shapeCount(Side::kLeft), 3);
  ASSERT_EQ(exact_distance.shapeCount(Side::kRight), 3);
  Workspace ws(*model);
  std::mt19937 rng(11);
  int compared = 0;
  double closest_gap = HUGE_VAL;  // smallest exact - capsule distance seen
  for (int k = 0; k < 400; ++k) {
    const Eigen::VectorXd q = randomConfiguration(*model, rng);
    model->update(ws, q, Eigen::VectorXd::Zero(model->nq()));
    const double exact = exact_distance(*model, ws);
    const double capsules = legs.closest(*model, ws).distance;
    if (!(exact > 1e-3)) continue;  // touching shapes: GJK's distance is a depth, not compared
    ++compared;
    EXPECT_LE(capsules, exact + 1e-6) << "configuration " << k;
    // A capsule overhangs its shape by at most its radius: the thighs', 0.06 m each.
    EXPECT_GE(capsules, exact - 0.121) << "configuration " << k << ": looser than the overhang";
    closest_gap = std::min(closest_gap, exact - capsules);
  }
  EXPECT_GT(compared, 100);
  EXPECT_LT(closest_gap, 0.01);  // where the cylinders' sides are closest, nearly exact
}

TEST(LegClearance, GradientMatchesCentralDifferences) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  const LegClearance legs(*model, "l_sole", "r_sole");
  Workspace ws(*model);
  std::mt19937 rng(5);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model->nq());
  Eigen::RowVectorXd g(model->nq());
  int checked = 0;
  for (int k = 0; k < 40; ++k) {
    Eigen::VectorXd q = randomConfiguration(*model, rng);
    q.segment<3>(3) = Eigen::Vector3d(0.3, -0.2, 0.1);  // a rotated base too
    model->update(ws, q, zero);
    const LegClearance::Closest c = legs.closest(*model, ws);
    legs.gradient(*model, ws, c, g);
    const double h = 1e-6;
    bool same_pair = true;
    Eigen::RowVectorXd fd(model->nq());
    for (int i = 0; i < model->nq() && same_pair; ++i) {
      Eigen::VectorXd qp = q, qm = q;
      qp[i] += h;
      qm[i] -= h;
      model->update(ws, qp, zero);
      const LegClearance::Closest cp = legs.closest(*model, ws);
      model->update(ws, qm, zero);
      const LegClearance::Closest cm = legs.closest(*model, ws);
      same_pair =
          cp.left == c.left && cp.right == c.right && cm.left == c.left && cm.right == c.right;
      fd[i] = (cp.distance - cm.distance) / (2 * h);
    }
    if (!same_pair) continue;
    ++checked;
    EXPECT_LE((g - fd).cwiseAbs().maxCoeff(), 1e-6 * std::max(1.0, fd.norm())) << "case " << k;
  }
  EXPECT_GT(checked, 20);
}

TEST(LegClearance, DistanceAtMatchesAGridSearchOverTheCapsulePairs) {
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  const LegClearance legs(*model, "l_sole", "r_sole");
  Workspace ws(*model);
  std::mt19937 rng(13);
  for (int k = 0; k < 10; ++k) {
    Eigen::VectorXd q = randomConfiguration(*model, rng);
    q.segment<3>(3) = Eigen::Vector3d(-0.4, 0.2, 0.1);  // a rotated base too
    const double d = legs.distanceAt(*model, q);
    // Oracle: every left/right capsule pair, its axes' distance by a grid search, less radii.
    model->update(ws, q, Eigen::VectorXd::Zero(model->nq()));
    double oracle = HUGE_VAL;
    for (const LinkCapsule& l : legs.capsules(Side::kLeft)) {
      const Eigen::Isometry3d Tl = model->framePose(ws, model->frameId(l.link));
      for (const LinkCapsule& r : legs.capsules(Side::kRight)) {
        const Eigen::Isometry3d Tr = model->framePose(ws, model->frameId(r.link));
        oracle = std::min(
            oracle, gridDistance(Tl * l.a, Tl * l.b, Tr * r.a, Tr * r.b) - l.radius - r.radius);
      }
    }
    EXPECT_LE(d, oracle + 1e-9) << "configuration " << k;  // the grid only overestimates
    EXPECT_GE(d, oracle - 2e-3) << "configuration " << k;  // by under its spacing
    EXPECT_EQ(d, legs.closest(*model, ws).distance) << "configuration " << k;  // same FK
  }
  EXPECT_THROW(legs.distanceAt(*model, Eigen::VectorXd::Zero(3)), ReachError);
  EXPECT_EQ(LegClearance().distanceAt(*model, Eigen::VectorXd::Zero(model->nq())), HUGE_VAL);
}

namespace {

/// The biped's URDF with extra primitives on the feet and thighs (several shapes per link, in
/// the file's order: the foot box, then a sphere at the toe and a cylinder under the heel).
std::string bipedWithSeveralShapesPerLink() {
  std::ifstream in(kUrdf);
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string xml = buffer.str();
  const std::string extra =
      "<collision><origin xyz=\"0.16 0.02 -0.01\"/><geometry><sphere radius=\"0.05\"/>"
      "</geometry></collision><collision><origin xyz=\"-0.1 0 -0.03\" rpy=\"1.5708 0 0\"/>"
      "<geometry><cylinder radius=\"0.03\" length=\"0.12\"/></geometry></collision>";
  for (const std::string link : {"l_foot", "r_foot", "l_thigh", "r_thigh"}) {
    const size_t at = xml.find("<link name=\"" + link + "\">");
    const size_t end = xml.find("</link>", at);
    xml.insert(end, extra);
  }
  return xml;
}

}  // namespace

TEST(LegClearance, SeparatedByAnswersTheTestOverEveryCapsulePair) {
  const auto biped = RobotModel::fromUrdfFile(kUrdf);
  const auto several = RobotModel::fromUrdfString(bipedWithSeveralShapesPerLink(), {}, "several");
  for (const auto& model : {biped, several}) {
    const LegClearance legs(*model, "l_sole", "r_sole");
    Workspace ws(*model);
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> margin_draw(-0.05, 0.3);
    int separated = 0, not_separated = 0;
    for (int k = 0; k < 600; ++k) {
      Eigen::VectorXd q = randomConfiguration(*model, rng);
      if (k % 2) q.segment<3>(3) = Eigen::Vector3d(0.3, -0.2, 0.5);  // a rotated base too
      model->update(ws, q, Eigen::VectorXd::Zero(model->nq()));
      // Oracle: the smallest distance over every left/right capsule pair (their axes' closest
      // points, less the radii).
      double oracle = HUGE_VAL;
      Eigen::Vector3d p, r;
      for (const LinkCapsule& l : legs.capsules(Side::kLeft)) {
        const Eigen::Isometry3d Tl = model->framePose(ws, model->frameId(l.link));
        for (const LinkCapsule& c : legs.capsules(Side::kRight)) {
          const Eigen::Isometry3d Tr = model->framePose(ws, model->frameId(c.link));
          oracle = std::min(oracle,
                            closestPointsOfSegments(Tl * l.a, Tl * l.b, Tr * c.a, Tr * c.b, p, r) -
                                l.radius - c.radius);
        }
      }
      for (const double margin : {oracle - 1e-4, oracle + 1e-4, margin_draw(rng)}) {
        const bool expected = oracle >= margin;
        EXPECT_EQ(legs.separatedBy(*model, ws, margin), expected)
            << model->source() << " configuration " << k << ": distance " << oracle << ", margin "
            << margin;
        (expected ? separated : not_separated) += 1;
      }
    }
    EXPECT_GT(separated, 600);  // both answers asked for
    EXPECT_GT(not_separated, 600);
  }
  EXPECT_EQ(LegClearance(*several, "l_sole", "r_sole").capsules(Side::kLeft).size(), 10u);
}

TEST(LegClearance, AccelerationDriftIsTheClosestPointsAccelerationAlongTheNormal) {
  // Oracles, along q(t) = q + t qd + t^2 / 2 qdd (coordinates are positions = velocities):
  //  - the two closest points, held fixed on their links: the second difference of their gap
  //    vector, along the normal, is gradient qdd + accelerationDrift;
  //  - when only the base translates, the legs' distance (a minimum over the points, convex in
  //    the translation) has a second difference at least that.
  const auto model = RobotModel::fromUrdfFile(kUrdf);
  const LegClearance legs(*model, "l_sole", "r_sole");
  Workspace ws(*model);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = model->nq();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  int checked = 0;
  for (int k = 0; k < 80; ++k) {
    Eigen::VectorXd q = randomConfiguration(*model, rng);
    q.segment<3>(3) = Eigen::Vector3d(0.2, 0.1, -0.3);
    const bool translation_only = k % 2 == 1;
    Eigen::VectorXd qd = zero, qdd = zero;
    for (int i = 0; i < (translation_only ? 3 : n); ++i) {
      qd[i] = 2.0 * u(rng);
      qdd[i] = 5.0 * u(rng);
    }
    model->update(ws, q, qd);
    const LegClearance::Closest c = legs.closest(*model, ws);
    const Eigen::Vector3d normal = (c.left_point - c.right_point).normalized();
    Eigen::RowVectorXd g(n);
    legs.gradient(*model, ws, c, g);
    const double predicted = g.dot(qdd) + legs.accelerationDrift(*model, ws, c);
    const FrameId fl = legs.capsules(Side::kLeft)[c.left].frame;
    const FrameId fr = legs.capsules(Side::kRight)[c.right].frame;
    const Eigen::Vector3d pl = model->framePose(ws, fl).inverse() * c.left_point;
    const Eigen::Vector3d pr = model->framePose(ws, fr).inverse() * c.right_point;
    const double h = 1e-4;
    Eigen::Vector3d gap[3];
    double minimum[3];
    for (int j = 0; j < 3; ++j) {
      const double t = (j - 1) * h;
      model->update(ws, q + t * qd + 0.5 * t * t * qdd, zero);
      gap[j] = model->framePose(ws, fl) * pl - model->framePose(ws, fr) * pr;
      minimum[j] = legs.closest(*model, ws).distance;
    }
    const double along_normal = normal.dot(gap[0] - 2 * gap[1] + gap[2]) / (h * h);
    const double minimum_dd = (minimum[0] - 2 * minimum[1] + minimum[2]) / (h * h);
    if (!((c.left_point - c.right_point).norm() > 0.02)) continue;  // axes nearly crossing
    ++checked;
    const double tol = 1e-3 * std::max(1.0, std::abs(along_normal));
    EXPECT_NEAR(predicted, along_normal, tol) << "case " << k;
    if (translation_only) EXPECT_GE(minimum_dd, predicted - 0.05) << "case " << k;
  }
  EXPECT_GT(checked, 40);
}
