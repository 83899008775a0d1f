/// \file leg_clearance.cpp
/// The legs' capsules and their distance (see the header).

#include "reach_trajopt/model/leg_clearance.h"

#include <algorithm>
#include <cmath>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

namespace {

/// The links from the root down to `link`, root first.
std::vector<std::string> pathFromRoot(const RobotModel& model, const std::string& link) {
  std::vector<std::string> path;
  for (std::string l = link; !l.empty(); l = model.parentLink(l)) path.push_back(l);
  std::reverse(path.begin(), path.end());
  return path;
}

/// True when `ancestor` is `link` or above it.
bool isBelow(const RobotModel& model, const std::string& link, const std::string& ancestor) {
  for (std::string l = link; !l.empty(); l = model.parentLink(l))
    if (l == ancestor) return true;
  return false;
}

double clamp01(double x) { return std::min(1.0, std::max(0.0, x)); }

}  // namespace

std::vector<LinkCapsule> boundingCapsules(const CollisionShape& shape) {
  // Each capsule: centre, half axis and radius in the shape's frame.
  struct Local {
    Eigen::Vector3d centre, half_axis;
    double radius;
  };
  std::vector<Local> local;
  switch (shape.type) {
    case CollisionShape::Type::kSphere:
      local.push_back({Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), shape.size[0]});
      break;
    case CollisionShape::Type::kCylinder:
      local.push_back(
          {Eigen::Vector3d::Zero(), 0.5 * shape.size[1] * Eigen::Vector3d::UnitZ(), shape.size[0]});
      break;
    case CollisionShape::Type::kBox: {
      int k = 0, j = 0;  // the longest and the shortest axes; i the middle one
      shape.size.maxCoeff(&k);
      shape.size.minCoeff(&j);
      if (j == k) j = (k + 1) % 3;
      const int i = 3 - k - j;
      const double L = shape.size[k], W = shape.size[i], H = shape.size[j];
      const int n = std::clamp(static_cast<int>(std::lround(H > 0.0 ? W / H : 8.0)), 1, 8);
      const double width = W / n;
      for (int m = 0; m < n; ++m) {
        Eigen::Vector3d centre = Eigen::Vector3d::Zero();
        centre[i] = -0.5 * W + (m + 0.5) * width;
        Eigen::Vector3d half_axis = Eigen::Vector3d::Zero();
        half_axis[k] = 0.5 * L;
        local.push_back({centre, half_axis, 0.5 * std::hypot(width, H)});
      }
      break;
    }
  }
  std::vector<LinkCapsule> out;
  for (const Local& l : local) {
    LinkCapsule c;
    c.link = shape.link;
    c.a = shape.pose * (l.centre - l.half_axis);
    c.b = shape.pose * (l.centre + l.half_axis);
    c.radius = l.radius;
    out.push_back(c);
  }
  return out;
}

double closestPointsOfSegments(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                               const Eigen::Vector3d& q0, const Eigen::Vector3d& q1,
                               Eigen::Vector3d& on_p, Eigen::Vector3d& on_q) {
  constexpr double kTiny = 1e-18;  // squared length below which a segment is a point [m^2]
  const Eigen::Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  if (a <= kTiny && e <= kTiny) {
    s = t = 0.0;
  } else if (a <= kTiny) {
    t = clamp01(f / e);
  } else {
    const double c = d1.dot(r);
    if (e <= kTiny) {
      s = clamp01(-c / a);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;  // >= 0
      s = denom > kTiny * std::max(1.0, a * e) ? clamp01((b * f - c * e) / denom) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = clamp01(-c / a);
      } else if (t > 1.0) {
        t = 1.0;
        s = clamp01((b - c) / a);
      }
    }
  }
  on_p = p0 + s * d1;
  on_q = q0 + t * d2;
  return (on_p - on_q).norm();
}

