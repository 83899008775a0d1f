/// \file exact_leg_distance.cpp
/// The legs' primitives in Bullet and their GJK distance (see the header).

#include "reach_trajopt/testing/exact_leg_distance.h"

#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#include <btBulletCollisionCommon.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

namespace {

std::unique_ptr<btConvexShape> bulletShape(const CollisionShape& s) {
  switch (s.type) {
    case CollisionShape::Type::kBox:
      return std::make_unique<btBoxShape>(btVector3(s.size.x(), s.size.y(), s.size.z()) * 0.5);
    case CollisionShape::Type::kSphere:
      return std::make_unique<btSphereShape>(s.size.x());
    case CollisionShape::Type::kCylinder:
      return std::make_unique<btCylinderShapeZ>(btVector3(s.size.x(), s.size.x(), s.size.y() / 2));
  }
  return nullptr;
}

btTransform toBullet(const Eigen::Isometry3d& T) {
  btMatrix3x3 R;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R[r][c] = T.linear()(r, c);
  return btTransform(R, btVector3(T.translation().x(), T.translation().y(), T.translation().z()));
}

std::vector<std::string> chainToRoot(const RobotModel& model, const std::string& link) {
  std::vector<std::string> chain;
  for (std::string l = link; !l.empty(); l = model.parentLink(l)) chain.push_back(l);
  return chain;
}

}  // namespace

struct ExactLegDistance::Shapes {
  struct Entry {
    FrameId frame;
    Eigen::Isometry3d pose;  // in the link frame
    std::unique_ptr<btConvexShape> shape;
  };
  std::vector<Entry> leg[2];
};

ExactLegDistance::ExactLegDistance(const RobotModel& model, const std::string& left_sole_frame,
                                   const std::string& right_sole_frame)
    : shapes_(std::make_unique<Shapes>()) {
  const std::string soles[2] = {left_sole_frame, right_sole_frame};
  std::set<std::string> chain[2];
  for (int s = 0; s < 2; ++s) {
    if (!model.hasFrame(soles[s]))
      throw ReachError("ExactLegDistance: unknown sole frame '" + soles[s] + "'");
    for (const std::string& l : chainToRoot(model, soles[s])) chain[s].insert(l);
  }
  for (const CollisionShape& shape : model.collisionShapes()) {
    // Walk up from the shape's link: the first link on exactly one sole's chain names its leg.
    for (const std::string& l : chainToRoot(model, shape.link)) {
      const bool on_left = chain[0].count(l) > 0, on_right = chain[1].count(l) > 0;
      if (on_left == on_right) {
        if (on_left) break;  // reached the shared part (pelvis): not a leg
        continue;
      }
      shapes_->leg[on_left ? 0 : 1].push_back(
          {model.frameId(shape.link), shape.pose, bulletShape(shape)});
      break;
    }
  }
}

ExactLegDistance::~ExactLegDistance() = default;
ExactLegDistance::ExactLegDistance(ExactLegDistance&&) noexcept = default;

int ExactLegDistance::shapeCount(Side side) const {
  return static_cast<int>(shapes_->leg[side == Side::kLeft ? 0 : 1].size());
}

double ExactLegDistance::operator()(const RobotModel& model, const Workspace& ws) const {
  double best = HUGE_VAL;
  btVoronoiSimplexSolver simplex;
  btGjkEpaPenetrationDepthSolver epa;
  for (const Shapes::Entry& l : shapes_->leg[0]) {
    const btTransform Tl = toBullet(model.framePose(ws, l.frame) * l.pose);
    for (const Shapes::Entry& r : shapes_->leg[1]) {
      btGjkPairDetector gjk(l.shape.get(), r.shape.get(), &simplex, &epa);
      btGjkPairDetector::ClosestPointInput in;
      in.m_transformA = Tl;
      in.m_transformB = toBullet(model.framePose(ws, r.frame) * r.pose);
      btPointCollector out;
      gjk.getClosestPoints(in, out, nullptr);
      const double d = out.m_hasResult ? std::max(0.0, double(out.m_distance)) : 0.0;
      best = std::min(best, d);
    }
  }
  return best;
}

}  // namespace reach_trajopt