LegClearance::LegClearance(const RobotModel& model, const std::string& left_sole_frame,
                           const std::string& right_sole_frame) {
  for (const std::string* f : {&left_sole_frame, &right_sole_frame})
    if (!model.hasFrame(*f))
      throw ReachError("leg clearance: unknown sole frame '" + *f + "' in " + model.source());
  const std::vector<std::string> left_path = pathFromRoot(model, left_sole_frame);
  const std::vector<std::string> right_path = pathFromRoot(model, right_sole_frame);
  size_t shared = 0;
  while (shared < left_path.size() && shared < right_path.size() &&
         left_path[shared] == right_path[shared])
    ++shared;
  if (shared >= left_path.size() || shared >= right_path.size())
    throw ReachError("leg clearance: the sole frames '" + left_sole_frame + "' and '" +
                     right_sole_frame + "' are on one chain of " + model.source() +
                     " (no two legs)");
  const std::string& left_top = left_path[shared];
  const std::string& right_top = right_path[shared];
  for (const CollisionShape& shape : model.collisionShapes()) {
    std::vector<LinkCapsule>* leg = isBelow(model, shape.link, left_top)    ? &left_
                                    : isBelow(model, shape.link, right_top) ? &right_
                                                                            : nullptr;
    if (!leg) continue;
    for (LinkCapsule& c : boundingCapsules(shape)) {
      c.frame = model.frameId(shape.link);
      leg->push_back(c);
    }
  }
  left_links_ = groupByLink(left_);
  right_links_ = groupByLink(right_);
}

std::vector<LegClearance::LinkGroup> LegClearance::groupByLink(
    const std::vector<LinkCapsule>& capsules) {
  std::vector<LinkGroup> groups;
  for (int i = 0; i < static_cast<int>(capsules.size());) {
    LinkGroup g;
    g.frame = capsules[i].frame;
    g.first = i;
    while (i < static_cast<int>(capsules.size()) && capsules[i].frame == g.frame) ++i;
    g.count = i - g.first;
    // The enclosing capsule's axis: the mean of its capsules' axes (a box's centre line).
    for (int k = g.first; k < i; ++k) {
      g.a += capsules[k].a / g.count;
      g.b += capsules[k].b / g.count;
    }
    // Its radius: the distance to the axis, a convex function, is largest over a capsule at one
    // of its ends, plus that capsule's radius.
    Eigen::Vector3d on_axis, on_end;
    for (int k = g.first; k < i; ++k)
      for (const Eigen::Vector3d* end : {&capsules[k].a, &capsules[k].b})
        g.radius =
            std::max(g.radius, closestPointsOfSegments(g.a, g.b, *end, *end, on_axis, on_end) +
                                   capsules[k].radius);
    groups.push_back(g);
  }
  return groups;
}

template <typename Visit>
void LegClearance::forEachPair(const RobotModel& model, const Workspace& ws, Visit&& visit) const {
  // The right capsules' end points in world, per thread (grown once, reused across calls).
  thread_local std::vector<Eigen::Vector3d> ra, rb;
  if (ra.size() < right_.size()) {
    ra.resize(right_.size());
    rb.resize(right_.size());
  }
  for (size_t j = 0; j < right_.size(); ++j) {
    const Eigen::Isometry3d T = model.framePose(ws, right_[j].frame);
    ra[j] = T * right_[j].a;
    rb[j] = T * right_[j].b;
  }
  Closest pair;
  for (size_t i = 0; i < left_.size(); ++i) {
    const Eigen::Isometry3d T = model.framePose(ws, left_[i].frame);
    const Eigen::Vector3d la = T * left_[i].a, lb = T * left_[i].b;
    for (size_t j = 0; j < right_.size(); ++j) {
      pair.distance =
          closestPointsOfSegments(la, lb, ra[j], rb[j], pair.left_point, pair.right_point) -
          left_[i].radius - right_[j].radius;
      pair.left = static_cast<int>(i);
      pair.right = static_cast<int>(j);
      visit(pair);
    }
  }
}

bool LegClearance::separatedBy(const RobotModel& model, const Workspace& ws, double margin) const {
  // Per thread, grown once: the right links' poses and enclosing axes in world; a link's
  // capsules' end points in world only when a pair of links needs them.
  thread_local std::vector<Eigen::Isometry3d> right_pose;
  thread_local std::vector<Eigen::Vector3d> rga, rgb, ra, rb, la, lb;
  thread_local std::vector<char> right_ready;
  const size_t n_right = right_links_.size();
  right_pose.resize(n_right);
  rga.resize(n_right);
  rgb.resize(n_right);
  right_ready.assign(n_right, 0);
  ra.resize(right_.size());
  rb.resize(right_.size());
  la.resize(left_.size());
  lb.resize(left_.size());
  for (size_t g = 0; g < n_right; ++g) {
    const LinkGroup& r = right_links_[g];
    right_pose[g] = model.framePose(ws, r.frame);
    rga[g] = right_pose[g] * r.a;
    rgb[g] = right_pose[g] * r.b;
  }
  Eigen::Vector3d on_l, on_r;
  for (const LinkGroup& l : left_links_) {
    const Eigen::Isometry3d Tl = model.framePose(ws, l.frame);
    const Eigen::Vector3d lga = Tl * l.a, lgb = Tl * l.b;
    bool left_ready = false;
    for (size_t g = 0; g < n_right; ++g) {
      const LinkGroup& r = right_links_[g];
      if (closestPointsOfSegments(lga, lgb, rga[g], rgb[g], on_l, on_r) - l.radius - r.radius >=
          margin)
        continue;  // every capsule pair of these two links is at least this far apart
      if (!left_ready) {
        for (int i = l.first; i < l.first + l.count; ++i) {
          la[i] = Tl * left_[i].a;
          lb[i] = Tl * left_[i].b;
        }
        left_ready = true;
      }
      if (!right_ready[g]) {
        for (int j = r.first; j < r.first + r.count; ++j) {
          ra[j] = right_pose[g] * right_[j].a;
          rb[j] = right_pose[g] * right_[j].b;
        }
        right_ready[g] = 1;
      }
      for (int i = l.first; i < l.first + l.count; ++i)
        for (int j = r.first; j < r.first + r.count; ++j)
          if (closestPointsOfSegments(la[i], lb[i], ra[j], rb[j], on_l, on_r) - left_[i].radius -
                  right_[j].radius <
              margin)
            return false;
    }
  }
  return true;
}

LegClearance::Closest LegClearance::closest(const RobotModel& model, const Workspace& ws) const {
  Closest best;
  forEachPair(model, ws, [&](const Closest& pair) {
    if (pair.distance < best.distance) best = pair;
  });
  return best;
}

void LegClearance::pairsWithin(const RobotModel& model, const Workspace& ws, double max_distance,
                               std::vector<Closest>& pairs) const {
  pairs.clear();
  forEachPair(model, ws, [&](const Closest& pair) {
    if (pair.distance < max_distance) pairs.push_back(pair);
  });
}

double LegClearance::distanceAt(const RobotModel& model,
                                const Eigen::Ref<const Eigen::VectorXd>& q) const {
  if (empty()) return std::numeric_limits<double>::infinity();
  requireSize("LegClearance::distanceAt q", q.size(), model.nq());
  Workspace ws(model);
  model.update(ws, q, Eigen::VectorXd::Zero(model.nq()));
  return closest(model, ws).distance;
}

namespace {

/// A capsule frame's kinematics at the model's last update(): what a pair's terms need.
struct FrameTerms {
  FrameId frame = -1;
  Matrix6Xd J;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d w = Eigen::Vector3d::Zero();  ///< angular velocity [rad/s]
  Vector6d jdot_qd = Vector6d::Zero();
};

void computeFrameTerms(const RobotModel& model, const Workspace& ws, FrameId frame, FrameTerms& f,
                       bool jacobian = true, bool velocity = true) {
  f.frame = frame;
  f.origin = model.framePose(ws, frame).translation();
  if (jacobian) {  // gradient()
    f.J.resize(6, model.nq());
    model.frameJacobian(ws, frame, f.J);
  }
  if (velocity) {  // accelerationDrift()
    f.w = model.frameVelocity(ws, frame).tail<3>();
    f.jdot_qd = model.frameJdotQd(ws, frame);
  }
}

/// The unit normal from the right closest point to the left one; false when the axes meet.
bool pairNormal(const LegClearance::Closest& c, Eigen::Vector3d& n) {
  if (c.left < 0 || c.right < 0) return false;
  const Eigen::Vector3d gap = c.left_point - c.right_point;
  const double norm = gap.norm();
  if (!(norm > 1e-12)) return false;
  n = gap / norm;
  return true;
}

/// Point Jacobian of p on a frame at o: J_lin - [p - o]x J_ang, so n^T of it is
/// n^T J_lin + ((p - o) x n)^T J_ang; added to `grad` with `sign`.
template <typename Row>
void addPointRow(const FrameTerms& f, const Eigen::Vector3d& p, const Eigen::Vector3d& n,
                 double sign, Row&& grad) {
  grad.noalias() += sign * n.transpose() * f.J.topRows<3>();
  grad.noalias() += sign * (p - f.origin).cross(n).transpose() * f.J.bottomRows<3>();
}

/// A point p fixed on the frame, r = p - o: its acceleration's drift is
/// (Jdot qd)_lin + (Jdot qd)_ang x r + w x (w x r).
Eigen::Vector3d pointDrift(const FrameTerms& f, const Eigen::Vector3d& p) {
  const Eigen::Vector3d r = p - f.origin;
  return f.jdot_qd.head<3>() + f.jdot_qd.tail<3>().cross(r) + f.w.cross(f.w.cross(r));
}

}  // namespace

void LegClearance::gradient(const RobotModel& model, const Workspace& ws, const Closest& c,
                            Eigen::Ref<Eigen::RowVectorXd> grad) const {
  requireSize("LegClearance::gradient", grad.size(), model.nq());
  grad.setZero();
  Eigen::Vector3d n;
  if (!pairNormal(c, n)) return;
  thread_local FrameTerms left, right;
  computeFrameTerms(model, ws, left_[c.left].frame, left, true, false);
  computeFrameTerms(model, ws, right_[c.right].frame, right, true, false);
  addPointRow(left, c.left_point, n, 1.0, grad);
  addPointRow(right, c.right_point, n, -1.0, grad);
}

double LegClearance::accelerationDrift(const RobotModel& model, const Workspace& ws,
                                       const Closest& c) const {
  Eigen::Vector3d n;
  if (!pairNormal(c, n)) return 0.0;
  thread_local FrameTerms left, right;
  computeFrameTerms(model, ws, left_[c.left].frame, left, false, true);
  computeFrameTerms(model, ws, right_[c.right].frame, right, false, true);
  return n.dot(pointDrift(left, c.left_point) - pointDrift(right, c.right_point));
}

void LegClearance::pairTerms(const RobotModel& model, const Workspace& ws,
                             const std::vector<Closest>& pairs,
                             Eigen::Ref<Eigen::MatrixXd> gradients,
                             Eigen::Ref<Eigen::VectorXd> drifts) const {
  const int count = static_cast<int>(pairs.size());
  requireSize("LegClearance::pairTerms gradients rows", gradients.rows(), count);
  requireSize("LegClearance::pairTerms gradients cols", gradients.cols(), model.nq());
  requireSize("LegClearance::pairTerms drifts", drifts.size(), count);
  // Each capsule frame's terms once, however many pairs it is in (a few frames per leg).
  // Reserved for every capsule's frame: a reference taken below stays valid while others are
  // added.
  thread_local std::vector<FrameTerms> frames;
  frames.reserve(left_.size() + right_.size());
  int used = 0;
  const auto termsOf = [&](FrameId frame) -> const FrameTerms& {
    for (int i = 0; i < used; ++i)
      if (frames[i].frame == frame) return frames[i];
    if (used == static_cast<int>(frames.size())) frames.emplace_back();
    computeFrameTerms(model, ws, frame, frames[used]);
    return frames[used++];
  };
  gradients.setZero();
  for (int k = 0; k < count; ++k) {
    const Closest& c = pairs[k];
    Eigen::Vector3d n;
    drifts[k] = 0.0;
    if (!pairNormal(c, n)) continue;
    const FrameTerms& left = termsOf(left_[c.left].frame);
    const FrameTerms& right = termsOf(right_[c.right].frame);
    addPointRow(left, c.left_point, n, 1.0, gradients.row(k));
    addPointRow(right, c.right_point, n, -1.0, gradients.row(k));
    drifts[k] = n.dot(pointDrift(left, c.left_point) - pointDrift(right, c.right_point));
  }
}

}  // namespace reach_trajopt
